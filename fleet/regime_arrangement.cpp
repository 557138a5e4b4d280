#include "fleet/regime_arrangement.hpp"

#include <omp.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "fleet/windowed_classes.hpp"

namespace ecorail::fleet {

bool RegimeArrangementOptions::IsValid(std::string* why) const {
  const auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (max_rounds < 0) return fail("regime arrangement: max_rounds must be >= 0");
  if (threads < 0) return fail("regime arrangement: threads must be >= 0 (0: OpenMP's default)");
  return true;
}

namespace {

// In a stretch of more than this many runs each run moves only to the stretch's two ends (the
// candidates grow with the square of the runs).
constexpr int kRunsForAllPlaces = 12;

struct Candidate {
  std::vector<int> headways_s, labels;
  int stretch = 0;
};

// [begin, end) headway ranges of one class each.
std::vector<std::pair<int, int>> stretches_of(const FleetProblem& p,
                                              const std::vector<int>& headways_s) {
  const std::vector<int> d = departures_from_headways(headways_s);
  std::vector<std::pair<int, int>> out;
  const int n = static_cast<int>(headways_s.size());
  const auto peak = [&](int k) {
    return p.windowed() && is_peak_headway(p.peak_windows, d[k], d[k + 1]);
  };
  for (int b = 0; b < n;) {
    int e = b + 1;
    while (e < n && peak(e) == peak(b)) ++e;
    out.push_back({b, e});
    b = e;
  }
  return out;
}

// Every reordering of one stretch's runs by one move or one phase swap.
void add_candidates(const std::vector<int>& h, const std::vector<int>& label, int b, int e,
                    int stretch, std::vector<Candidate>& out) {
  std::vector<std::pair<int, int>> runs;  // [first, end) within h
  for (int k = b; k < e;) {
    int f = k + 1;
    while (f < e && label[f] == label[k]) ++f;
    runs.push_back({k, f});
    k = f;
  }
  const int m = static_cast<int>(runs.size());
  const auto build = [&](const std::vector<int>& order, int swapped_run) {
    Candidate c{std::vector<int>(h.begin(), h.begin() + b),
                std::vector<int>(label.begin(), label.begin() + b), stretch};
    for (int r : order) {
      const auto [first, end] = runs[r];
      for (int k = first; k < end; ++k) {
        // A phase swap takes each headway's partner in its alternating run.
        const int from = r == swapped_run ? ((k - first) % 2 == 0 ? k + 1 : k - 1) : k;
        c.headways_s.push_back(h[from]);
        c.labels.push_back(label[from]);
      }
    }
    c.headways_s.insert(c.headways_s.end(), h.begin() + e, h.end());
    c.labels.insert(c.labels.end(), label.begin() + e, label.end());
    out.push_back(std::move(c));
  };
  std::vector<int> identity(m);
  for (int r = 0; r < m; ++r) identity[r] = r;
  const bool all_places = m <= kRunsForAllPlaces;
  for (int i = 0; i < m; ++i) {
    std::vector<int> rest = identity;
    rest.erase(rest.begin() + i);
    for (int j = 0; j <= m - 1; ++j) {
      if (j == i) continue;  // back where it was
      // The swap with the run before, which that run's move one place on makes too (when it
      // may move there).
      if (j == i - 1 && (all_places || i == m - 1)) continue;
      if (!all_places && j != 0 && j != m - 1) continue;
      std::vector<int> order = rest;
      order.insert(order.begin() + j, i);
      build(order, -1);
    }
  }
  for (int r = 0; r < m; ++r) {
    const auto [first, end] = runs[r];
    const int len = end - first;
    if (len < 2 || len % 2 != 0 || h[first] == h[first + 1]) continue;
    bool alternating = true;
    for (int k = first; k < end; ++k) alternating &= h[k] == h[first + (k - first) % 2];
    if (alternating) build(identity, r);
  }
}

}  // namespace

RegimeArrangement arrange_regime_runs(const energy::FleetEnergyModel& model, const FleetProblem& p,
                                      const std::vector<int>& headways_s,
                                      const std::vector<int>& run_of_headway,
                                      const RegimeArrangementOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  if (run_of_headway.size() != headways_s.size())
    throw std::invalid_argument("regime arrangement: one run label per headway expected");
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const auto used_of = [&](const std::vector<int>& h) {
    const std::vector<int> d = departures_from_headways(h);
    return departures_problem(p, d).empty() ? model.evaluate(d).total.used_regen_J : -1.0;
  };
  RegimeArrangement out;
  out.headways_s = headways_s;
  std::vector<int> labels = run_of_headway;
  const std::string problem = departures_problem(p, departures_from_headways(headways_s));
  if (!problem.empty()) throw std::invalid_argument("regime arrangement: the start: " + problem);
  out.start_used_J = out.used_J = used_of(headways_s);
  out.evaluations = 1;
  for (int round = 0; round < options.max_rounds && !(options.stop && options.stop()); ++round) {
    std::vector<Candidate> candidates;
    const std::vector<std::pair<int, int>> st = stretches_of(p, out.headways_s);
    for (std::size_t s = 0; s < st.size(); ++s)
      add_candidates(out.headways_s, labels, st[s].first, st[s].second, static_cast<int>(s),
                     candidates);
    std::vector<double> used(candidates.size(), -1.0);
    // Each candidate is priced on its own: the order of evaluation does not matter.
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < static_cast<long>(candidates.size()); ++i)
      used[i] = used_of(candidates[i].headways_s);
    out.evaluations += static_cast<long>(candidates.size());
    // The best gain of each stretch (ties: the first candidate).
    std::vector<long> best_of(st.size(), -1);
    long best = -1;
    for (long i = 0; i < static_cast<long>(candidates.size()); ++i) {
      if (used[i] <= out.used_J) continue;
      long& b = best_of[candidates[i].stretch];
      if (b < 0 || used[i] > used[b]) b = i;
      if (best < 0 || used[i] > used[best]) best = i;
    }
    if (best < 0) break;
    // The stretches' best moves together (stretches far apart hardly interact); kept only
    // when that beats the single best move.
    std::vector<int> joint = out.headways_s, joint_labels = labels;
    int gaining = 0;
    for (std::size_t s = 0; s < st.size(); ++s) {
      if (best_of[s] < 0) continue;
      ++gaining;
      const Candidate& c = candidates[best_of[s]];
      std::copy(c.headways_s.begin() + st[s].first, c.headways_s.begin() + st[s].second,
                joint.begin() + st[s].first);
      std::copy(c.labels.begin() + st[s].first, c.labels.begin() + st[s].second,
                joint_labels.begin() + st[s].first);
    }
    double joint_used = -1.0;
    if (gaining > 1) joint_used = used_of(joint), ++out.evaluations;
    if (joint_used > used[best]) {
      out.headways_s = std::move(joint), labels = std::move(joint_labels), out.used_J = joint_used;
    } else {
      out.headways_s = candidates[best].headways_s;
      labels = candidates[best].labels;
      out.used_J = used[best];
    }
    ++out.rounds;
  }
  out.run_of_headway = std::move(labels);
  return out;
}

}  // namespace ecorail::fleet
