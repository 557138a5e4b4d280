// Example 04: the library objects of docs/architecture.md, with the same calls as its worked
// examples (so the document cannot drift from the API): checked options and a solver summary,
// a multi-stop run with dwells by name laid out as a trip and a timeline, a section library with
// frontiers, a restart, free dwells, a moving speed cap behind a train ahead, and a policy
// ladder read back by the advisor. Exits non-zero if a result is not usable or a check fails.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/journey.hpp"
#include "dp/journey_plan.hpp"
#include "dp/section_library.hpp"
#include "dp/section_solve.hpp"
#include "output/timeline.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"

using namespace ecorail;

namespace {

int check(bool ok, const char* what) {
  std::printf("%-58s %s\n", what, ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}

}  // namespace

int main() {
  const data::Line line = data::default_line();
  const physics::Train train = data::default_train();
  const physics::Route route = data::build_route(line, "A6", "A7", train);
  int failures = 0;

  // Summaries and options.
  dp::SectionSolveOptions options;
  options.engine.threads = 2;
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const dp::SectionSolution s = dp::solve_section(train, route, 110.0, options);
  std::cout << s.summary.BriefReport();
  failures += check(s.summary.IsSolutionUsable(), "section solve is usable");

  // A multi-stop run: route list, dwells by name, trip, timeline.
  const std::vector<std::string> stops = data::stops_between(line, "A6", "A8");
  const std::vector<physics::Route> routes = data::build_routes(line, stops, train);
  dp::DwellSpec dwell_plan;
  dwell_plan.by_stop_s = {{"A7", 45.0}};
  const std::vector<double> dwells = dp::resolve_dwells(dwell_plan, stops);
  dp::JourneyOptions journey;
  journey.measure_marginals = false;
  const dp::JourneySolution j = dp::solve_journey(train, routes, dwells, 220.0, journey);
  const physics::Trip trip = dp::journey_trip(j, routes, 0.0, train.regen_efficiency);
  const output::Timeline table = output::journey_timeline(j, routes);
  std::cout << j.summary.BriefReport();
  failures += check(j.summary.IsSolutionUsable(), "journey is usable");
  failures += check(std::abs(trip.arrival_s() - 265.0) < 0.01 &&
                        std::abs(table.back().t_s - trip.arrival_s()) < 1e-6,
                    "trip and timeline arrive at 220 s + 45 s");

  // A section library with short frontiers (10 s, 2 s step: quick), a restart, free dwells.
  dp::SectionLibraryOptions lib_options;
  lib_options.frontier_span_s = 10.0;
  lib_options.frontier_step_s = 2.0;
  const std::vector<physics::Route> three =
      data::build_routes(line, data::stops_between(line, "A6", "A9"), train);
  const dp::SectionLibrary library(train, three, lib_options);
  library.build_frontiers(0, library.size(), nullptr);
  const double price = library.frontier(0).marginal_at(library.min_time_s(0) + 5.0);
  const double t = library.frontier(0).time_for_marginal(price);
  failures += check(std::abs(t - library.min_time_s(0) - 5.0) < 1e-6,
                    "frontier: time_for_marginal inverts marginal_at");
  const dp::SectionTimeSolve exact = library.solve(0, 110.0);
  const physics::Trip first = exact.trip.shifted(7 * 3600.0);
  const physics::PowerBins p = first.power_bins(0.1);
  double traction_J = 0.0;
  for (double w : p.traction_W) traction_J += w * p.step_s;
  failures += check(
      std::abs(traction_J - first.ledger().traction_work_J) < 1e-9 * first.ledger().traction_work_J,
      "power bins add up to the ledger");

  const dp::SectionEngine& engine = library.engine(0);
  const dp::TimeSearchResult rest =
      dp::solve_for_time(engine, 75.0, {}, dp::StartState{400.0, 15.0});
  failures += check(rest.converged, "restart from 400 m at 15 m/s in 75 s");
  const dp::JourneySolution free =
      dp::solve_journey_free_dwells(library, 0, 3, {{20.0, 60.0}, {20.0, 60.0}}, 400.0, journey);
  failures += check(free.summary.IsSolutionUsable() && free.sections[0].dwell_after_s == 20.0,
                    "free dwells go to their minimum");

  // A moving speed cap behind a train ahead that stands at 900 m for a minute, then leaves.
  physics::SimulationOptions sim;
  const double b = 0.8;
  auto ahead_m = [](double t_s) { return t_s < 60.0 ? 900.0 : 900.0 + 12.0 * (t_s - 60.0); };
  sim.speed_cap = [&](double t_s, double s_m) {
    const double gap_m = std::max(0.0, ahead_m(t_s) - s_m - 50.0);
    return std::sqrt(2.0 * gap_m * b);
  };
  const physics::SimulationResult capped =
      physics::simulate(engine.motion(), exact.search.run.program, sim);
  failures += check(capped.max_cap_overspeed_ms <= 1e-6, "the follower keeps the cap");

  // A policy ladder and the advisor.
  policy::PolicyLadderOptions ladder;
  ladder.nominal_time_s = 110.0;
  ladder.time_offsets_s = {-5.0, 0.0, 5.0};
  const policy::PolicyTable ptable = policy::build_policy_ladder(
      engine, {line.name, line.checksum(), data::train_checksum(train)}, ladder);
  const auto file = std::filesystem::temp_directory_path() / "ecorail_example_04.bin";
  policy::save_policy(ptable, file);
  const policy::Advisor advisor = policy::Advisor::load(file, line, train);
  const policy::Advice now = advisor.advise(300.0, 16.0);
  std::filesystem::remove(file);
  failures += check(now.feasible && advisor.table().layers.size() == 3,
                    "the advisor reads the ladder back");
  return failures == 0 ? 0 : 1;
}
