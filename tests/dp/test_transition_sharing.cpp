// The transition table integrates a transition once for every class of alike stages (same
// substeps, gradient, curve, tunnel drag and uniform speed row) and uses it wherever the speed
// envelope cannot bind; a stage reads its class's rows where they are its own transitions bit
// for bit, without a copy. That must give the table of integrating every stage on its own, to
// the last bit, and the same sweeps: on every section of the reference line (gradients, curves,
// limits, braking curves) and on a made-up route whose segment ends and grid positions fall
// anywhere. On a long level line the table keeps a small part of its entries.
#include <gtest/gtest.h>

#include <cstring>

#include "data/line_loader.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/backward_sweep.hpp"
#include "dp/section_engine.hpp"
#include "dp/transition_table.hpp"

namespace ecorail {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Compares a shared table with one integrated stage by stage; returns the entries compared.
long expect_same_tables(const dp::SectionEngine& engine, dp::Objective objective) {
  const dp::TransitionTable shared(engine.motion(), engine.grid(), objective, engine.dp_step(),
                                   true);
  const dp::TransitionTable own(engine.motion(), engine.grid(), objective, engine.dp_step(), false);
  const dp::StageGrid& grid = engine.grid();
  const int nodes = grid.offset(grid.stage_count() - 1);
  long differing = 0;
  for (int node = 0; node < nodes; ++node) {
    for (int c = 0; c < physics::kControlCount; ++c) {
      const auto control = static_cast<physics::Control>(c);
      const dp::Transition a = shared.at(node, control);
      const dp::Transition b = own.at(node, control);
      if (a.lower != b.lower || !same_bits(a.energy_J, b.energy_J) ||
          !same_bits(a.time_s, b.time_s) || !same_bits(a.weight, b.weight)) {
        ++differing;
      }
    }
  }
  EXPECT_EQ(differing, 0);
  // The sweeps read the stages' rows (a class's or their own): the same cost-to-go and controls.
  for (const double lambda : {0.0, 2.0e4, 3.0e5}) {
    dp::ValueFunction a, b;
    dp::backward_sweep(grid, shared, lambda, a);
    dp::backward_sweep(grid, own, lambda, b);
    long differing_nodes = 0;
    for (int node = 0; node < grid.total_nodes(); ++node) {
      if (!same_bits(a.cost_to_go[node], b.cost_to_go[node]) || a.best[node] != b.best[node]) {
        ++differing_nodes;
      }
    }
    EXPECT_EQ(differing_nodes, 0) << "lambda " << lambda;
  }
  EXPECT_EQ(shared.dependencies().first, own.dependencies().first);
  EXPECT_EQ(shared.dependencies().last, own.dependencies().last);
  EXPECT_EQ(own.shared_entries(), 0);
  EXPECT_EQ(shared.shared_entries() + shared.stage_integrations(),
            static_cast<long>(nodes) * physics::kControlCount);
  return shared.shared_entries();
}

TEST(TransitionSharing, SharedTableIsTheStageByStageTableOnEverySection) {
  const physics::Train train = data::default_train();
  const data::Line line = data::default_line();
  const auto& stations = line.stations;
  long shared = 0, total = 0;
  for (std::size_t k = 0; k + 1 < stations.size(); ++k) {
    const physics::Route route =
        data::build_route(line, stations[k].name, stations[k + 1].name, train);
    const dp::SectionEngine engine(train, route, {});
    shared += expect_same_tables(engine, dp::Objective::Traction);
    total += static_cast<long>(engine.grid().total_nodes()) * physics::kControlCount;
  }
  // Most transitions are shared on the reference line (its gradients change every few hundred
  // metres and its limits rarely).
  EXPECT_GT(shared, total / 2);
}

TEST(TransitionSharing, SharedTableIsTheStageByStageTableOnAnIrregularRoute) {
  const physics::Train train = data::default_train();
  std::vector<physics::RouteSegment> segments;
  // Ends at odd positions, curves, a tunnel, a lower limit in the middle, steep grades.
  const double ends[] = {137.3, 402.9, 655.55, 901.0, 1240.7, 1502.25, 1833.3};
  const double grades[] = {0.0, 12.5, -8.0, 3.3, 0.0, -25.0, 4.0};
  const double radii[] = {0.0, 600.0, 0.0, 350.0, 0.0, 0.0, 1200.0};
  const double limits_kmh[] = {80.0, 80.0, 55.0, 55.0, 80.0, 70.0, 70.0};
  double start = 0.0;
  for (int k = 0; k < 7; ++k) {
    physics::RouteSegment seg;
    seg.start_m = start;
    seg.end_m = ends[k];
    seg.gradient_permille = grades[k];
    seg.curve_radius_m = radii[k];
    seg.speed_limit_ms = limits_kmh[k] / 3.6;
    if (k == 4) seg.tunnel_drag_N_per_kN_kmh2 = 2e-4;
    segments.push_back(seg);
    start = ends[k];
  }
  const physics::Route route(segments, 0.0, 1, "X", "Y");
  for (const double ds : {5.0, 3.7}) {
    dp::EngineOptions options;
    options.grid.ds_m = ds;
    options.grid.dv_kmh = 0.3;
    options.grid.substep_m = ds / 2.0;
    const dp::SectionEngine engine(train, route, options);
    EXPECT_GT(expect_same_tables(engine, dp::Objective::Traction), 0) << ds;
    expect_same_tables(engine, dp::Objective::Net);
  }
}

// 12 km of level track at one limit (the run's stop braking curve and the limit are where the
// envelope binds): the stages' own rows and the class's rows are under 2 % of the nodes' entries
// (0.87 % when written; 14 % while a brake that stalls from a crawl was integrated at every
// stage, 100 % when every stage copied its class's rows), and the table is still the
// stage-by-stage one.
TEST(TransitionSharing, ALongLevelLineKeepsFewEntries) {
  const physics::Train train = data::default_train();
  physics::RouteSegment seg;
  seg.start_m = 0.0;
  seg.end_m = 12000.0;
  seg.speed_limit_ms = 80.0 / 3.6;
  const physics::Route route({seg}, 0.0, 1, "X", "Y");
  const dp::SectionEngine engine(train, route, {});
  const long entries = static_cast<long>(engine.grid().offset(engine.grid().stage_count() - 1)) *
                       physics::kControlCount;
  expect_same_tables(engine, dp::Objective::Traction);
  const dp::TransitionTable& table = engine.transitions();
  EXPECT_LT(table.stored_entries(), entries / 50)
      << table.stored_entries() << " of " << entries << " entries stored";
}

}  // namespace
}  // namespace ecorail
