// TTOBench import: each field's mapping on hand-computable cases (power caps, efficiencies,
// rotating mass, pneumatic braking, Davis terms, units, stops, limits, gradients, curvatures,
// tunnels) and malformed files, each of which must name its JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "data/input_error.hpp"
#include "data/ttobench_io.hpp"
#include "physics/motion.hpp"
#include "physics/route.hpp"
#include "physics/speed_envelope.hpp"

namespace ecorail::data {
namespace {

// A train whose every number is easy to follow by hand.
std::string train_json(const std::string& extra = "", const std::string& mass_unit = "kg",
                       const std::string& mass_value = "100000") {
  return R"J({
  "metadata": {"id": "hand_train", "library version": "TTOBench v1.4"},
  "mass": {"unit": ")J" +
         mass_unit + R"J(", "value": )J" + mass_value + R"J(},
  "rho": {"unit": "%", "value": 10},
  "length": {"unit": "m", "value": 50},
  "max traction power": {"unit": "MW", "value": 2},
  "max reg braking power": {"unit": "kW", "value": 1500},
  "max traction force": {"unit": "kN", "value": 200},
  "max reg braking force": {"unit": "N", "value": 150000},
  "max pn braking force": {"unit": "kN", "value": 100},
  "max speed": {"unit": "m/s", "value": 36},
  "rolling resistance r0": {"unit": "kN", "value": 2},
  "rolling resistance r1": {"unit": "kN/(km/h)", "value": 0.036},
  "rolling resistance r2": {"unit": "kN/(km/h)^2", "value": 0.00036},
  "efficiency traction": {"unit": "%", "value": 90},
  "efficiency reg brake": {"unit": "-", "value": 0.8})J" +
         extra + "\n}";
}

std::string track_json(const std::string& extra = "") {
  return R"J({
  "metadata": {"id": "hand_track", "library version": "TTOBench v1.4"},
  "altitude": {"unit": "m", "value": 12},
  "stops": {"unit": "km", "values": [0, 1.5, 3]},
  "speed limits": {"units": {"position": "m", "velocity": "km/h"},
                   "values": [[0, 60], [1000, 90]]},
  "gradients": {"units": {"position": "m", "slope": "permil"},
                "values": [[0, 0], [2000, 5.5]]})J" +
         extra + "\n}";
}

void expect_path(const std::function<void()>& f, const std::string& path) {
  try {
    f();
    ADD_FAILURE() << "no InputError; expected one naming " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), path) << e.what();
    EXPECT_EQ(e.file(), "f.json") << e.what();
  }
}

TEST(TtobenchTrain, PowerCapsForcesAndUnits) {
  const physics::Train t = train_from_ttobench(train_json(), "f.json");
  EXPECT_EQ(t.name, "hand_train");
  EXPECT_DOUBLE_EQ(t.mass_kg, 100000.0);
  // Traction: 200 kN up to 2000 kW / 200 kN = 10 m/s, then P / v.
  EXPECT_DOUBLE_EQ(t.traction.force_N(5.0), 200000.0);
  EXPECT_DOUBLE_EQ(t.traction.force_N(20.0), 100000.0);
  // Regenerative brake: 150 kN up to 10 m/s, then 1500 kW / v; plus 100 kN pneumatic.
  EXPECT_DOUBLE_EQ(t.braking.force_N(20.0), 75000.0);
  EXPECT_DOUBLE_EQ(t.pneumatic_brake_N, 100000.0);
  EXPECT_DOUBLE_EQ(t.max_brake_N(20.0, 0.0), 175000.0);
  EXPECT_DOUBLE_EQ(t.max_brake_N(5.0, 0.0), 250000.0);
  EXPECT_DOUBLE_EQ(t.max_speed_ms, 36.0);
  EXPECT_DOUBLE_EQ(t.length_m, 50.0);
  EXPECT_DOUBLE_EQ(t.traction_efficiency, 0.9);
  EXPECT_DOUBLE_EQ(t.regen_efficiency, 0.8);
  // No comfort limits given: none applied.
  EXPECT_TRUE(std::isinf(t.max_accel_m_s2));
  EXPECT_TRUE(std::isinf(t.max_decel_m_s2));
  // Mass in tonnes reads the same.
  EXPECT_DOUBLE_EQ(train_from_ttobench(train_json("", "t", "100"), "f.json").mass_kg, 100000.0);
}

