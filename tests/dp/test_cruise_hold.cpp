// Cruising as a speed hold (dp::hold_cruising): a saw tooth of full traction and coasting in a
// narrow band of speed becomes one hold at the band's mean speed, which covers the stretch in
// about the same time for less energy; programs that do not oscillate are left alone. The saw
// tooth is made here by a hysteresis law on a long level line, independent of the DP.
#include <gtest/gtest.h>

#include <cmath>

#include "data/train_io.hpp"
#include "dp/policy_extraction.hpp"
#include "physics/motion.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail {
namespace {

using physics::Control;

struct LevelLine {
  physics::Train train = data::default_train();
  physics::Route route;
  physics::SpeedEnvelope envelope;
  std::unique_ptr<physics::Motion> motion;
  LevelLine() {
    physics::RouteSegment seg;
    seg.start_m = 0.0;
    seg.end_m = 10000.0;
    seg.speed_limit_ms = units::kmh_to_ms(80.0);
    route = physics::Route({seg}, 0.0, 1, "L0", "L1");
    envelope = physics::SpeedEnvelope(train, route);
    motion = std::make_unique<physics::Motion>(train, route, envelope);
  }
  physics::SimulationResult simulate(const physics::ControlProgram& program) const {
    return physics::simulate(*motion, program, physics::SimulationOptions{});
  }
};

// Full traction up to hi_kmh, coasting down to lo_kmh, again and again until end_m, then a
// coast into the stop: the switch positions found by stepping 0.5 m with the motion kernel.
physics::ControlProgram saw_tooth(const LevelLine& line, double lo_kmh, double hi_kmh,
                                  double end_m) {
  physics::ControlProgram program{{0.0, Control::MaxTraction}};
  const physics::StepSettings step{0.05, 4};
  double s = 0.0, e = 0.0;
  Control c = Control::MaxTraction;
  while (s < end_m) {
    const auto adv = line.motion->advance(s, e, s + 0.5, c, step);
    s += 0.5;
    e = adv.e_end;
    const double v_kmh = units::ms_to_kmh(physics::speed_from_e(e));
    const Control next = c == Control::MaxTraction && v_kmh >= hi_kmh ? Control::Coast
                         : c == Control::Coast && v_kmh <= lo_kmh     ? Control::MaxTraction
                                                                      : c;
    if (next != c) program.push_back({s, c = next});
  }
  if (c != Control::Coast) program.push_back({s, Control::Coast});
  return program;
}

TEST(CruiseHold, SawToothBecomesOneHoldAtItsMeanSpeed) {
  const LevelLine line;
  const physics::ControlProgram saw = saw_tooth(line, 68.0, 72.0, 9000.0);
  ASSERT_GT(saw.size(), 10u);  // a real saw tooth
  const physics::SimulationResult saw_run = line.simulate(saw);
  ASSERT_FALSE(saw_run.stopped_early);

  const physics::ControlProgram held = dp::hold_cruising(saw, saw_run);
  ASSERT_EQ(held.size(), 3u);
  EXPECT_EQ(held[0].control, Control::MaxTraction);
  EXPECT_EQ(held[1].control, Control::Hold);
  EXPECT_EQ(held[2].control, Control::Coast);
  EXPECT_EQ(held[2].from_m, saw.back().from_m);  // the final coast starts where it did

  const physics::SimulationResult hold_run = line.simulate(held);
  ASSERT_FALSE(hold_run.stopped_early);
  // The hold's speed is the saw tooth's mean (distance over time), inside its band.
  double v_hold_kmh = 0.0;
  for (const auto& p : hold_run.trace) {
    if (p.s_m > held[1].from_m + 10.0 && p.s_m < held[2].from_m) {
      v_hold_kmh = units::ms_to_kmh(p.v_ms);
      break;
    }
  }
  EXPECT_GT(v_hold_kmh, 68.5);
  EXPECT_LT(v_hold_kmh, 71.5);
  // Same mean speed, so about the same time; less resistance work, so less energy.
  EXPECT_NEAR(hold_run.running_time_s, saw_run.running_time_s, 0.005 * saw_run.running_time_s);
  EXPECT_LT(hold_run.energy.traction_work_J, saw_run.energy.traction_work_J);
}

TEST(CruiseHold, TooFewSwingsOrAWideBandAreLeftAlone) {
  const LevelLine line;
  // Two switches only (traction, coast, traction, then the limit): no cruise.
  const physics::ControlProgram saw = saw_tooth(line, 68.0, 72.0, 9000.0);
  const physics::ControlProgram two(saw.begin(), saw.begin() + 3);
  const auto two_run = line.simulate(two);
  EXPECT_EQ(dp::hold_cruising(two, two_run).size(), two.size());
  // A band of 30 km/h is no cruise.
  const physics::ControlProgram wide = saw_tooth(line, 40.0, 70.0, 9000.0);
  const auto wide_run = line.simulate(wide);
  EXPECT_EQ(dp::hold_cruising(wide, wide_run).size(), wide.size());
}

TEST(CruiseHold, MergeShortEntriesDropsPhasesBelowTheMinimum) {
  const LevelLine line;
  const physics::ControlProgram program{{0.0, Control::MaxTraction},
                                        {400.0, Control::Coast},
                                        {405.0, Control::Hold},
                                        {407.0, Control::Coast},
                                        {1200.0, Control::MaxBrake}};
  const auto run = line.simulate(program);
  int merged = 0;
  // 5 m: only the 2 m hold goes; the coasts on either side join.
  const auto five = dp::merge_short_entries(program, run, 5.0, 0.0, &merged);
  EXPECT_EQ(merged, 1);
  ASSERT_EQ(five.size(), 3u);
  EXPECT_EQ(five[1].from_m, 400.0);
  EXPECT_EQ(five[1].control, Control::Coast);
  // 10 m: the 5 m coast goes too; traction runs on to the long coast.
  const auto ten = dp::merge_short_entries(program, run, 10.0, 0.0, &merged);
  EXPECT_EQ(merged, 2);
  ASSERT_EQ(ten.size(), 3u);
  EXPECT_EQ(ten[1].from_m, 407.0);
  // By duration: at about 60 km/h the 5 m coast lasts 0.3 s, the 2 m hold 0.12 s.
  const auto brief = dp::merge_short_entries(program, run, 0.0, 0.2, &merged);
  EXPECT_EQ(merged, 1);
  EXPECT_EQ(brief.size(), 3u);
}

}  // namespace
}  // namespace ecorail
