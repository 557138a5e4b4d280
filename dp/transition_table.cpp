#include "dp/transition_table.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>

namespace ecorail::dp {

namespace {

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
  table_.resize(static_cast<std::size_t>(grid.offset(last)) * physics::kControlCount);
  auto fill = [&](int node, int i, int c, const physics::Advance& adv) {
    Transition& t = table_[static_cast<std::size_t>(node) * physics::kControlCount + c];
    if (adv.stalled) {
      t = {0.0, 0.0, 0.0, -1};
      return;
    }
    t.energy_J = energy_cost_J(objective, motion.train(), adv.traction_work_J, adv.brake_work_J,
                               adv.traction_input_J, adv.regen_J);
    t.time_s = adv.time_s;
    grid.locate(i + 1, physics::speed_from_e(adv.e_end), &t.lower, &t.weight);
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
                                                   physics::kControlCount);
  std::vector<int> class_of_entry(class_offset.back());
  for (std::size_t k = 0; k < representative.size(); ++k) {
    for (long n = class_offset[k]; n < class_offset[k + 1]; ++n) {
      class_of_entry[n] = static_cast<int>(k);
    }
  }
  const long shared_total = class_offset.back();
#pragma omp parallel for schedule(dynamic, 16)
  for (long n = 0; n < shared_total; ++n) {
    const int k = class_of_entry[n];
    const int i = representative[k];
    const double v = grid.dv_ms() * static_cast<double>(n - class_offset[k]);
    for (int c = 0; c < physics::kControlCount; ++c) {
      shared[static_cast<std::size_t>(n) * physics::kControlCount + c] =
          motion.advance_unsupervised(grid.position(i), 0.5 * v * v, grid.position(i + 1),
                                      static_cast<physics::Control>(c), step);
    }
  }
  stage_classes_ = static_cast<int>(representative.size());
  class_integrations_ = shared_total * physics::kControlCount;

  // Every stage: a shared transition where it is valid there, its own integration elsewhere.
  long own = 0, used = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : own, used)
  for (int i = 0; i < last; ++i) {
    const int k = class_of[i];
    const bool shares = k >= 0 && members[k] > 1;
    for (int j = 0; j < grid.node_count(i); ++j) {
      const int node = grid.offset(i) + j;
      const double v = grid.speed(i, j);
      for (int c = 0; c < physics::kControlCount; ++c) {
        if (shares && j < grid.node_count(i) - 1) {
          const physics::Motion::FreeAdvance& f =
              shared[static_cast<std::size_t>(class_offset[k] + j) * physics::kControlCount + c];
          if (!f.stopped && f.e_max <= envelope_min[i]) {
            fill(node, i, c, f.advance);
            ++used;
            continue;
          }
        }
        fill(node, i, c,
             motion.advance(grid.position(i), 0.5 * v * v, grid.position(i + 1),
                            static_cast<physics::Control>(c), step));
        ++own;
      }
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
    const int next_begin = grid.offset(i + 1);
    const int next_count = grid.node_count(i + 1);
    for (int c = 0; c < deps_.chunks(i); ++c) {
      int lo = next_count, hi = -1;
      const int end = std::min(begin + grid.node_count(i), begin + (c + 1) * kSweepChunk);
      for (int node = begin + c * kSweepChunk; node < end; ++node) {
        for (int k = 0; k < physics::kControlCount; ++k) {
          const Transition& t = at(node, static_cast<physics::Control>(k));
          if (t.lower < 0) continue;
          const int local = t.lower - next_begin;
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

}  // namespace ecorail::dp
