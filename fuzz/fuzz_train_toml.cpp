// Train TOML: parsed and checked, written back and read again (the writer must produce what the
// reader accepts), and its route A6 -> A7 on the reference line built (the start check).
#include <cstdlib>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const data::Line line = data::default_line();
  physics::Train train;
  try {
    train = data::parse_train_toml(std::string(fuzz::as_text(data, size)), "train.toml");
  } catch (const data::InputError&) {
    return 0;
  }
  // A train the reader accepted must survive its own writer: an error here is a bug.
  const physics::Train again = data::parse_train_toml(data::train_to_toml(train), "again.toml");
  if (data::train_to_toml(again) !=
      data::train_to_toml(data::parse_train_toml(data::train_to_toml(again), "third.toml"))) {
    std::abort();  // writing and reading is exact after the first round trip (docs/formats.md)
  }
  fuzz::refuse_cleanly([&] { data::build_route(line, "A6", "A7", train); });
  return 0;
}
