#include <gtest/gtest.h>

#include <cstdio>

#include "recovery/delay_recovery.hpp"
#include "recovery_fixture.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;
using testing::small_plan;
using testing::test_store;

TEST(FollowerRecoveryExplore, Scan) {
  for (double h : {50.0, 60.0, 70.0, 80.0})
    for (double D : {20.0, 30.0, 40.0, 50.0})
      for (std::size_t s : {0u, 1u}) {
        const Plan plan = small_plan({0.0, h});
        DelayRecoveryOptions o;
        o.max_followers = 1;
        o.lateness_first = true;
        const DelayRecoveryResult r = recover_delay(small_library(), plan, 0, s, D, o, test_store());
        if (r.train_trips.size() < 2) { std::printf("h %g D %g s %zu: free\n", h, D, s); continue; }
        const auto st = r.train_trips[1].stops();
        std::printf("h %g D %g s %zu: back %s wait %.2f |", h, D, s, r.trains[1].back_on_time_at.c_str(), r.followers[0].station_wait_s);
        for (std::size_t k = 0; k < st.size(); ++k)
          std::printf(" [%.2f %.2f | %.2f %.2f]", st[k].arrival_s, st[k].departure_s, plan.trains[1].arrival_s[k], plan.trains[1].departure_s[k]);
        std::printf(" LF %.2f EF %.2f\n", r.summary.total_lateness_s, r.summary.energy_first_total_lateness_s);
      }
}

}  // namespace
}  // namespace ecorail::recovery