TEST(TtobenchTrain, DavisTermsAreTheAbsoluteForces) {
  const physics::Train t = train_from_ttobench(train_json(), "f.json");
  // At 36 km/h: 2000 N + 36 N/(km/h) * 36 + 0.36 N/(km/h)^2 * 36^2 = 3762.56 N.
  EXPECT_NEAR(t.resistance_N(10.0, 0.0), 3762.56, 1e-9);
  // A 10 per mille climb adds m g / 100 with g = 9.81.
  EXPECT_NEAR(t.resistance_N(10.0, 10.0) - t.resistance_N(10.0, 0.0), 100000.0 * 9.81 / 100.0,
              1e-9);
}

TEST(TtobenchTrain, RotatingMassSetsTheInertia) {
  const physics::Train t = train_from_ttobench(train_json(), "f.json");
  EXPECT_DOUBLE_EQ(t.effective_mass_kg(), 110000.0);
  // One 1 m step of full traction from 5 m/s on level track: de/ds = (F - W) / (M (1 + rho)).
  const physics::Route route({{0.0, 1000.0, 0.0, 0.0, 30.0}}, 0.0, 1, "a", "b");
  const physics::SpeedEnvelope env(t, route, 1.0);
  const physics::Motion motion(t, route, env);
  const physics::Substep sub = motion.substep(100.0, 12.5, 1e-3, physics::Control::MaxTraction, 4);
  const double w = t.resistance_N(5.0, 0.0);
  EXPECT_NEAR((sub.e_end - 12.5) / 1e-3, (200000.0 - w) / 110000.0, 1e-3);
}

TEST(TtobenchTrain, PneumaticBrakingRegeneratesNothing) {
  const physics::Train t = train_from_ttobench(train_json(), "f.json");
  const physics::Route route({{0.0, 1000.0, 0.0, 0.0, 30.0}}, 0.0, 1, "a", "b");
  const physics::SpeedEnvelope env(t, route, 1.0);
  const physics::Motion motion(t, route, env);
  // Full braking over 1 m at 20 m/s: 75 kN regenerative (1500 kW / 20 m/s) + 100 kN pneumatic.
  const physics::Substep sub = motion.substep(100.0, 200.0, 1.0, physics::Control::MaxBrake, 4);
  EXPECT_NEAR(sub.brake_work_J, 175000.0, 200.0);
  EXPECT_NEAR(sub.brake_work_J - sub.regen_brake_work_J, 100000.0, 1.0);
  // Below 10 m/s the regenerative part is its force cap, 150 kN.
  const physics::Substep slow = motion.substep(100.0, 12.5, 0.1, physics::Control::MaxBrake, 4);
  EXPECT_NEAR(slow.regen_brake_work_J, 15000.0, 1e-6);
  // Without a pneumatic brake every joule of braking is regenerative.
  physics::Train all_regen = t;
  all_regen.pneumatic_brake_N = 0.0;
  const physics::SpeedEnvelope env2(all_regen, route, 1.0);
  const physics::Motion m2(all_regen, route, env2);
  const physics::Substep s2 = m2.substep(100.0, 200.0, 1.0, physics::Control::MaxBrake, 4);
  EXPECT_EQ(s2.regen_brake_work_J, s2.brake_work_J);
  EXPECT_NEAR(s2.brake_work_J, 75000.0, 200.0);
}

