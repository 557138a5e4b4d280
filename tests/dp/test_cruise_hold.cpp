// Cruising as a speed hold (dp::hold_cruising): a saw tooth of full traction and coasting in a
// narrow band of speed becomes one hold at the band's mean speed, which covers the stretch in
// about the same time for less energy; programs that do not oscillate are left alone. The saw
// tooth is made here by a hysteresis law on a long level line, independent of the DP.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

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
  explicit LevelLine(double gradient_permille = 0.0) {
    physics::RouteSegment seg;
    seg.start_m = 0.0;
    seg.end_m = 10000.0;
    seg.gradient_permille = gradient_permille;
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

// hold_cruising leaves the program exactly as it is.
void expect_left_alone(const physics::ControlProgram& program,
                       const physics::SimulationResult& run) {
  const physics::ControlProgram kept = dp::hold_cruising(program, run);
  ASSERT_EQ(kept.size(), program.size());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    EXPECT_EQ(kept[k].from_m, program[k].from_m);
    EXPECT_EQ(kept[k].control, program[k].control);
  }
}

// A program driven 0.5 m at a time from rest under `rule`, which is given the position, the
// speed (km/h) and the control in force and returns the next step's control, or nothing to
// stop there; each change of control is an entry. `at_m` is where it stopped.
struct Driven {
  physics::ControlProgram program;
  double at_m = 0.0;
};
Driven drive(const physics::Motion& motion, double end_m,
             const std::function<std::optional<Control>(double, double, Control)>& rule) {
  Driven out{{{0.0, Control::MaxTraction}}, 0.0};
  const physics::StepSettings step{0.05, 4};
  double e = 0.0;
  Control c = Control::MaxTraction;
  while (out.at_m < end_m) {
    e = motion.advance(out.at_m, e, out.at_m + 0.5, c, step).e_end;
    out.at_m += 0.5;
    const std::optional<Control> next =
        rule(out.at_m, units::ms_to_kmh(physics::speed_from_e(e)), c);
    if (!next) break;
    if (*next != c) out.program.push_back({out.at_m, c = *next});
  }
  return out;
}

