// Prefix resume of the forward re-simulation (physics::simulate with an earlier run): a run of
// an edited program resumed from the earlier run's last checkpoint before the first change must
// be the full re-simulation of that program bit for bit: every trace point, the energy ledger,
// the running time, the stop error and the checkpoints themselves compared with ==. The edits
// are drawn at random (counter-based draws): switch points moved far, moved by less than the
// event tolerance, moved onto a step boundary, a checkpoint or a route change; controls
// changed (the first entry too); entries inserted and deleted. Each edit resumes from the
// previous resumed run, so checkpoints written by a resumed run are exercised as well, and
// some from only a prefix of it (physics::resume_prefix, what an engine keeps). Two
// routes: A6 -> A7 of the embedded line, and a TTOBench-like route (gradient, curve, tunnel and
// limit changes) driven by a train with a tabulated traction curve and a pneumatic brake.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "physics/motion.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail::physics {
namespace {

constexpr std::uint64_t kSalt = 0x7265'7375'6d65ULL;  // "resume"

struct Draws {
  std::uint64_t seed;
  std::uint64_t edit = 0;
  int k = 0;
  // A counter-based draw (splitmix64 of seed, edit, k and the salt): the same programs on
  // every run and platform, keyed by what they are for.
  double uniform() {
    std::uint64_t z = seed ^ (edit * 0x9E37'79B9'7F4A'7C15ULL) ^
                      (static_cast<std::uint64_t>(k++) * 0xBF58'476D'1CE4'E5B9ULL) ^ kSalt;
    z = (z ^ (z >> 30)) * 0xBF58'476D'1CE4'E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D0'49BB'1331'11EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  std::size_t index(std::size_t n) {
    return std::min(n - 1, static_cast<std::size_t>(uniform() * static_cast<double>(n)));
  }
  Control control() { return static_cast<Control>(index(kControlCount)); }
};

void expect_same(const SimulationResult& a, const SimulationResult& b, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.trace.size(), b.trace.size());
  for (std::size_t i = 0; i < a.trace.size(); ++i) {
    const TracePoint& p = a.trace[i];
    const TracePoint& q = b.trace[i];
    ASSERT_TRUE(p.t_s == q.t_s && p.s_m == q.s_m && p.v_ms == q.v_ms &&
                p.accel_m_s2 == q.accel_m_s2 && p.force_N == q.force_N && p.regime == q.regime)
        << "trace point " << i;
  }
  EXPECT_EQ(a.energy.traction_work_J, b.energy.traction_work_J);
  EXPECT_EQ(a.energy.brake_work_J, b.energy.brake_work_J);
  EXPECT_EQ(a.energy.regen_J, b.energy.regen_J);
  EXPECT_EQ(a.energy.traction_input_J, b.energy.traction_input_J);
  EXPECT_EQ(a.running_time_s, b.running_time_s);
  EXPECT_EQ(a.end_position_m, b.end_position_m);
  EXPECT_EQ(a.end_speed_ms, b.end_speed_ms);
  EXPECT_EQ(a.stop_error_m, b.stop_error_m);
  EXPECT_EQ(a.max_overspeed_ms, b.max_overspeed_ms);
  EXPECT_EQ(a.stopped_early, b.stopped_early);
  ASSERT_EQ(a.checkpoints.size(), b.checkpoints.size());
  for (std::size_t i = 0; i < a.checkpoints.size(); ++i) {
    const SimulationCheckpoint& p = a.checkpoints[i];
    const SimulationCheckpoint& q = b.checkpoints[i];
    ASSERT_TRUE(p.trace_size == q.trace_size && p.s_m == q.s_m && p.e == q.e && p.t_s == q.t_s &&
                p.energy.traction_work_J == q.energy.traction_work_J &&
                p.energy.brake_work_J == q.energy.brake_work_J &&
                p.energy.regen_J == q.energy.regen_J &&
                p.energy.traction_input_J == q.energy.traction_input_J &&
                p.max_overspeed_ms == q.max_overspeed_ms)
        << "checkpoint " << i;
  }
}

// A plausible program: full traction, then switches at random positions (holds most often),
// full braking towards the end.
ControlProgram random_program(Draws& d, double length_m) {
  ControlProgram p = {{0.0, Control::MaxTraction}};
  const int n = 2 + static_cast<int>(d.index(6));
  std::vector<double> at;
  for (int i = 0; i < n; ++i) at.push_back((0.15 + 0.7 * d.uniform()) * length_m);
  std::sort(at.begin(), at.end());
  for (double x : at) p.push_back({x, d.uniform() < 0.4 ? Control::Hold : d.control()});
  p.push_back({0.93 * length_m, Control::MaxBrake});
  return p;
}

// One random edit of a program; positions may be drawn from the earlier run's steps and
// checkpoints and from the route's change points, to land exactly on the places where a
// resume has to be careful.
ControlProgram edit(Draws& d, ControlProgram p, const SimulationResult& earlier,
                    const Route& route) {
  const double length = route.length_m();
  auto between = [&](std::size_t k) {  // strictly inside entry k's neighbours
    const double lo = p[k - 1].from_m;
    const double hi = k + 1 < p.size() ? p[k + 1].from_m : length;
    return lo + (0.001 + 0.998 * d.uniform()) * (hi - lo);
  };
  auto fits = [&](std::size_t k, double x) {
    return x > p[k - 1].from_m && (k + 1 == p.size() || x < p[k + 1].from_m) && x < length;
  };
  const std::size_t k = p.size() > 1 ? 1 + d.index(p.size() - 1) : 0;
  switch (d.index(8)) {
    case 0:
      if (k > 0) p[k].from_m = between(k);
      break;
    case 1:  // a move around the event tolerance of 1e-9 m
      if (k > 0) {
        const double tiny[] = {1e-12, 5e-10, 1e-9, 2e-9, 1e-7, 1e-6};
        const double x = p[k].from_m + (d.uniform() < 0.5 ? -1.0 : 1.0) * tiny[d.index(6)];
        if (fits(k, x)) p[k].from_m = x;
      }
      break;
    case 2:  // onto a step boundary of the earlier run
      if (k > 0) {
        const double x = earlier.trace[d.index(earlier.trace.size())].s_m;
        if (fits(k, x)) p[k].from_m = x;
      }
      break;
    case 3:  // onto a checkpoint of the earlier run
      if (k > 0 && !earlier.checkpoints.empty()) {
        const double x = earlier.checkpoints[d.index(earlier.checkpoints.size())].s_m;
        if (fits(k, x)) p[k].from_m = x;
      }
      break;
    case 4: {  // onto a route change
      const std::vector<double> changes = route.change_points_m();
      if (k > 0 && !changes.empty()) {
        const double x = changes[d.index(changes.size())];
        if (fits(k, x)) p[k].from_m = x;
      }
      break;
    }
    case 5:  // another control, the first entry's too
      p[d.index(p.size())].control = d.control();
      break;
    case 6: {  // a new entry
      const double x = d.uniform() * length;
      auto it = std::upper_bound(p.begin(), p.end(), x,
                                 [](double s, const ProgramStep& q) { return s < q.from_m; });
      if (it != p.begin() && (it - 1)->from_m != x) p.insert(it, {x, d.control()});
      break;
    }
    case 7:
      if (k > 0) p.erase(p.begin() + static_cast<std::ptrdiff_t>(k));
      break;
  }
  return p;
}

// Returns how many of the edits resumed from a checkpoint past the start (so that the test
// shows it exercised resuming, not only the fall-back to a full run).
int check_edits(const Motion& motion, std::uint64_t seed, int programs, int edits_each) {
  const SimulationOptions opt;
  int resumed = 0;
  for (int r = 0; r < programs; ++r) {
    Draws d{seed, static_cast<std::uint64_t>(r) * 1000};
    ControlProgram program = random_program(d, motion.route().length_m());
    SimulationResult sim = simulate(motion, program, opt);
    for (int i = 0; i < edits_each; ++i) {
      d.edit = static_cast<std::uint64_t>(r) * 1000 + static_cast<std::uint64_t>(i) + 1;
      d.k = 0;
      ControlProgram next = edit(d, program, sim, motion.route());
      const SimulationResult full = simulate(motion, next, opt);
      SimulationResult resumed_run = simulate(motion, next, opt, sim);
      const double x = first_difference_m(next, program);
      if (sim.checkpoints.size() > 1 && sim.checkpoints[1].s_m < x) ++resumed;
      expect_same(full, resumed_run,
                  "program " + std::to_string(r) + ", edit " + std::to_string(i));
      if (::testing::Test::HasFatalFailure()) return resumed;
      if (i % 3 == 0) {
        // The same from only a prefix of the earlier run (what an engine keeps).
        const double up_to = (0.1 + 0.8 * d.uniform()) * motion.route().length_m();
        expect_same(full, simulate(motion, next, opt, resume_prefix(sim, up_to)),
                    "prefix, program " + std::to_string(r) + ", edit " + std::to_string(i));
        if (::testing::Test::HasFatalFailure()) return resumed;
      }
      program = std::move(next);
      sim = std::move(resumed_run);
    }
  }
  return resumed;
}

TEST(SimulationResume, ResumedRunsEqualFullRunsOnA6ToA7) {
  const Train train = data::default_train();
  const Route route = data::build_route(data::default_line(), "A6", "A7", train);
  const SpeedEnvelope envelope(train, route);
  const Motion motion(train, route, envelope);
  const int resumed = check_edits(motion, 6, 6, 10);
  EXPECT_GE(resumed, 20);
}

TEST(SimulationResume, ResumedRunsEqualFullRunsOnAGradedRouteWithATabulatedTrain) {
  Train train = data::default_train();
  train.traction = ForceEnvelope::table(
      {{0.0, 310.0}, {30.0, 300.0}, {55.0, 240.0}, {80.0, 150.0}, {100.0, 110.0}}, 3000.0);
  train.pneumatic_brake_N = 40000.0;
  std::vector<RouteSegment> segments;
  const double grades[] = {0.0, 12.0, -8.0, 3.5, -25.0, 30.0, 0.0, -4.0};
  double s = 0.0;
  for (int i = 0; i < 8; ++i) {
    RouteSegment seg;
    seg.start_m = s;
    seg.end_m = s + 250.0 + 37.5 * i;
    seg.gradient_permille = grades[i];
    seg.curve_radius_m = i % 3 == 1 ? 400.0 : 0.0;
    seg.tunnel_drag_N_per_kN_kmh2 = i == 4 ? 2e-4 : 0.0;
    seg.speed_limit_ms = units::kmh_to_ms(i == 5 ? 60.0 : 80.0);
    segments.push_back(seg);
    s = seg.end_m;
  }
  const Route route(segments, 0.0, 1, "T0", "T1");
  const SpeedEnvelope envelope(train, route);
  const Motion motion(train, route, envelope);
  const int resumed = check_edits(motion, 7, 6, 10);
  EXPECT_GE(resumed, 20);
}

// A run with a speed cap keeps no checkpoints and is never resumed: the resumed call is the
// full run.
TEST(SimulationResume, ACappedRunIsSimulatedInFull) {
  const Train train = data::default_train();
  const Route route = data::build_route(data::default_line(), "A6", "A7", train);
  const SpeedEnvelope envelope(train, route);
  const Motion motion(train, route, envelope);
  SimulationOptions opt;
  opt.speed_cap = [](double, double s) { return s < 600.0 ? 1e9 : 15.0; };
  const ControlProgram a = {{0.0, Control::MaxTraction}, {900.0, Control::Coast}};
  const ControlProgram b = {{0.0, Control::MaxTraction}, {950.0, Control::Coast}};
  const SimulationResult first = simulate(motion, a, opt);
  EXPECT_TRUE(first.checkpoints.empty());
  expect_same(simulate(motion, b, opt), simulate(motion, b, opt, first), "capped");
}

}  // namespace
}  // namespace ecorail::physics