TEST(TtobenchTrain, ComfortLimitsAndTunnelTable) {
  const physics::Train t = train_from_ttobench(train_json(R"J(,
  "max acceleration": {"unit": "m/s^2", "value": 0.5},
  "max deceleration": {"unit": "m/s^2", "value": 0.6},
  "tunnel resistance": {"units": {"cross section": "m^2", "coefficient": "kN/(km/h)^2"},
                        "values": [[24, 0.0012], [40, 0.0006]]})J"),
                                               "f.json");
  EXPECT_DOUBLE_EQ(t.max_accel_m_s2, 0.5);
  EXPECT_DOUBLE_EQ(t.max_decel_m_s2, 0.6);
  // Full traction at 5 m/s is cut to M_eff a + W.
  EXPECT_DOUBLE_EQ(t.max_traction_N(5.0, 1000.0), 110000.0 * 0.5 + 1000.0);
  ASSERT_EQ(t.tunnel_drag.size(), 2u);
  EXPECT_DOUBLE_EQ(t.tunnel_drag[1].cross_section_m2, 40.0);
  EXPECT_DOUBLE_EQ(t.tunnel_drag[1].C_kN_per_kmh2, 0.0006);
}

TEST(TtobenchTrack, StopsLimitsGradientsAndUnits) {
  const Line line = line_from_ttobench(track_json(), "f.json");
  ASSERT_EQ(line.stations.size(), 3u);
  EXPECT_EQ(line.stations[0].name, "S0");
  EXPECT_EQ(line.stations[2].name, "S2");
  EXPECT_DOUBLE_EQ(line.stations[1].km_post_m, 1500.0);
  ASSERT_EQ(line.limits.size(), 2u);
  EXPECT_DOUBLE_EQ(line.limits[0].end_km_post_m, 1000.0);
  EXPECT_DOUBLE_EQ(line.limits[1].end_km_post_m, 3000.0);
  EXPECT_DOUBLE_EQ(line.limits[1].value, 90.0);
  ASSERT_EQ(line.gradients.size(), 2u);
  EXPECT_DOUBLE_EQ(line.gradients[1].value, 5.5);
  EXPECT_TRUE(line.cap_limits_at_train_speed);
  // Named stops.
  const Line named =
      line_from_ttobench(track_json(R"J(, "stop names": ["Here", "Mid", "There"])J"), "f.json");
  EXPECT_EQ(named.stations[1].name, "Mid");
}

TEST(TtobenchTrack, CurvaturesAndTunnels) {
  const Line line = line_from_ttobench(track_json(R"J(,
  "curvatures": {"units": {"position": "m", "radius at start": "m", "radius at end": "m"},
                 "values": [[0, "infinity", "infinity"], [500, "infinity", -500],
                            [600, -500, -500], [700, "infinity", "infinity"]]},
  "tunnels": {"units": {"position": "m", "length": "m", "cross section": "m^2"},
              "values": [[2000, 300, 40]]})J"),
                                       "f.json");
  ASSERT_EQ(line.curvatures.size(), 4u);
  EXPECT_EQ(line.curvatures[1].curvature_start_per_m, 0.0);
  EXPECT_DOUBLE_EQ(line.curvatures[1].curvature_end_per_m, -1.0 / 500.0);
  EXPECT_DOUBLE_EQ(line.curvatures[3].end_km_post_m, 3000.0);
  ASSERT_EQ(line.tunnels.size(), 1u);
  EXPECT_DOUBLE_EQ(line.tunnels[0].end_km_post_m, 2300.0);
  EXPECT_DOUBLE_EQ(line.tunnels[0].cross_section_m2, 40.0);
}

// Metadata is free text: keys TTOBench does not define there are read past and reported (one
// warning each); the same key at the top level of a track or train (where a solve reads) is
// refused with its path.
TEST(TtobenchMetadata, UnknownKeysAreReportedNotRefused) {
  auto with_note = [](std::string text) {
    text.replace(text.find("\"library version\""), 0, "\"note\": {\"any\": [1, 2]}, ");
    return text;
  };
  const std::string train = with_note(train_json());
  const std::string track = with_note(track_json());
  EXPECT_NO_THROW(train_from_ttobench(train, "f.json"));
  EXPECT_NO_THROW(line_from_ttobench(track, "f.json"));
  for (const std::string& text : {train, track}) {
    const std::vector<std::string> w = ttobench_metadata_warnings(text);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("'metadata.note'"), std::string::npos) << w[0];
  }
  EXPECT_TRUE(ttobench_metadata_warnings(train_json()).empty());
  EXPECT_TRUE(ttobench_metadata_warnings(track_json()).empty());
  // The same train with or without the note is the same model.
  const physics::Train a = train_from_ttobench(train, "f.json");
  const physics::Train b = train_from_ttobench(train_json(), "f.json");
  EXPECT_EQ(a.mass_kg, b.mass_kg);
  EXPECT_EQ(a.name, b.name);
  expect_path([&] { line_from_ttobench(track_json(R"J(, "note": "x")J"), "f.json"); }, "note");
}

