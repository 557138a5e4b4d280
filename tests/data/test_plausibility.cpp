// Plausibility ranges: inputs that parse but describe no railway are refused at load
// time with one InputError naming file, row and field and the range, before any solve. Each
// case here was once solved and reported as a success (exit 0) or ran into nonsense: a gradient
// of 1e308 per mille, a negative Davis coefficient, a train with no traction, absurd mass or
// gravity, a curve of 1 cm. The edges of each range are accepted.
#include <gtest/gtest.h>

#include "data/line_loader.hpp"
#include "data/plausibility.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "data_test_support.hpp"

namespace ecorail::data::test {
namespace {

std::string contest_train_text() {
  return read_file(contest_dir() / "train.toml");
}

// The contest train with the first occurrence of from replaced by to.
physics::Train train_with(const std::string& from, const std::string& to) {
  std::string text = contest_train_text();
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  text.replace(pos, from.size(), to);
  return parse_train_toml(text, "t.toml");
}

// Row 35 of the contest gradients (km 12290-12910, +3.5 per mille) lies on A6 -> A7.
void expect_gradient_refused(const std::string& value, bool refused) {
  TempDir dir;
  copy_contest_line(dir.path());
  edit_file(dir / "gradients.csv", "12290,12910,3.5", "12290,12910," + value);
  const std::string file = (dir / "gradients.csv").string();
  if (refused) {
    expect_input_error([&] { load_line(dir.path()); }, file, 35, "gradient_permille",
                       {"plausibility range", "100 per mille"});
  } else {
    EXPECT_NO_THROW(load_line(dir.path())) << value;
  }
}

TEST(Plausibility, GradientsBeyondHundredPerMilleAreRefused) {
  expect_gradient_refused("1e308", true);
  expect_gradient_refused("100000", true);
  expect_gradient_refused("-100000", true);
  expect_gradient_refused("100.001", true);
  expect_gradient_refused("100", false);
  expect_gradient_refused("-100", false);
}

TEST(Plausibility, CurveRadiiBelowTenMetresAreRefusedButZeroIsStraight) {
  for (const auto& [radius, refused] :
       {std::pair{"0.01", true}, {"9.99", true}, {"10", false}, {"0", false}}) {
    TempDir dir;
    copy_contest_line(dir.path());
    edit_file(dir / "curves.csv", "91,174,1000", std::string("91,174,") + radius);
    if (refused) {
      expect_input_error([&] { load_line(dir.path()); }, (dir / "curves.csv").string(), 3,
                         "radius_m", {"10 m", "plausibility range"});
    } else {
      EXPECT_NO_THROW(load_line(dir.path())) << radius;
    }
  }
}

TEST(Plausibility, TomlLinesGetTheSameRanges) {
  const std::string toml =
      "[[stations]]\nname = \"X\"\nkm_post_m = 0\n[[stations]]\nname = \"Y\"\nkm_post_m = 1000\n"
      "[[gradients]]\nstart_km_post_m = 0\nend_km_post_m = 1000\ngradient_permille = 250\n"
      "[[speed_limits]]\nstart_km_post_m = 0\nend_km_post_m = 1000\nlimit_kmh = 80\n"
      "[[curves]]\nstart_km_post_m = 0\nend_km_post_m = 1000\nradius_m = 0\n";
  TempDir dir;
  write_file(dir / "line.toml", toml);
  expect_input_error([&] { load_line(dir / "line.toml"); }, (dir / "line.toml").string(), 1,
                     "gradient_permille", {"100 per mille"});
}

TEST(Plausibility, TrainFieldsOutsideTheirRangesAreRefused) {
  const struct {
    const char* from;
    const char* to;
    const char* field;
  } cases[] = {
      {"A = 2.031", "A = -50.0", "davis.A"},
      {"B = 0.0622", "B = -0.01", "davis.B"},
      {"C = 0.001807", "C = -1e-6", "davis.C"},
      {"mass_t = 194.295", "mass_t = 1e12", "mass_t"},
      {"mass_t = 194.295", "mass_t = 0.001", "mass_t"},
      {"gravity_m_s2 = 9.8", "gravity_m_s2 = 100000.0", "gravity_m_s2"},
      {"gravity_m_s2 = 9.8", "gravity_m_s2 = 1.62", "gravity_m_s2"},
      {"max_speed_kmh = 80.0", "max_speed_kmh = 1e9", "max_speed_kmh"},
      {"max_accel_m_s2 = 1.0", "max_accel_m_s2 = 50.0", "max_accel_m_s2"},
      {"rotating_mass_factor = 0.0", "rotating_mass_factor = 7.0", "rotating_mass_factor"},
  };
  for (const auto& c : cases) {
    expect_input_error([&] { train_with(c.from, c.to); }, "t.toml", 0, c.field,
                       {"plausibility range"});
  }
  // The edges are accepted.
  EXPECT_NO_THROW(train_with("A = 2.031", "A = 0.0"));
  EXPECT_NO_THROW(train_with("gravity_m_s2 = 9.8", "gravity_m_s2 = 9.81"));
}

TEST(Plausibility, EnvelopesMustMoveAndStopTheTrain) {
  // No traction at all: once a run "in 0.000 s" with a stop error of -1354 m.
  expect_input_error(
      [] {
        train_with("{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [203.0] }",
                   "{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [0.0] }");
      },
      "t.toml", 0, "traction", {"starting resistance"});
  // Traction far beyond any adhesion (1e6 kN on 194 t).
  expect_input_error(
      [] {
        train_with("{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [203.0] }",
                   "{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [1e6] }");
      },
      "t.toml", 0, "traction", {"m/s^2 times the mass"});
  expect_input_error(
      [] {
        std::string text = contest_train_text();
        text = text.substr(0, text.find("[braking]")) +
               "[braking]\npoints = [[0.0, 0.0], [80.0, 0.0]]\n";
        parse_train_toml(text, "t.toml");
      },
      "t.toml", 0, "braking", {"braking force above 0"});
}

TEST(Plausibility, ATrainThatCannotStartOnTheSteepestClimbIsRefusedWhenTheRouteIsBuilt) {
  // 20 kN starts the contest train on level track (3.9 kN) but not on a 30 per mille climb
  // (194.3 t x 9.8 x 32 / 1000 = 61 kN).
  const physics::Train weak = train_with("{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [203.0] }",
                                         "{ from_kmh = 0.0, to_kmh = 51.5, coeffs_kN = [20.0] }");
  TempDir dir;
  copy_contest_line(dir.path());
  const physics::Route level = build_route(load_line(dir.path()), "A6", "A7", weak);
  EXPECT_GT(level.length_m(), 1000.0);
  edit_file(dir / "gradients.csv", "12910,13290,-1.8", "12910,13290,-30");
  // Running A6 -> A7 (falling km posts) a -30 row is a 30 per mille climb.
  expect_input_error([&] { build_route(load_line(dir.path()), "A6", "A7", weak); },
                     "train '" + weak.name + "'", 0, "traction",
                     {"steepest climb", "30 per mille"});
  // The reference train starts there.
  EXPECT_NO_THROW(build_route(load_line(dir.path()), "A6", "A7", default_train()));
}

}  // namespace
}  // namespace ecorail::data::test
