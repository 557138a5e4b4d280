// Clock-dependent headway classes (question 2.2). A headway h_k = t_{k+1} - t_k is a peak
// headway when its open interval (t_k, t_{k+1}) overlaps a peak window (from, to), and then lies
// in the peak range (120-150 s by default); every other headway lies in the off-peak range (the
// problem's headway_min_s..headway_max_s, 300-660 s). The class of a headway depends on where it
// sits on the clock, not on its index, so whether any timetable exists is a reachability
// question over (headways so far, clock time): WindowedReach answers it exactly, once, and the
// windowed DP (windowed_dp.hpp) runs on the states it keeps. When no timetable exists, the error
// says how many peak headways each window needs and how many headways the span can hold at all.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fleet/fleet_problem.hpp"

namespace ecorail::fleet {

// Whether the open interval (from_s, to_s) overlaps one of the windows.
bool is_peak_headway(const std::vector<PeakWindow>& windows, int from_s, int to_s);

// For a train departing at t_s: the longest headway that stays off-peak (0 inside a window; a
// large number after the last window). Windows sorted and disjoint.
int offpeak_reach_s(const std::vector<PeakWindow>& windows, int t_s);

// Exact reachability: keeps[k][t] says whether a timetable can have its (k+1)-th departure at
// clock time t and still reach the span with the remaining headways, every headway in its
// class.
class WindowedReach {
 public:
  explicit WindowedReach(const FleetProblem& problem);
  bool feasible() const { return feasible_; }
  bool keeps(int k, int t_s) const { return alive_[k][t_s] != 0; }
  // The allowed headways from a departure at t_s: [off_lo, off_hi] off-peak and [peak_lo,
  // peak_hi] peak (an empty range has lo > hi).
  struct Ranges {
    int off_lo, off_hi, peak_lo, peak_hi;
  };
  Ranges ranges(int t_s) const;

 private:
  const FleetProblem* problem_;
  std::vector<std::vector<std::uint8_t>> alive_;  // backward reachable, per headway count
  bool feasible_ = false;
};

// Fewest and most headways that can fill [0, span] with every headway in its class (-1, -1 when
// none can).
std::pair<int, int> windowed_headway_count_range(const FleetProblem& problem);

// FleetProblem::IsValid for a windowed problem: fields, windows sorted and disjoint, and that a
// timetable exists (else a sentence with each window's need and the count range).
bool windowed_problem_valid(const FleetProblem& problem, std::string* error);
// Why the departures break a windowed problem's rules ("" when they keep them).
std::string windowed_departures_problem(const FleetProblem& problem,
                                        const std::vector<int>& departures_s);
// The uniform timetable under the classes: the least sum of squared headways (for the fixed
// span, the least variance), i.e. the most even service the classes allow: within each class
// the headways differ by as little as whole seconds and the windows' edges permit, peak
// headways as long and off-peak ones as short as the count of trains allows. Throws
// std::invalid_argument when no timetable exists.
std::vector<int> windowed_uniform_headways(const FleetProblem& problem);

// The timetable nearest to given class headways (least sum of squared deviations of each
// headway from its class's target), e.g. a published answer whose departures do not keep the
// classes exactly: peak 149 s and off-peak 331.5 s (331/332 s) for the contest paper's 2.2.
std::vector<int> windowed_nearest_headways(const FleetProblem& problem, double peak_target_s,
                                           double offpeak_target_s);

}  // namespace ecorail::fleet