// The driven program, then a hold from where it stopped and a final coast from coast_m.
physics::ControlProgram then_hold_and_coast(Driven d, double coast_m) {
  d.program.push_back({d.at_m, Control::Hold});
  d.program.push_back({coast_m, Control::Coast});
  return d.program;
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

// Down a descent the grid's run can climb to its cruise in a staircase: coasts that gain
// speed and short traction blips, inside a narrow band. Its switch speeds never swing back, so
// it is no saw tooth, and held at its mean speed it would run a different run (on TTOBench St
// Gallen - Wil after 20 km such a hold ran 26 s slower than the grid's run at the same price).
TEST(CruiseHold, AStaircaseUpADescentIsNoSawTooth) {
  const LevelLine line(-15.0);
  // Traction to 60 km/h, then coasts of 0.5 km/h gain, each followed by 0.5 km/h of traction,
  // up to 65 km/h (a band the saw tooth test accepts): every switch speed above the one before.
  double coast_from_kmh = 0.0;
  bool first_climb = true;
  const Driven d = drive(*line.motion, 6000.0, [&](double, double v_kmh, Control c) {
    std::optional<Control> next = c;
    if (v_kmh >= 65.0) return std::optional<Control>();
    if (c == Control::MaxTraction &&
        (first_climb ? v_kmh >= 60.0 : v_kmh >= coast_from_kmh + 1.0)) {
      next = Control::Coast, coast_from_kmh = v_kmh, first_climb = false;
    } else if (c == Control::Coast && v_kmh >= coast_from_kmh + 0.5) {
      next = Control::MaxTraction;
    }
    return next;
  });
  const physics::ControlProgram stairs = then_hold_and_coast(d, 8000.0);
  ASSERT_GE(stairs.size(), 8u);  // at least three coasts and three blips
  const physics::SimulationResult run = line.simulate(stairs);
  ASSERT_FALSE(run.stopped_early);
  // Every coast gains speed: a staircase, not a saw tooth.
  for (std::size_t k = 1; k + 1 < stairs.size(); ++k) {
    if (stairs[k].control != Control::Coast) continue;
    double v_in = 0.0, v_out = 0.0;
    for (const auto& p : run.trace) {
      if (p.s_m <= stairs[k].from_m) v_in = p.v_ms;
      if (p.s_m <= stairs[k + 1].from_m) v_out = p.v_ms;
    }
    ASSERT_GT(v_out, v_in);
  }
  expect_left_alone(stairs, run);
}

// A staircase down: coasts that lose 1 km/h, each followed by a traction blip of 0.3 km/h, from
// 70 to 66 km/h. It swings, but every peak and every trough is below the one before and the
// peaks fall further than the tooth swings: a hold from its first switch would cruise at 70
// km/h, not at the staircase's speeds, so it is left as it is.
TEST(CruiseHold, AStaircaseDownIsNoSawTooth) {
  const LevelLine line;
  double switch_kmh = 0.0;
  bool first_climb = true;
  const Driven d = drive(*line.motion, 8000.0, [&](double, double v_kmh, Control c) {
    std::optional<Control> next = c;
    if (!first_climb && v_kmh <= 66.0) return std::optional<Control>();
    if (c == Control::MaxTraction && (first_climb ? v_kmh >= 70.0 : v_kmh >= switch_kmh + 0.3)) {
      next = Control::Coast, switch_kmh = v_kmh, first_climb = false;
    } else if (c == Control::Coast && v_kmh <= switch_kmh - 1.0) {
      next = Control::MaxTraction, switch_kmh = v_kmh;
    }
    return next;
  });
  const physics::ControlProgram stairs = then_hold_and_coast(d, 9000.0);
  ASSERT_GE(stairs.size(), 10u);  // at least four coasts and four blips
  const physics::SimulationResult run = line.simulate(stairs);
  ASSERT_FALSE(run.stopped_early);
  expect_left_alone(stairs, run);
}

// Traction riding an 80 km/h limit, a long coast through a dip (a climb, then a descent that
// brings the train back near the limit) and traction riding the limit again: three switches in
// a band of under 1 km/h, but the coast falls far below it in between. Held at the mean speed
// it would drive the dip at a steady speed, which costs more than coasting it; it is left as
// it is.
TEST(CruiseHold, ACoastThroughADipBetweenTwoRidesOfTheLimitIsNoSawTooth) {
  physics::Train train = data::default_train();
  std::vector<physics::RouteSegment> segments;
  for (const auto& [from_m, to_m, gradient] :
       std::vector<std::array<double, 3>>{{0.0, 2500.0, 0.0},
                                          {2500.0, 2800.0, 4.0},
                                          {2800.0, 4500.0, -25.0},
                                          {4500.0, 12000.0, 0.0}}) {
    physics::RouteSegment seg;
    seg.start_m = from_m;
    seg.end_m = to_m;
    seg.gradient_permille = gradient;
    seg.speed_limit_ms = units::kmh_to_ms(80.0);
    segments.push_back(seg);
  }
  const physics::Route route(segments, 0.0, 1, "D0", "D1");
  const physics::SpeedEnvelope envelope(train, route);
  const physics::Motion motion(train, route, envelope);
  // Coast from 2500 m; traction again where the coast, back down the descent, first reaches
  // 79.5 km/h after its dip.
  const physics::StepSettings step{0.05, 4};
  double s = 0.0, e = 0.0, dip_kmh = 80.0, back_m = NAN;
  physics::ControlProgram probe{{0.0, Control::MaxTraction}, {2500.0, Control::Coast}};
  while (s < 9000.0) {
    const Control c = s < 2500.0 ? Control::MaxTraction : Control::Coast;
    e = motion.advance(s, e, s + 0.5, c, step).e_end;
    s += 0.5;
    const double v_kmh = units::ms_to_kmh(physics::speed_from_e(e));
    if (s > 2500.0) dip_kmh = std::min(dip_kmh, v_kmh);
    if (s > 2800.0 && v_kmh >= 79.5) {
      back_m = s;
      break;
    }
  }
  ASSERT_TRUE(std::isfinite(back_m));
  ASSERT_LT(dip_kmh, 77.0);  // a real dip, well below the band of the switch speeds
  const physics::ControlProgram program{{0.0, Control::MaxTraction},    {2500.0, Control::Coast},
                                        {back_m, Control::MaxTraction}, {9000.0, Control::Coast},
                                        {9300.0, Control::MaxTraction}, {9400.0, Control::Coast}};
  const physics::SimulationResult run =
      physics::simulate(motion, program, physics::SimulationOptions{});
  ASSERT_FALSE(run.stopped_early);
  expect_left_alone(program, run);
}

// A tooth whose first phase rides the 80 km/h limit, above the tooth's mean speed (about 78.3
// km/h): after a hold at 79.5 km/h, traction rides the limit, then coasts to 78 km/h alternate
// with blips to 78.5-78.6 km/h. The ride never reaches the mean, so a hold from its end would
// keep 80 km/h; the ride is kept, and the hold starts where the tooth's first coast reaches the
// mean.
TEST(CruiseHold, AToothEnteredRidingALimitAboveItIsHeldAtItsOwnSpeed) {
  const LevelLine line;
  int stage = 0;  // 0 up to 79.5, 1 hold, 2 ride the limit, 3.. the tooth
  const std::array<double, 6> switch_kmh = {78.0, 78.6, 78.0, 78.5, 78.1, 78.6};
  Driven d = drive(*line.motion, 6000.0, [&](double s, double v_kmh, Control c) {
    std::optional<Control> next = c;
    if (stage == 0 && v_kmh >= 79.5)
      next = Control::Hold, stage = 1;
    else if (stage == 1 && s >= 1500.0)
      next = Control::MaxTraction, stage = 2;
    else if (stage == 2 && s >= 2500.0)
      next = Control::Coast, stage = 3;
    else if (stage >= 3) {
      const double target = switch_kmh[static_cast<std::size_t>(stage - 3)];
      if (c == Control::Coast ? v_kmh <= target : v_kmh >= target) {
        if (stage - 3 + 1 == static_cast<int>(switch_kmh.size())) return std::optional<Control>();
        next = c == Control::Coast ? Control::MaxTraction : Control::Coast, ++stage;
      }
    }
    return next;
  });
  const physics::ControlProgram tooth = then_hold_and_coast(d, 8000.0);
  ASSERT_EQ(tooth.size(), 11u);  // traction, hold, the ride, six phases of the tooth, hold, coast
  const physics::SimulationResult run = line.simulate(tooth);
  ASSERT_FALSE(run.stopped_early);
  // The ride: at the limit before the tooth's first coast.
  double v_ride_kmh = 0.0;
  for (const auto& p : run.trace) {
    if (p.s_m <= 2500.0) v_ride_kmh = units::ms_to_kmh(p.v_ms);
  }
  ASSERT_NEAR(v_ride_kmh, 80.0, 0.05);
  // The ride is kept and the tooth's own first coast leads into the hold, at the tooth's speed.
  const physics::ControlProgram held = dp::hold_cruising(tooth, run);
  const physics::SimulationResult held_run = line.simulate(held);
  ASSERT_FALSE(held_run.stopped_early);
  std::size_t k = 0;
  while (k + 1 < held.size() && !(held[k].control == Control::Hold && held[k].from_m > 2500.0)) {
    ++k;
  }
  ASSERT_LT(k + 1, held.size());  // the tooth's hold
  EXPECT_EQ(held[k - 1].control, Control::Coast);
  EXPECT_EQ(held[k - 1].from_m, 2500.0);
  for (const auto& p : held_run.trace) {
    if (p.s_m > held[k].from_m + 1.0 && p.s_m < held[k + 1].from_m) {
      EXPECT_GT(units::ms_to_kmh(p.v_ms), 77.9);
      EXPECT_LT(units::ms_to_kmh(p.v_ms), 78.7);
    }
  }
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
