#include "fitting/synthetic_log.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "physics/motion.hpp"
#include "physics/route.hpp"
#include "physics/simulator.hpp"
#include "physics/speed_envelope.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {

namespace {

struct Sample {
  double t_s, s_m, v_ms, force_N, gradient;
};

physics::Route random_route(std::mt19937_64& rng, const SyntheticLogOptions& opt) {
  std::uniform_real_distribution<double> len(2500.0, 6000.0);
  std::uniform_real_distribution<double> seg_len(300.0, 1200.0);
  std::uniform_real_distribution<double> grade(-opt.max_gradient_permille,
                                               opt.max_gradient_permille);
  const double length = len(rng);
  std::vector<physics::RouteSegment> segs;
  double s = 0.0;
  while (s < length) {
    const double e = std::min(length, s + seg_len(rng));
    physics::RouteSegment seg;
    seg.start_m = s;
    seg.end_m = e;
    seg.gradient_permille = std::round(grade(rng) * 10.0) / 10.0;
    seg.speed_limit_ms = units::kmh_to_ms(100.0);
    segs.push_back(seg);
    s = e;
  }
  return physics::Route(std::move(segs), 0.0, 1, "S", "T");
}

// One station run: full traction to v_hi, coast to v_lo, sometimes brake further, repeat.
std::vector<Sample> simulate_run(const physics::Train& truth, std::mt19937_64& rng,
                                 const SyntheticLogOptions& opt) {
  const physics::Route route = random_route(rng, opt);
  const physics::SpeedEnvelope envelope(truth, route, 0.25);
  const physics::Motion motion(truth, route, envelope);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  enum class Phase { Traction, Coast, Brake };
  Phase phase = Phase::Traction;
  double v_hi = 0, v_lo = 0, v_brake = 0;
  auto new_targets = [&]() {
    v_hi = units::kmh_to_ms(45.0 + 30.0 * u01(rng));
    v_lo = units::kmh_to_ms(20.0) + (v_hi - units::kmh_to_ms(35.0)) * u01(rng);
    v_brake = u01(rng) < 0.35
                  ? std::max(units::kmh_to_ms(8.0), v_lo - units::kmh_to_ms(5.0 + 15.0 * u01(rng)))
                  : -1.0;
  };
  new_targets();
  const physics::ControlLaw law = [&](double, double v) {
    switch (phase) {
      case Phase::Traction:
        if (v >= v_hi) phase = Phase::Coast;
        break;
      case Phase::Coast:
        if (v <= v_lo) phase = v_brake > 0.0 ? Phase::Brake : Phase::Traction;
        if (phase == Phase::Traction) new_targets();
        break;
      case Phase::Brake:
        if (v <= v_brake) {
          phase = Phase::Traction;
          new_targets();
        }
        break;
    }
    return phase == Phase::Traction ? physics::Control::MaxTraction
           : phase == Phase::Coast  ? physics::Control::Coast
                                    : physics::Control::MaxBrake;
  };
  physics::SimulationOptions so;
  so.step_m = opt.step_m;
  so.rk_order = 4;
  const physics::SimulationResult sim = physics::simulate(motion, law, {}, so);
  const auto& tr = sim.trace;
  std::vector<Sample> out;
  for (double t = 0.0; t <= tr.back().t_s; t += opt.sample_s) {
    auto it = std::lower_bound(tr.begin(), tr.end(), t,
                               [](const physics::TracePoint& p, double x) { return p.t_s < x; });
    if (it == tr.begin()) ++it;
    if (it == tr.end()) break;
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double w = b.t_s > a.t_s ? (t - a.t_s) / (b.t_s - a.t_s) : 1.0;
    Sample smp;
    smp.t_s = t;
    smp.s_m = a.s_m + w * (b.s_m - a.s_m);
    smp.v_ms = a.v_ms + w * (b.v_ms - a.v_ms);
    smp.force_N = b.force_N;
    smp.gradient = route.at(smp.s_m).gradient_permille;
    out.push_back(smp);
  }
  return out;
}

}  // namespace

SyntheticLog make_synthetic_log(const physics::Train& truth, const SyntheticLogOptions& opt) {
  std::mt19937_64 rng(opt.seed);
  SyntheticLog out;
  Log& log = out.log;
  log.label = "synthetic(seed " + std::to_string(opt.seed) + ")";
  log.format = LogFormat::Plain;
  log.has_position = log.has_gradient = log.has_traction = log.has_braking = true;
  double t0 = 0.0;
  double s0 = 0.0;
  while (static_cast<int>(log.rows.size()) < opt.rows) {
    const std::vector<Sample> run = simulate_run(truth, rng, opt);
    for (const Sample& smp : run) {
      LogRow r;
      r.time_s = t0 + smp.t_s;
      r.speed_ms = smp.v_ms;
      r.position_m = s0 + smp.s_m;
      r.gradient_permille = smp.gradient;
      r.traction_force_N = std::max(smp.force_N, 0.0);
      r.braking_force_N = std::max(-smp.force_N, 0.0);
      log.rows.push_back(r);
    }
    t0 += run.back().t_s;
    s0 += run.back().s_m;
    for (double d = opt.sample_s; d <= opt.dwell_s; d += opt.sample_s) {
      LogRow r;
      r.time_s = t0 + d;
      r.speed_ms = 0.0;
      r.position_m = s0;
      r.gradient_permille = log.rows.back().gradient_permille;
      r.traction_force_N = 0.0;
      r.braking_force_N = 0.0;
      log.rows.push_back(r);
    }
    t0 += opt.dwell_s + opt.sample_s;
  }
  log.rows.resize(static_cast<std::size_t>(opt.rows));
  std::normal_distribution<double> noise(0.0, units::kmh_to_ms(opt.speed_noise_kmh));
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    LogRow& r = log.rows[i];
    r.source_row = static_cast<int>(i) + 2;
    if (r.speed_ms > 0.1) {
      r.speed_ms = std::max(0.0, r.speed_ms + noise(rng));
      if (r.speed_ms > units::kmh_to_ms(10.0)) candidates.push_back(i);
    }
  }
  const auto n_corrupt = static_cast<std::size_t>(
      std::lround(opt.corrupt_fraction * static_cast<double>(log.rows.size())));
  std::shuffle(candidates.begin(), candidates.end(), rng);
  candidates.resize(std::min(candidates.size(), n_corrupt));
  std::sort(candidates.begin(), candidates.end());
  std::uniform_real_distribution<double> size(opt.corrupt_min_kmh, opt.corrupt_max_kmh);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (std::size_t i : candidates) {
    const double d = units::kmh_to_ms(size(rng)) * (u01(rng) < 0.5 ? -1.0 : 1.0);
    log.rows[i].speed_ms = std::max(0.0, log.rows[i].speed_ms + d);
    out.corrupted_rows.push_back(log.rows[i].source_row);
  }
  return out;
}

}  // namespace ecorail::fitting
