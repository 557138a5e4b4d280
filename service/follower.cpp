#include "service/follower.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ecorail::service {

namespace {

// A held-up follower's wait is rounded up by this much (and then to 0.01 s), so that the
// sampled check is met with room to spare rather than to the last bit.
constexpr double kWaitMargin_s = 0.05;
// A candidate that drives under the cap replaces the wait only when it arrives this much earlier.
constexpr double kEarlierBy_s = 0.05;
// Waits and faster runs tried in turn (each faster run may need a longer wait).
constexpr int kFasterTries = 4;

// The clock time from which the leader is at or beyond position_m for good: when it first
// reaches it, or its arrival when the position lies at or past the end of its run (it then
// leaves the line).
double leader_clear_at(const physics::Trip& leader, double position_m) {
  const double length = leader.length_m();
  if (position_m >= length) return leader.arrival_s();
  return leader.time_at(std::max(0.0, position_m));
}

// The least wait before leaving at start_s for which `run` (a section's run from rest, its own
// clock from 0) keeps gap >= v^2 / 2b behind the leader at every trace point and at the start.
double clearance_wait_s(const physics::Trip& leader, const physics::SimulationResult& run,
                        double section_start_m, double start_s, double b, double room_m) {
  double need = leader_clear_at(leader, section_start_m + room_m) - start_s;
  for (const physics::TracePoint& p : run.trace) {
    const double ahead = section_start_m + p.s_m + room_m + p.v_ms * p.v_ms / (2.0 * b);
    need = std::max(need, leader_clear_at(leader, ahead) - (start_s + p.t_s));
  }
  return std::max(0.0, need);
}

// The least distance margin (gap - v^2 / 2b) of a section run leaving at start_s.
double section_distance_margin_m(const physics::Trip& leader, const physics::SimulationResult& run,
                                 double section_start_m, double start_s, double b, double room_m) {
  const LeaderTrack track(leader);
  double least = 1e300;
  for (const physics::TracePoint& p : run.trace) {
    const double lead = track.position_m(start_s + p.t_s);
    if (!std::isfinite(lead)) break;
    least = std::min(least, lead - room_m - (section_start_m + p.s_m) - p.v_ms * p.v_ms / (2 * b));
  }
  return least;
}

bool arrives(const physics::SimulationResult& sim) {
  return dp::run_arrives(sim) && !sim.stopped_early;
}

// The sections of a held-up follower given a recovery: at every stop it leaves when it is ready
// (its planned departure, or its arrival plus the least dwell when late) and the line ahead is
// clear for the run it drives, that run being the recovery's for the departure (its plan when
// on time). A run chosen for a later departure is faster and may need a longer wait, so the two
// are iterated; the run finally driven always leaves no earlier than its own least wait.
void drive_recovering(const dp::SectionLibrary& library, const ServicePlan& plan,
                      const physics::Trip& leader, const physics::Trip& planned, double b,
                      double room, int train, const FollowerRecovery& recovery,
                      std::vector<physics::SimulationResult>& sims,
                      std::vector<double>& dwell_after, double& trip_departure,
                      FollowerRun& out, std::vector<CapEvent>* events) {
  const std::size_t n = library.size();
  double start = trip_departure;
  auto pick = [&](std::size_t i, double departure) {
    const physics::SimulationResult* r = recovery.run(i, departure);
    return r != nullptr ? r : &plan.runs[i];
  };
  auto rounded = [](double w) { return std::ceil((w + kWaitMargin_s) * 100.0) / 100.0; };
  for (std::size_t i = 0; i < n; ++i) {
    const double section_start = plan.trip.section_start_m(i);
    const double planned_arrival = planned.stop(i + 1).arrival_s;
    // Candidates: the run for leaving when ready, then, while that run must wait, the run for
    // leaving after the wait (faster, so it may need a longer wait), and the planned run with
    // its own wait. Each leaves no earlier than its own least wait. The earliest arrival is
    // driven (lateness first), the least energy among arrivals within kEarlierBy_s of it.
    struct Candidate {
      const physics::SimulationResult* run;
      double departure_s;
    };
    std::vector<Candidate> candidates;
    auto add = [&](const physics::SimulationResult* r) {
      for (const Candidate& c : candidates)
        if (c.run == r) return false;
      const double w = clearance_wait_s(leader, *r, section_start, start, b, room);
      candidates.push_back({r, w > 0.0 ? start + rounded(w) : start});
      return true;
    };
    const physics::SimulationResult* tried = pick(i, start);
    for (int it = 0; it <= kFasterTries && add(tried); ++it) {
      if (candidates.back().departure_s <= start) break;
      tried = pick(i, candidates.back().departure_s);
    }
    add(&plan.runs[i]);
    auto earliest_arrival = [&] {
      double a = 1e300;
      for (const Candidate& c : candidates) a = std::min(a, c.departure_s + c.run->running_time_s);
      return a;
    };
    // Where the train ahead sets that arrival, leaving when ready and running slower for it
    // costs less: tried too (it may need a wait of its own, and is then later).
    double earliest = earliest_arrival();
    if (recovery.run_in) {
      const physics::SimulationResult* slower = recovery.run_in(i, earliest - start);
      if (slower != nullptr && slower->running_time_s > kEarlierBy_s) add(slower);
      earliest = earliest_arrival();
    }
    const physics::SimulationResult* run = nullptr;
    double departure = start, least_cost = 1e300;
    for (const Candidate& c : candidates) {
      if (c.departure_s + c.run->running_time_s > earliest + kEarlierBy_s) continue;
      const double cost = c.run->energy.traction_work_J;
      if (run == nullptr || cost < least_cost) {
        run = c.run;
        departure = c.departure_s;
        least_cost = cost;
      }
    }
    const double wait = departure - start;
    if (wait > 0.0 || run != &plan.runs[i]) {
      ++out.sections_redriven;
      if (events != nullptr) {
        CapEvent ev;
        ev.train = train;
        ev.section = static_cast<int>(i);
        ev.planned_cost_J = library.engine(i).energy_cost_J(plan.runs[i]);
        ev.supervised_cost_J = NAN;
        ev.reoptimised_cost_J = library.engine(i).energy_cost_J(*run);
        ev.reoptimised_wait_s = wait;
        ev.station_wait_s = wait;
        ev.waited_late_s = start + wait + plan.runs[i].running_time_s - planned_arrival;
        ev.driven = run == &plan.runs[i] ? "waited" : wait > 0.0 ? "waited, then recovered"
                                                                 : "recovered";
        ev.late_s = departure + run->running_time_s - planned_arrival;
        ev.reoptimised_late_s = ev.late_s;
        events->push_back(ev);
      }
    }
    out.station_wait_s += wait;
    if (i == 0)
      trip_departure = departure;
    else
      dwell_after[i - 1] += wait;
    sims[i] = *run;
    const double arrival = departure + sims[i].running_time_s;
    out.late_s[i + 1] = arrival - planned_arrival;
    if (i + 1 < n) {
      const double least_dwell =
          std::min(plan.dwells_s[i], i + 1 < recovery.min_dwell_s.size()
                                         ? recovery.min_dwell_s[i + 1]
                                         : plan.dwells_s[i]);
      const double next = std::max(planned.stop(i + 1).departure_s, arrival + least_dwell);
      dwell_after[i] = next - arrival;
      start = next;
    }
  }
}

}  // namespace