TEST(TtobenchMalformed, EachErrorNamesItsJsonPath) {
  const auto train = [](const std::string& text) { train_from_ttobench(text, "f.json"); };
  const auto track = [](const std::string& text) { line_from_ttobench(text, "f.json"); };
  std::string t = train_json();
  expect_path([&] { train(t.substr(0, t.find("\"mass\"")) + t.substr(t.find("\"rho\""))); },
              "mass");
  expect_path([&] { train(train_json("", "lb")); }, "mass.unit");
  expect_path([&] { train(train_json("", "kg", "\"heavy\"")); }, "mass.value");
  expect_path([&] { train(train_json("", "kg", "-5")); }, "mass.value");
  expect_path([&] { train(train_json(R"J(, "colour": "red")J")); }, "colour");
  expect_path(
      [&] {
        std::string s = train_json();
        const std::string scalar = R"J("efficiency traction": {"unit": "%", "value": 90})J";
        s.replace(s.find(scalar), scalar.size(),
                  R"J("efficiency traction": {"units": {"speed": "km/h"}, "values": [[0, 0.9]]})J");
        train(s);
      },
      "efficiency traction");
  expect_path(
      [&] {
        train(train_json(R"J(, "tunnel resistance": {"units": {"cross section": "m^2",
            "coefficient": "kN/(km/h)^2"}, "values": [[24, 0.001, 3]]})J"));
      },
      "tunnel resistance.values[0]");
  std::string k = track_json();
  expect_path([&] { track(k.replace(k.find("[0, 1.5, 3]"), 11, "[0.2, 1.5, 3]")); },
              "stops.values[0]");
  k = track_json();
  expect_path([&] { track(k.replace(k.find("[1000, 90]"), 10, "[1000, 90, 1]")); },
              "speed limits.values[1]");
  k = track_json();
  expect_path([&] { track(k.replace(k.find("[2000, 5.5]"), 11, "[0, 5.5]")); },
              "gradients.values[1][0]");
  k = track_json();
  expect_path([&] { track(k.replace(k.find("\"km/h\""), 6, "\"mph\"")); },
              "speed limits.units.velocity");
  expect_path(
      [&] {
        track(track_json(R"J(, "tunnels": {"units": {"position": "m", "length": "m",
            "cross section": "m^2"}, "values": [[2900, 300, 40]]})J"));
      },
      "tunnels.values[0][1]");
  expect_path(
      [&] {
        track(track_json(R"J(, "curvatures": {"units": {"position": "m",
            "radius at start": "m", "radius at end": "m"}, "values": [[0, 0, 300]]})J"));
      },
      "curvatures.values[0][1]");
  // A train given where a track is expected, and broken JSON: named too.
  try {
    track(train_json());
    ADD_FAILURE() << "a train read as a track";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a TTOBench train"), std::string::npos) << e.what();
  }
  try {
    track("{\"stops\": [1, 2,");
    ADD_FAILURE() << "broken JSON read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("syntax error at byte"), std::string::npos) << e.what();
  }
  // A number beyond double's range: nlohmann reports it as out_of_range, not a parse error;
  // found by fuzz_ttobench (fuzz/seeds/ttobench/number_overflow.json).
  for (const std::string text : {"1E1191", "{\"stops\": [1E400]}"}) {
    for (const bool as_track : {true, false}) {
      try {
        if (as_track) {
          track(text);
        } else {
          train_from_ttobench(text, "train.json");
        }
        ADD_FAILURE() << "an overflowing number read: " << text;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("within double's range"), std::string::npos)
            << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace ecorail::data
