#include "recovery/plan_adjustment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::recovery {

bool PlanAdjustmentOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (thetas.empty() || extra_dwells_s.empty())
    return fail("PlanAdjustmentOptions: at least one theta and one extra dwell");
  for (double t : thetas)
    if (!(t >= 0.0 && t <= 1.0)) return fail("--thetas must lie in [0, 1]");
  for (double x : extra_dwells_s)
    if (!(x >= 0.0 && x <= 60.0)) return fail("--extra-dwells must lie in [0, 60] s");
  if (run_early_s.empty()) return fail("PlanAdjustmentOptions: at least one run_early_s");
  for (double b : run_early_s)
    if (!(b >= 0.0 && b <= 600.0)) return fail("--run-early-values must lie in [0, 600] s");
  if (!(max_dwell_s > 0.0 && max_dwell_s <= 600.0))
    return fail("the longest dwell of --adjust must lie in (0, 600] s");
  if (search_days < 2 || search_days > 1000000) return fail("--search-days must lie in [2, 1e6]");
  if (!(target_punctuality >= 0.0 && target_punctuality <= 1.0))
    return fail("--target must lie in [0, 1]");
  if (threads < 0) return fail("--threads must be >= 0");
  return true;
}

std::string PlanAdjustmentSummary::BriefReport() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "plan adjustment: %d candidates, chosen %zu; punctuality target %.4f %s; %s",
                candidates, chosen + 1, target_punctuality, target_met ? "met" : "NOT met",
                std::string(dp::status_word(termination, warnings.size())).c_str());
  return std::string(buf) + "\n";
}

std::string PlanAdjustmentSummary::FullReport() const {
  std::string out = BriefReport();
  for (const std::string& w : warnings) out += "  warning: " + w + "\n";
  return out;
}

void plan_pattern(const Plan& plan, std::vector<double>* running, std::vector<double>* dwells) {
  const std::size_t n = plan.sections();
  running->assign(n, 0.0);
  dwells->assign(n > 0 ? n - 1 : 0, 0.0);
  for (std::size_t j = 0; j < n; ++j) (*running)[j] = plan.running_time_s(0, j);
  for (std::size_t j = 1; j < n; ++j) (*dwells)[j - 1] = plan.dwell_s(0, j);
  for (std::size_t k = 1; k < plan.trains.size(); ++k) {
    for (std::size_t j = 0; j < n; ++j)
      if (std::fabs(plan.running_time_s(k, j) - (*running)[j]) > 1.5e-3 ||
          (j > 0 && std::fabs(plan.dwell_s(k, j) - (*dwells)[j - 1]) > 1.5e-3))
        throw std::invalid_argument("a plan whose trains all run one pattern (train " +
                                    std::to_string(k + 1) + " differs from train 1 at " +
                                    plan.stations[j] + ")");
  }
}

PlanAdjustmentResult adjust_plan(const dp::SectionLibrary& library, const Plan& base,
                                 const MonteCarloOptions& simulation, SectionRuns& runs,
                                 const PlanAdjustmentOptions& options,
                                 const std::function<void(int, int)>& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  std::vector<double> r0, w0;
  plan_pattern(base, &r0, &w0);
  const std::size_t n = base.sections();
  std::vector<double> departures;
  for (const TrainStops& t : base.trains) departures.push_back(t.departure_s[0]);
  PlanAdjustmentResult out;
  const int total = static_cast<int>(options.thetas.size() * options.extra_dwells_s.size() *
                                     options.run_early_s.size());
  for (double extra : options.extra_dwells_s) {
    std::vector<double> w = w0;
    double dwell_change = 0.0;
    for (double& d : w) {
      const double nd = std::max(d, std::min(options.max_dwell_s, d + extra));
      dwell_change += nd - d;
      d = nd;
    }
    double running = -dwell_change;
    for (double r : r0) running += r;
    std::vector<std::size_t> all(n);
    std::vector<double> lo(n), hi(n), opt;
    double min_sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      all[j] = j;
      lo[j] = runs.min_time_s(j);
      hi[j] = runs.max_time_s(j);
      min_sum += lo[j];
    }
    if (running <= min_sum + 1e-6) {
      out.summary.warnings.push_back("extra dwell " + std::to_string(extra) +
                                     " s leaves no running-time margin; skipped");
      continue;
    }
    split_by_price(runs, all, lo, hi, running, opt);
    const double margin = (running - min_sum) / static_cast<double>(n);
    for (double theta : options.thetas) {
      std::vector<double> times;
      double sum_ms = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        const double even = std::min(hi[j], lo[j] + margin);
        const double t = std::round(((1.0 - theta) * opt[j] + theta * even) * 1000.0) / 1000.0;
        times.push_back(t);
        sum_ms += t;
      }
      // Keep the trip time to the millisecond: the rounding goes to the longest section.
      const std::size_t longest =
          static_cast<std::size_t>(std::max_element(times.begin(), times.end()) - times.begin());
      times[longest] = std::round((times[longest] + running - sum_ms) * 1000.0) / 1000.0;
      const Plan plan = plan_from_pattern(base.stations, times, w, departures);
      for (double early : options.run_early_s) {
        PlanCandidate c;
        c.theta = theta;
        c.extra_dwell_s = extra;
        c.run_early_s = early;
        c.dwells_s = w;
        c.running_times_s = times;
        c.plan = plan;
        MonteCarloOptions sim = simulation;
        sim.run_early_s = early;
        const MonteCarlo mc(library, c.plan, sim, runs);
        const DayRecord plan_day = mc.plan_day();
        c.plan_traction_kJ = plan_day.traction_kJ;
        c.plan_substation_kJ = plan_day.substation_kJ;
        const std::vector<DayRecord> days = mc.run_days(0, options.search_days, options.threads);
        c.statistics = summarise(days, pooled_histogram(days));
        c.meets_target = c.statistics.punctuality.mean >= options.target_punctuality;
        out.candidates.push_back(std::move(c));
        if (progress) progress(static_cast<int>(out.candidates.size()), total);
      }
    }
  }
  if (out.candidates.empty())
    throw std::invalid_argument("no candidate plan has running-time margin");
  PlanAdjustmentSummary& s = out.summary;
  s.candidates = static_cast<int>(out.candidates.size());
  s.target_punctuality = options.target_punctuality;
  bool any = false;
  for (std::size_t i = 0; i < out.candidates.size(); ++i) {
    const PlanCandidate& c = out.candidates[i];
    if (c.meets_target && (!any || c.statistics.substation_kJ.mean <
                                       out.candidates[s.chosen].statistics.substation_kJ.mean)) {
      s.chosen = i;
      any = true;
    }
  }
  s.target_met = any;
  if (!any) {
    for (std::size_t i = 0; i < out.candidates.size(); ++i)
      if (out.candidates[i].statistics.punctuality.mean >
          out.candidates[s.chosen].statistics.punctuality.mean)
        s.chosen = i;
    s.warnings.push_back(
        "no candidate reaches the punctuality target; the most punctual is chosen");
  }
  s.termination = dp::Termination::CONVERGENCE;
  return out;
}

}  // namespace ecorail::recovery
