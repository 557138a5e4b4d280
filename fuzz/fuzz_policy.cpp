// Policy tables: the bytes are resealed first (file size field and trailing FNV-1a checksum
// recomputed, as anyone can), so the fuzzer explores the structure behind the checksum, which
// is where an offset past the node count once read past the heap buffer. A table that decodes
// is then used as the advisor and the inspector use it (interpolation at every stage, CSV).
#include <algorithm>
#include <ostream>
#include <streambuf>
#include <string>

#include "data/line.hpp"
#include "fuzz_support.hpp"
#include "policy/policy_table.hpp"

using namespace ecorail;

namespace {
struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string b(fuzz::as_text(data, size));
  if (b.size() >= 28) {
    const std::uint64_t n = b.size();
    for (int k = 0; k < 8; ++k) b[12 + k] = static_cast<char>(n >> (8 * k));
    const std::uint64_t sum = data::fnv1a64(std::string_view(b).substr(0, b.size() - 8));
    for (int k = 0; k < 8; ++k) b[b.size() - 8 + k] = static_cast<char>(sum >> (8 * k));
  }
  policy::PolicyTable t;
  try {
    t = policy::decode_policy(b, "table.bin");
  } catch (const policy::PolicyFormatError&) {
    return 0;
  }
  const int stages = std::min(t.stage_count(), 64);
  for (int layer = 0; layer < static_cast<int>(t.layers.size()); ++layer) {
    for (int i = 0; i < stages; ++i) {
      const double s = t.position_m[i];
      t.cost_to_go_J(layer, s, 0.0);
      t.cost_to_go_J(layer, s + 0.5, 10.0);
    }
  }
  NullBuffer null;
  std::ostream out(&null);
  policy::write_policy_csv(out, t);
  return 0;
}
