// The binary policy format: exact round trip, CSV export, and that every truncation, every
// single-bit flip, a wrong magic or version, trailing bytes and well-framed nonsense are clear
// PolicyFormatErrors, never a crash or an out-of-bounds read. Uses a coarse grid (ds 50 m,
// dv 4 km/h) on A6 -> A7 so the file is small enough to corrupt at every byte.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "data/line.hpp"
#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "policy/policy_table.hpp"
#include "policy_test_support.hpp"

namespace ecorail {
namespace {

policy::PolicyTable small_table() {
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(line, "A6", "A7", train);
  dp::EngineOptions options;
  options.grid = {50.0, 4.0, 25.0};
  const dp::SectionEngine engine(train, route, options);
  policy::PolicyTable table =
      policy::make_policy_table(engine, line.name, line.checksum(), data::train_checksum(train));
  for (double lambda : {6e5, 9e5})
    table.layers.push_back(policy::build_policy_layer(engine, lambda));
  table.layers[1].time_offset_s = -5.0;
  return table;
}

const policy::PolicyTable& table() {
  static const policy::PolicyTable t = small_table();
  return t;
}

const std::string& bytes() {
  static const std::string b = policy::encode_policy(table());
  return b;
}

// Recomputes the size field and the trailing checksum, as a buggy writer would produce them.
std::string reseal(std::string b) {
  const std::uint64_t size = b.size();
  for (int k = 0; k < 8; ++k) b[12 + k] = static_cast<char>(size >> (8 * k));
  const std::uint64_t sum = data::fnv1a64(std::string_view(b).substr(0, b.size() - 8));
  for (int k = 0; k < 8; ++k) b[b.size() - 8 + k] = static_cast<char>(sum >> (8 * k));
  return b;
}

std::string error_of(const std::string& b) {
  return policy::testing::decode_error_of(b);
}

TEST(PolicyFormat, RoundTripIsExact) {
  const policy::PolicyTable& a = table();
  const policy::PolicyTable b = policy::decode_policy(bytes());
  EXPECT_EQ(b.line_name, a.line_name);
  EXPECT_EQ(b.line_checksum, a.line_checksum);
  EXPECT_EQ(b.train_name, a.train_name);
  EXPECT_EQ(b.train_checksum, a.train_checksum);
  EXPECT_EQ(b.from, "A6");
  EXPECT_EQ(b.to, "A7");
  EXPECT_EQ(b.route_length_m, a.route_length_m);
  EXPECT_EQ(b.objective, a.objective);
  EXPECT_EQ(b.grid_spec.ds_m, 50.0);
  EXPECT_EQ(b.grid_spec.dv_kmh, 4.0);
  EXPECT_EQ(b.position_m, a.position_m);
  EXPECT_EQ(b.stage_offset, a.stage_offset);
  EXPECT_EQ(b.speed_ms, a.speed_ms);
  ASSERT_EQ(b.layers.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(b.layers[k].lambda_J_per_s, a.layers[k].lambda_J_per_s);
    EXPECT_EQ(b.layers[k].time_offset_s, a.layers[k].time_offset_s);
    EXPECT_EQ(b.layers[k].planned_time_s, a.layers[k].planned_time_s);
    EXPECT_EQ(b.layers[k].control, a.layers[k].control);
    EXPECT_EQ(b.layers[k].regime, a.layers[k].regime);
    EXPECT_EQ(b.layers[k].force_N, a.layers[k].force_N);
    EXPECT_EQ(b.layers[k].cost_to_go_J, a.layers[k].cost_to_go_J);
    EXPECT_EQ(b.layers[k].time_to_go_s, a.layers[k].time_to_go_s);
  }
  EXPECT_EQ(policy::encode_policy(b), bytes());
  EXPECT_EQ(b.nominal_layer(), 0);
  // The header starts with the magic and the version, little-endian.
  EXPECT_EQ(std::memcmp(bytes().data(), "ECRLPOL\n", 8), 0);
  EXPECT_EQ(bytes()[8], 1);
  EXPECT_EQ(bytes()[9], 0);
}

TEST(PolicyFormat, FileRoundTripAndMissingFile) {
  const auto dir = std::filesystem::temp_directory_path() / "ecorail_policy_format_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "t.bin";
  policy::save_policy(table(), path);
  EXPECT_EQ(std::filesystem::file_size(path), bytes().size());
  EXPECT_EQ(policy::encode_policy(policy::load_policy(path)), bytes());
  EXPECT_THROW(policy::load_policy(dir / "missing.bin"), policy::PolicyFormatError);
  std::filesystem::remove_all(dir);
}

TEST(PolicyFormat, CsvHasOneRowPerLayerAndNode) {
  std::ostringstream out;
  policy::write_policy_csv(out, table());
  std::istringstream in(out.str());
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header,
            "layer,lambda_kJ_per_s,stage,s_m,node,v_kmh,control,regime,force_kN,cost_to_go_kJ,"
            "time_to_go_s,energy_to_go_kJ");
  std::size_t rows = 0;
  std::string first;
  while (std::getline(in, row)) {
    if (rows++ == 0) first = row;
  }
  EXPECT_EQ(rows, 2u * table().speed_ms.size());
  EXPECT_EQ(first.rfind("0,600.000000,0,0.000000,0,0.000000,max_traction,full_traction,", 0), 0u)
      << first;
}

TEST(PolicyFormat, EveryTruncationIsAClearError) {
  const std::string& b = bytes();
  for (std::size_t n = 0; n < b.size(); ++n) {
    const std::string msg = error_of(b.substr(0, n));
    ASSERT_FALSE(msg.empty()) << "truncated to " << n << " bytes was accepted";
    if (n >= 20) {
      ASSERT_NE(msg.find("truncated"), std::string::npos) << msg;
    }
  }
  EXPECT_NE(error_of(b.substr(0, 5)).find("wrong magic"), std::string::npos);
  EXPECT_NE(error_of(b + "x").find("size mismatch"), std::string::npos);
}

TEST(PolicyFormat, EverySingleBitFlipIsDetected) {
  const std::string& b = bytes();
  for (std::size_t pos = 0; pos < b.size(); ++pos) {
    std::string c = b;
    c[pos] = static_cast<char>(c[pos] ^ (1 << (pos % 8)));
    ASSERT_FALSE(error_of(c).empty()) << "bit flip at byte " << pos << " was accepted";
  }
  std::string c = b;
  c[b.size() / 2] ^= 0x10;
  EXPECT_NE(error_of(c).find("corrupted: checksum"), std::string::npos) << error_of(c);
}

TEST(PolicyFormat, WrongMagicAndVersionAreNamed) {
  std::string c = bytes();
  c[0] = 'X';
  EXPECT_NE(error_of(c).find("not an ecorail policy table"), std::string::npos);
  c = bytes();
  c[8] = 2;
  EXPECT_NE(error_of(c).find("format version 2, this program reads version 1"), std::string::npos)
      << error_of(c);
  EXPECT_NE(error_of("").find("wrong magic"), std::string::npos);
}

TEST(PolicyFormat, WellFramedNonsenseIsRejectedNotTrusted) {
  // Sealed again after corruption, so only the parser and the validation stand in the way.
  const std::string& b = bytes();
  std::mt19937 rng(42);
  int rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string c = b;
    const int flips = 1 + trial % 4;
    for (int k = 0; k < flips; ++k) {
      const std::size_t pos = 20 + rng() % (c.size() - 28);
      c[pos] = static_cast<char>(rng());
    }
    try {
      const policy::PolicyTable t = policy::decode_policy(reseal(c));
      // Accepted: then it is internally consistent, so lookups stay in bounds.
      for (int i = 0; i < t.stage_count(); ++i) (void)t.cost_to_go_J(0, t.position_m[i], 10.0);
    } catch (const policy::PolicyFormatError&) {
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 0);
  // A node count that does not fit, and an unknown control code, named as such.
  std::string c = bytes();
  const policy::PolicyTable& t = table();
  const std::size_t counts = 20 + 4 + policy::kPolicyUnits.size() + 4 + t.line_name.size() + 8 + 4 +
                             t.train_name.size() + 8 + 4 + t.from.size() + 4 + t.to.size() + 8 + 1 +
                             4 * 8;
  c[counts + 4 + 3] = 0x7f;
  EXPECT_NE(error_of(reseal(c)).find("inconsistent counts"), std::string::npos)
      << error_of(reseal(c));
  c = bytes();
  const std::size_t controls = c.size() - 8 - 2 * t.speed_ms.size() * (2 + 3 * 8);
  c[controls] = 7;
  EXPECT_NE(error_of(reseal(c)).find("control code"), std::string::npos) << error_of(reseal(c));
}

}  // namespace
}  // namespace ecorail