bool keeps_separation(const SeparationScan& scan) {
  return scan.min_distance_margin_m >= -kDistanceMarginTolerance_m &&
         scan.min_gap_m >= -kDistanceMarginTolerance_m;
}

FollowerRun drive_follower(const dp::SectionLibrary& library, const ServicePlan& plan,
                           const physics::Trip& leader, double departure_s,
                           const ServiceOptions& options, double b, int train,
                           std::vector<CapEvent>* events, const FollowerRecovery* recovery) {
  if (!(b > 0.0)) throw std::invalid_argument("the separation braking must be positive");
  const std::size_t n = library.size();
  const double room = options.separation.train_length_m + options.separation.safety_margin_m;
  const physics::Trip planned = plan.trip.shifted(departure_s);
  FollowerRun out;
  out.planned_scan = scan_separation(leader, planned, b, options.separation);
  const SeparationScan& before = out.planned_scan;
  out.held_up = before.exceeded || before.min_distance_margin_m < 0.0 || before.min_gap_m < 0.0;
  for (const physics::SimulationResult& r : plan.runs) out.plan_traction_J += r.energy.traction_work_J;
  if (!out.held_up) {
    out.traction_J = out.plan_traction_J;
    out.trip = planned;
    out.scan = before;
    out.late_s.assign(n + 1, 0.0);
    return out;
  }
  std::vector<physics::SimulationResult> sims(n);
  std::vector<double> dwell_after(n, 0.0);
  double trip_departure = departure_s, start = departure_s;
  out.late_s.assign(n + 1, 0.0);
  const bool recovering = recovery != nullptr && static_cast<bool>(recovery->run);
  if (recovering)
    drive_recovering(library, plan, leader, planned, b, room, train, *recovery, sims, dwell_after,
                     trip_departure, out, events);
  for (std::size_t i = 0; !recovering && i < n; ++i) {
    const dp::SectionEngine& engine = library.engine(i);
    const double section_start = plan.trip.section_start_m(i);
    const double planned_arrival = planned.stop(i + 1).arrival_s;
    double wait = clearance_wait_s(leader, plan.runs[i], section_start, start, b, room);
    physics::SimulationResult run = plan.runs[i];
    if (wait > 0.0) {
      wait = std::ceil((wait + kWaitMargin_s) * 100.0) / 100.0;
      CapEvent ev;
      ev.train = train;
      ev.section = static_cast<int>(i);
      const double section_end = section_start + library.route(i).length_m();
      for (const CapStretch& c : before.binding)
        if (c.to_m >= section_start && c.from_m <= section_end) {
          ev.first_binding = c;
          break;
        }
      ev.planned_cost_J = engine.energy_cost_J(plan.runs[i]);
      ev.station_wait_s = wait;
      ev.waited_late_s = start + wait + plan.runs[i].running_time_s - planned_arrival;
      ev.supervised_cost_J = NAN;
      ev.reoptimised_cost_J = NAN;
      // Leaving earlier and driving under the cap is tried only when the wait makes it late.
      const physics::SpeedCap cap = separation_cap(leader, section_start, b, options.separation);
      physics::SimulationResult best;
      double best_wait = wait, best_arrival = start + wait + plan.runs[i].running_time_s;
      bool replaced = false;
      // Lateness first (no credit for arriving early), then energy.
      double best_cost = ev.planned_cost_J;
      const char* best_kind = "waited";
      auto consider = [&](physics::SimulationResult&& sim, double w, const char* kind) {
        if (!arrives(sim)) return;
        const double arrival = start + w + sim.running_time_s;
        const double late = std::max(0.0, arrival - planned_arrival);
        const double best_late = std::max(0.0, best_arrival - planned_arrival);
        const double cost = engine.energy_cost_J(sim);
        if (late > best_late - kEarlierBy_s && !(late <= best_late + 1e-9 && cost < best_cost))
          return;
        if (section_distance_margin_m(leader, sim, section_start, start + w, b, room) <
            -kDistanceMarginTolerance_m)
          return;
        best = std::move(sim);
        best_wait = w;
        best_arrival = arrival;
        best_cost = cost;
        best_kind = kind;
        replaced = true;
      };
      // Wait, then run the section faster than planned for the time left (the section
      // library's energy-optimal run for that time, down to the flat-out run); a faster run may
      // need a longer wait, so the two are iterated a few times.
      if (ev.waited_late_s > kEarlierBy_s) {
        double w = wait;
        for (int it = 0; it < kFasterTries; ++it) {
          const double time_left = planned_arrival - start - w;
          const bool flat_out = time_left <= library.min_time_s(i) + 0.02;
          physics::SimulationResult faster =
              flat_out ? library.min_time_run(i) : library.solve(i, time_left).search.run.sim;
          const double w2 = clearance_wait_s(leader, faster, section_start, start, b, room);
          const double w_round = std::ceil((w2 + kWaitMargin_s) * 100.0) / 100.0;
          consider(std::move(faster), w_round, "waited, then faster");
          if (flat_out || w2 <= w + 1e-9) break;
          w = w_round;
        }
        ev.faster_tried = true;
      }
      // Leaving earlier and driving under the cap, when waiting still makes it late and an
      // earlier arrival is possible at all: no run arrives before the flat-out time, nor before
      // the leader is clear of the stop by the room (a follower at rest there needs gap >= 0).
      const double earliest_arrival =
          std::max(start + library.min_time_s(i), leader_clear_at(leader, section_end + room));
      if (options.mode != FollowerMode::Wait && best_arrival - planned_arrival > kEarlierBy_s &&
          best_arrival - earliest_arrival > std::max(kEarlierBy_s, options.redrive_gain_s)) {
        // The planned control braked by the supervisor, leaving now: reported in both modes
        // (what the cap alone would do), driven in the supervised one.
        physics::SimulationResult sup =
            drive_planned(engine, plan.programs[i], plan.runs[i], cap, start, options.resim_step_m);
        ev.supervised_cost_J = engine.energy_cost_J(sup);
        ev.supervised_late_s = start + sup.running_time_s - planned_arrival;
        if (options.mode == FollowerMode::Supervised) {
          consider(std::move(sup), 0.0, "supervised");
        } else {
          dp::CappedSectionOptions capped = options.capped;
          capped.max_wait_s = std::min(capped.max_wait_s, wait);
          dp::CappedSectionResult r = dp::solve_capped_section(
              engine, cap, start, planned_arrival - start, capped, plan.programs[i]);
          ev.report = r.summary.BriefReport();
          if (r.summary.termination != dp::Termination::FAILURE) {
            ev.reoptimised_cost_J = r.summary.cost_J;
            ev.reoptimised_wait_s = r.wait_s;
            ev.reoptimised_late_s = start + r.wait_s + r.sim.running_time_s - planned_arrival;
            consider(std::move(r.sim), r.wait_s, "reoptimised");
          }
        }
      }
      if (replaced) {
        run = std::move(best);
        wait = best_wait;
      }
      ev.driven = best_kind;
      ev.station_wait_s = wait;
      ev.late_s = best_arrival - planned_arrival;
      if (events) events->push_back(ev);
      ++out.sections_redriven;
      out.station_wait_s += wait;
      if (i == 0)
        trip_departure += wait;
      else
        dwell_after[i - 1] += wait;
      start += wait;
    }
    sims[i] = std::move(run);
    const double arrival = start + sims[i].running_time_s;
    out.late_s[i + 1] = arrival - planned_arrival;
    if (i + 1 < n) {
      const double next = std::max(planned.stop(i + 1).departure_s, arrival + plan.dwells_s[i]);
      dwell_after[i] = next - arrival;
      start = next;
    }
  }
  out.late_s[0] = trip_departure - departure_s;
  for (const physics::SimulationResult& r : sims) out.traction_J += r.energy.traction_work_J;
  out.trip = trip_of(library, sims, dwell_after, trip_departure);
  out.scan = scan_separation(leader, out.trip, b, options.separation);
  if (!keeps_separation(out.scan)) {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "train %d comes %.3f m closer than its braking distance to the train ahead "
                  "(least gap %.3f m): the follower model broke its invariant",
                  train + 1, -out.scan.min_distance_margin_m, out.scan.min_gap_m);
    throw std::logic_error(buf);
  }
  return out;
}

physics::Trip trip_of(const dp::SectionLibrary& library,
                      const std::vector<physics::SimulationResult>& runs,
                      const std::vector<double>& dwell_after_s, double departure_s) {
  std::vector<physics::TripSection> sections;
  for (std::size_t i = 0; i < runs.size(); ++i)
    sections.push_back({&library.route(i), &runs[i], dwell_after_s[i]});
  return physics::Trip(sections, departure_s, library.train().regen_efficiency);
}

}  // namespace ecorail::service
