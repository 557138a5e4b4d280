// Benchmarks of calibration (docs/calibration.md quotes them): one synthetic log of 10 000 rows
// (0.2 km/h noise, 2 % corrupted rows) calibrated by equation error, by output error and by
// both, as `ecorail calibrate` runs them; and the envelope fit of 161 points.
#include <benchmark/benchmark.h>

#include <map>

#include "data/train_io.hpp"
#include "fitting/calibration.hpp"
#include "fitting/envelope_fit.hpp"
#include "fitting/synthetic_log.hpp"

namespace {

using namespace ecorail;

const fitting::Log& log_of(int rows) {
  static std::map<int, fitting::Log> cache;
  auto it = cache.find(rows);
  if (it == cache.end()) {
    physics::Train truth = data::default_train();
    truth.davis.A = 2.6;
    truth.davis.B = 0.045;
    truth.davis.C = 0.0021;
    truth.rotating_mass_factor = 0.08;
    fitting::SyntheticLogOptions o;
    o.rows = rows;
    o.corrupt_fraction = 0.02;
    o.seed = 42;
    it = cache.emplace(rows, fitting::make_synthetic_log(truth, o).log).first;
  }
  return it->second;
}

void calibrate_with(benchmark::State& state, fitting::Method method) {
  const fitting::Log& log = log_of(static_cast<int>(state.range(0)));
  const physics::Train base = data::default_train();
  fitting::CalibrationOptions o;
  o.method = method;
  for (auto _ : state) {
    const fitting::Summary s = fitting::calibrate({log}, base, o);
    benchmark::DoNotOptimize(s.results.back().params[fitting::kDavisA].value);
  }
  state.counters["rows"] = static_cast<double>(log.rows.size());
}

void BM_CalibrateEquationError(benchmark::State& state) {
  calibrate_with(state, fitting::Method::EquationError);
}
void BM_CalibrateOutputError(benchmark::State& state) {
  calibrate_with(state, fitting::Method::OutputError);
}
void BM_CalibrateBoth(benchmark::State& state) {
  calibrate_with(state, fitting::Method::Both);
}

BENCHMARK(BM_CalibrateEquationError)->Arg(2000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CalibrateOutputError)->Arg(2000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CalibrateBoth)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_FitEnvelope(benchmark::State& state) {
  const physics::Train ref = data::default_train();
  std::vector<fitting::EnvelopePoint> pts;
  for (double v = 0.0; v <= 80.0 + 1e-9; v += 0.5) {
    pts.push_back({v, ref.traction.force_kN_at_kmh(v), 0});
  }
  for (auto _ : state) {
    const auto r = fitting::fit_envelope(pts, fitting::EnvelopeFitOptions{});
    benchmark::DoNotOptimize(r.piecewise.breakpoint_kmh);
  }
}
BENCHMARK(BM_FitEnvelope)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
