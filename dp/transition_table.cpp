#include "dp/transition_table.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>

namespace ecorail::dp {

namespace {

// A stop this far short of a stage's end is a stall at every stage (Motion's test is 1 mm).
constexpr double kStallMargin_m = 1e-3 + 1e-6;

// The bits of a double, so alike stages are alike to the last bit (and -0.0 is not 0.0).
std::uint64_t bits_of(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// What an integration from s0 to s1 depends on besides the start state and the envelope: the
// substeps as Motion::advance splits them (length, track resistance, tunnel drag). Also the
// smallest envelope at the substep ends (where Motion::substep supervises it).
std::vector<std::uint64_t> stage_key(const physics::Motion& motion, double s0, double s1,
                                     const physics::StepSettings& step, double* envelope_min) {
  std::vector<std::uint64_t> key;
  *envelope_min = std::numeric_limits<double>::infinity();
  double s = s0;
  while (s < s1 - 1e-9) {
    const physics::RouteSegment& seg = motion.route().at(s);
    const double next = std::min({s1, seg.end_m, s + step.max_substep_m});
    const double h = next - s;
    key.push_back(bits_of(h));
    key.push_back(bits_of(seg.track_N_per_kN()));
    key.push_back(bits_of(seg.tunnel_drag_N_per_kN_kmh2));
    *envelope_min = std::min(*envelope_min, motion.envelope().e_at(s + h));
    s = next;
  }
  return key;
}

}  // namespace

TransitionTable::TransitionTable(const physics::Motion& motion, const StageGrid& grid,
                                 Objective objective, const physics::StepSettings& step,
                                 bool share) {
  const int last = grid.stage_count() - 1;
  constexpr int K = physics::kControlCount;
  stage_offset_.resize(grid.stage_count());
  for (int i = 0; i < grid.stage_count(); ++i) stage_offset_[i] = grid.offset(i);
  constexpr Transition kInfeasibleEntry{0.0, 0.0, 0.0, -1};
  // An integration's cost and time; its end is located by the caller.
  auto priced = [&](const physics::Advance& adv) {
    Transition t;
    t.energy_J = energy_cost_J(objective, motion.train(), adv.traction_work_J, adv.brake_work_J,
                               adv.traction_input_J, adv.regen_J);
    t.time_s = adv.time_s;
    return t;
  };
  // An entry from an integration out of stage i; its lower node counted on stage i + 1.
  auto entry_of = [&](int i, const physics::Advance& adv) {
    if (adv.stalled) return kInfeasibleEntry;
    Transition t = priced(adv);
    grid.locate(i + 1, physics::speed_from_e(adv.e_end), &t.lower, &t.weight);
    t.lower -= grid.offset(i + 1);
    return t;
  };

  // Classes of alike stages; a class of one stage is integrated stage by stage.
  std::vector<int> class_of(std::max(0, last), -1);
  std::vector<double> envelope_min(std::max(0, last), 0.0);
  std::vector<int> representative, members, uniform_max;
  if (share) {
    std::map<std::vector<std::uint64_t>, int> classes;
    for (int i = 0; i < last; ++i) {
      auto [it, added] = classes.emplace(
          stage_key(motion, grid.position(i), grid.position(i + 1), step, &envelope_min[i]),
          static_cast<int>(representative.size()));
      if (added) {
        representative.push_back(i);
        members.push_back(0);
        uniform_max.push_back(0);
      }
      class_of[i] = it->second;
      ++members[it->second];
      // Every node but the top one is uniform (speed j dv, the same at every stage).
      uniform_max[it->second] = std::max(uniform_max[it->second], grid.node_count(i) - 1);
    }
  }
  // Each shared class's transitions from the uniform speeds, integrated once.
  std::vector<long> class_offset(representative.size() + 1, 0);
  for (std::size_t k = 0; k < representative.size(); ++k) {
    class_offset[k + 1] = class_offset[k] + (members[k] > 1 ? uniform_max[k] : 0);
  }
  std::vector<physics::Motion::FreeAdvance> shared(static_cast<std::size_t>(class_offset.back()) *
                                                   K);
  std::vector<int> class_of_entry(class_offset.back());
  for (std::size_t k = 0; k < representative.size(); ++k) {
    for (long n = class_offset[k]; n < class_offset[k + 1]; ++n) {
      class_of_entry[n] = static_cast<int>(k);
    }
  }
  const long shared_total = class_offset.back();
  // A transition that stops well short of its stage's end (a brake from a crawl) is infeasible
  // at every stage of its class: the stall is the same comparison of the same substeps, a
  // millimetre from the end, and only a stop within rounding of that millimetre could differ.
  auto stalls_everywhere = [](const physics::Motion::FreeAdvance& f) {
    return f.stopped && f.advance.stalled && f.stop_short_of_end_m > kStallMargin_m;
  };
  // The class's rows: each entry located among the uniform speeds (a stage reads it only where
  // its own locate gives the same, below).
  class_rows_.resize(static_cast<std::size_t>(shared_total) * K);
  const double dv = grid.dv_ms();
#pragma omp parallel for schedule(dynamic, 16)
  for (long n = 0; n < shared_total; ++n) {
    const int k = class_of_entry[n];
    const int i = representative[k];
    const double v = dv * static_cast<double>(n - class_offset[k]);
    for (int c = 0; c < K; ++c) {
      const std::size_t e = static_cast<std::size_t>(n) * K + c;
      shared[e] = motion.advance_unsupervised(grid.position(i), 0.5 * v * v, grid.position(i + 1),
                                              static_cast<physics::Control>(c), step);
      const physics::Advance& adv = shared[e].advance;
      Transition& t = class_rows_[e];
      if (adv.stalled || (shared[e].stopped && !stalls_everywhere(shared[e]))) {
        t = kInfeasibleEntry;
        continue;
      }
      t = priced(adv);
      grid.uniform_position(physics::speed_from_e(adv.e_end), &t.lower, &t.weight);
    }
  }
  stage_classes_ = static_cast<int>(representative.size());
  class_integrations_ = shared_total * K;

  // Each stage: the nodes whose every transition is the class's (the envelope cannot bend it,
  // it does not stop, and its end lies between uniform nodes of the next stage) read the
  // class's rows; the longest run of them is shared, and the other nodes get their own rows.
  rows_.resize(std::max(0, last));
  auto class_entry = [&](int i, int j, int c) -> const physics::Motion::FreeAdvance* {
    const int k = class_of[i];
    if (k < 0 || members[k] < 2 || j >= grid.node_count(i) - 1) return nullptr;
    const physics::Motion::FreeAdvance& f =
        shared[static_cast<std::size_t>(class_offset[k] + j) * K + c];
    return (!f.stopped || stalls_everywhere(f)) && f.e_max <= envelope_min[i] ? &f : nullptr;
  };
#pragma omp parallel for schedule(dynamic, 16)
  for (int i = 0; i < last; ++i) {
    StageRows& r = rows_[i];
    const int k = class_of[i];
    if (k < 0 || members[k] < 2) continue;
    r.class_row = class_offset[k];
    int run_from = 0, run_length = 0;
    for (int j = 0, from = 0; j <= grid.node_count(i); ++j) {
      bool whole = j < grid.node_count(i);
      for (int c = 0; c < K && whole; ++c) {
        const physics::Motion::FreeAdvance* f = class_entry(i, j, c);
        whole = f != nullptr &&
                (f->advance.stalled ||
                 grid.locates_uniformly(i + 1, physics::speed_from_e(f->advance.e_end)));
      }
      if (whole) continue;
      if (j - from > run_length) run_from = from, run_length = j - from;
      from = j + 1;
    }
    r.shared_from = run_from;
    r.shared_to = run_from + run_length;
  }
  long own_total = 0;
  for (int i = 0; i < last; ++i) {
    rows_[i].own_row = own_total;
    own_total += grid.node_count(i) - (rows_[i].shared_to - rows_[i].shared_from);
  }
  own_rows_.resize(static_cast<std::size_t>(own_total) * K);
  // The stages' own rows: a transition the class holds taken from it, the others integrated.
  long own = 0, used = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : own, used)
  for (int i = 0; i < last; ++i) {
    const StageRows& r = rows_[i];
    used += static_cast<long>(r.shared_to - r.shared_from) * K;
    long row = r.own_row;
    for (int j = 0; j < grid.node_count(i); ++j) {
      if (j >= r.shared_from && j < r.shared_to) continue;
      const double v = grid.speed(i, j);
      for (int c = 0; c < K; ++c) {
        Transition& t = own_rows_[static_cast<std::size_t>(row) * K + c];
        if (const physics::Motion::FreeAdvance* f = class_entry(i, j, c)) {
          t = entry_of(i, f->advance);
          ++used;
          continue;
        }
        t = entry_of(i, motion.advance(grid.position(i), 0.5 * v * v, grid.position(i + 1),
                                       static_cast<physics::Control>(c), step));
        ++own;
      }
      ++row;
    }
  }
  stage_integrations_ = own;
  shared_entries_ = used;
  // Dependency ranges of the sweep's chunks: the next-stage chunks any transition lands in.
  deps_.chunk_offset.assign(1, 0);
  for (int i = 0; i <= last; ++i) {
    const int chunks = (grid.node_count(i) + kSweepChunk - 1) / kSweepChunk;
    deps_.chunk_offset.push_back(deps_.chunk_offset.back() + chunks);
  }
  deps_.first.assign(deps_.chunk_offset.back(), 0);
  deps_.last.assign(deps_.chunk_offset.back(), -1);
  for (int i = 0; i < last; ++i) {
    const int begin = grid.offset(i);
    const int next_count = grid.node_count(i + 1);
    for (int c = 0; c < deps_.chunks(i); ++c) {
      int lo = next_count, hi = -1;
      const int end = std::min(begin + grid.node_count(i), begin + (c + 1) * kSweepChunk);
      for (int node = begin + c * kSweepChunk; node < end; ++node) {
        const Transition* out = row(i, node - begin);
        for (int k = 0; k < K; ++k) {
          const Transition& t = out[k];
          if (t.lower < 0) continue;
          const int local = t.lower;
          lo = std::min(lo, local);
          hi = std::max(hi, std::min(local + 1, next_count - 1));
        }
      }
      const int g = deps_.chunk_offset[i] + c;
      deps_.first[g] = hi < 0 ? 0 : lo / kSweepChunk;
      deps_.last[g] = hi < 0 ? -1 : hi / kSweepChunk;
    }
  }
}

Transition TransitionTable::at(int node, physics::Control c) const {
  const int i =
      static_cast<int>(std::upper_bound(stage_offset_.begin(), stage_offset_.end(), node) -
                       stage_offset_.begin() - 1);
  Transition t = row(i, node - stage_offset_[i])[static_cast<int>(c)];
  if (t.lower >= 0) t.lower += stage_offset_[i + 1];
  return t;
}

}  // namespace ecorail::dp
