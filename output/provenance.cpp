#include "output/provenance.hpp"

#include <cstdio>

#include "data/train_io.hpp"
#include "data/version.hpp"

namespace ecorail::output {

namespace {
std::string hex64(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}
}  // namespace

nlohmann::json program_json() {
  return {{"name", "ecorail"},
          {"version", data::version()},
          {"commit", data::commit()},
          {"build_type", data::build_type()}};
}

nlohmann::json provenance_json(const data::Line& line, const physics::Train& train,
                               const nlohmann::json& grid, const nlohmann::json& options) {
  return {{"program", program_json()},
          {"line", {{"name", line.name}, {"checksum", hex64(line.checksum())}}},
          {"train", {{"name", train.name}, {"checksum", hex64(data::train_checksum(train))}}},
          {"grid", grid},
          {"options", options}};
}

}  // namespace ecorail::output
