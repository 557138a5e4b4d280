// A policy table file is untrusted input: its FNV-1a checksum can be recomputed by
// anyone, so every header field and every offset is checked against sane ranges before use.
// Each table here carries a valid checksum; once, the first read past the heap buffer
// (stage_offset[1] beyond the node count, seen under ASan), the second allocated without end
// or cast a huge double to an integer (envelope resolution 1e-9 m or a subnormal), the third
// made `policy --inspect` run for ever (substep 1e-12 m). Also: /dev/zero and a directory are
// refused at once with a one-line PolicyFormatError.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "data/line.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "policy/policy_table.hpp"
#include "policy_test_support.hpp"

namespace ecorail {
namespace {

const std::string& good_bytes() {
  static const std::string b = [] {
    const data::Line line = data::default_line();
    const physics::Train train = data::default_train();
    const physics::Route route = data::build_route(line, "A6", "A7", train);
    dp::EngineOptions options;
    options.grid = {100.0, 10.0, 50.0};
    const dp::SectionEngine engine(train, route, options);
    policy::PolicyTable t =
        policy::make_policy_table(engine, line.name, line.checksum(), data::train_checksum(train));
    t.layers.push_back(policy::build_policy_layer(engine, 7e5));
    return policy::encode_policy(t);
  }();
  return b;
}

// Byte offset of the first grid field (ds_m), after the strings of the header.
std::size_t grid_offset(const std::string& b) {
  std::size_t pos = 8 + 4 + 8;
  auto skip_string = [&] {
    std::uint32_t n = 0;
    std::memcpy(&n, b.data() + pos, 4);
    pos += 4 + n;
  };
  skip_string();  // units
  skip_string();  // line name
  pos += 8;
  skip_string();  // train name
  pos += 8;
  skip_string();  // from
  skip_string();  // to
  pos += 8 + 1;   // route length, objective
  return pos;
}

void put_f64(std::string& b, std::size_t pos, double x) {
  std::memcpy(b.data() + pos, &x, 8);
}
void put_u32(std::string& b, std::size_t pos, std::uint32_t x) {
  std::memcpy(b.data() + pos, &x, 4);
}

// A valid checksum over the edited bytes, as anyone can compute it.
std::string reseal_checksum(std::string b) {
  const std::uint64_t sum = data::fnv1a64(std::string_view(b).substr(0, b.size() - 8));
  std::memcpy(b.data() + b.size() - 8, &sum, 8);
  return b;
}

TEST(PolicyUntrusted, TheUneditedTableDecodes) {
  EXPECT_EQ(policy::testing::decode_error_of(reseal_checksum(good_bytes())), "");
}

TEST(PolicyUntrusted, AStageOffsetBeyondTheNodeCountIsRefusedBeforeUse) {
  std::string b = good_bytes();
  const std::size_t counts = grid_offset(b) + 4 * 8;
  std::uint32_t stages = 0, nodes = 0;
  std::memcpy(&stages, b.data() + counts, 4);
  std::memcpy(&nodes, b.data() + counts + 4, 4);
  const std::size_t offsets = counts + 12 + 8 * stages;
  put_u32(b, offsets + 4, nodes + 1000);  // stage_offset[1]
  const std::string e = policy::testing::decode_error_of(reseal_checksum(b));
  EXPECT_NE(e.find("t.bin: invalid table: stage"), std::string::npos) << e;
}

TEST(PolicyUntrusted, GridFieldsOutsideSaneRangesAreRefused) {
  const struct {
    int field;  // 0 ds, 1 dv, 2 substep, 3 envelope resolution
    double value;
    const char* says;
  } cases[] = {
      {3, 1e-9, "envelope_resolution_m"},
      {3, 4.9e-324, "envelope_resolution_m"},
      {3, 1e300, "envelope_resolution_m"},
      {2, 1e-12, "substep_m"},
      {0, 1e-300, "ds_m"},
      {1, 1e-300, "dv_kmh"},
      {0, 1e300, "ds_m"},
  };
  for (const auto& c : cases) {
    std::string b = good_bytes();
    put_f64(b, grid_offset(b) + 8 * c.field, c.value);
    const std::string e = policy::testing::decode_error_of(reseal_checksum(b));
    EXPECT_NE(e.find(c.says), std::string::npos) << c.says << " = " << c.value << ": " << e;
  }
}

TEST(PolicyUntrusted, DevicesAndDirectoriesAreRefusedAtOnce) {
  for (const char* path : {"/dev/zero", "/dev/null"}) {
    try {
      policy::load_policy(path);
      ADD_FAILURE() << path << " was read as a table";
    } catch (const policy::PolicyFormatError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
  try {
    policy::load_policy(std::filesystem::temp_directory_path());
    ADD_FAILURE() << "a directory was read as a table";
  } catch (const policy::PolicyFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ecorail
