// Property test of the knock-on model (recover_delay's followers, service/follower.hpp): random
// delays (0 to 900 s, at a random station) on random short plans (A6 -> A9, four trains, random
// headways of 60 to 400 s, so that followers are sometimes free, sometimes held up in a chain).
// Invariants, checked independently of the scan the model uses: every driven train keeps at
// least its braking distance behind the actual run of the train ahead at every sample (the
// leader's position read from its own trip with state_at), never arrives at or leaves a station
// before the train ahead, never leaves a stop or arrives before its timetable, reports the
// lateness of its re-simulated trip and is on time from the station where it says it is back
// on time; the chain stops at the first train not held up, and the late train's own recovery
// is the same, to the bit, as without followers when nobody is held up; the followers' candidate
// runs solved lazily give the same trips.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "recovery/delay_recovery.hpp"
#include "recovery_fixture.hpp"
#include "service/separation.hpp"

namespace ecorail::recovery {
namespace {

using testing::small_library;
using testing::small_plan;
using testing::test_store;

// Independently of service::scan_separation: gap to the leader's own state_at, less the
// braking distance, least over the follower's samples while the leader is on the line.
double least_distance_margin_m(const physics::Trip& leader, const physics::Trip& follower,
                               double b) {
  double least = INFINITY;
  for (const physics::Trip::Sample& p : follower.samples()) {
    const double t = follower.departure_s() + p.t_s;
    if (t >= leader.arrival_s()) break;
    const double gap = leader.state_at(t).position_m - p.s_m;
    least = std::min(least, gap - p.v_ms * p.v_ms / (2.0 * b));
  }
  return least;
}

TEST(KnockOnProperty, FollowersKeepTheirBrakingDistanceAndNeverPass) {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> headway(60.0, 400.0), delay(0.0, 900.0);
  std::uniform_int_distribution<int> station(0, 1);
  const double b = service::default_separation_braking_m_s2(small_library().train());
  int held_up = 0, free_chains = 0;
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<double> departures = {0.0};
    for (int k = 1; k < 4; ++k) departures.push_back(departures.back() + std::round(headway(rng)));
    const Plan plan = small_plan(departures);
    const std::size_t j = static_cast<std::size_t>(station(rng));
    const double d = std::round(delay(rng));
    SCOPED_TRACE("trial " + std::to_string(trial) + ": delay " + std::to_string(d) +
                 " s at station " + std::to_string(j));
    DelayRecoveryOptions o;
    o.max_followers = 3;
    const DelayRecoveryResult r = recover_delay(small_library(), plan, 0, j, d, o, test_store());
    ASSERT_EQ(r.train_trips.size(), r.trains.size());
    for (std::size_t i = 1; i < r.train_trips.size(); ++i) {
      const physics::Trip& ahead = r.train_trips[i - 1];
      const physics::Trip& me = r.train_trips[i];
      EXPECT_GE(least_distance_margin_m(ahead, me, b), -0.01) << "train " << i + 1;
      const auto a = ahead.stops(), m = me.stops();
      const TrainStops& planned = plan.trains[static_cast<std::size_t>(r.trains[i].train)];
      for (std::size_t s = 0; s < m.size(); ++s) {
        EXPECT_GT(m[s].arrival_s, a[s].arrival_s) << "station " << s;
        EXPECT_GT(m[s].departure_s, a[s].departure_s) << "station " << s;
        EXPECT_GE(m[s].departure_s, planned.departure_s[s] - 1e-6) << "station " << s;
        // The lateness reported is the re-simulated trip's, and a follower never arrives
        // before its timetable.
        if (s > 0) {
          EXPECT_NEAR(r.trains[i].lateness_s[s], m[s].arrival_s - planned.arrival_s[s], 1e-6);
          EXPECT_GE(m[s].arrival_s, planned.arrival_s[s] - 1e-6) << "station " << s;
        }
      }
      // Back on time where it says: no arrival from there on later than the tolerance.
      const int e = r.trains[i].back_on_time_at.empty()
                        ? -1
                        : plan.station_index(r.trains[i].back_on_time_at);
      if (e > 0) {
        for (std::size_t s = static_cast<std::size_t>(e); s < m.size(); ++s)
          EXPECT_LE(m[s].arrival_s, planned.arrival_s[s] + 0.05) << "station " << s;
      }
    }
    // Every follower but the last one checked is held up; the last is free unless the chain
    // was cut by max_followers.
    for (std::size_t i = 0; i + 1 < r.followers.size(); ++i) EXPECT_TRUE(r.followers[i].affected);
    if (!r.followers.empty() && !r.followers.back().affected) {
      EXPECT_TRUE(r.summary.cascade_ends);
      ++free_chains;
    }
    EXPECT_EQ(r.summary.cascade_trains, r.summary.followers_affected);
    held_up += r.summary.followers_affected;
    // Candidate runs solved lazily (DelayOptions::lazy_follower_solves): the same trips.
    if (r.summary.followers_affected > 0) {
      DelayRecoveryOptions lazy = o;
      lazy.lazy_follower_solves = true;
      const DelayRecoveryResult z =
          recover_delay(small_library(), plan, 0, j, d, lazy, test_store());
      ASSERT_EQ(z.train_trips.size(), r.train_trips.size());
      for (std::size_t i = 0; i < r.train_trips.size(); ++i) {
        const auto a = r.train_trips[i].stops(), c = z.train_trips[i].stops();
        ASSERT_EQ(a.size(), c.size());
        for (std::size_t s = 0; s < a.size(); ++s) {
          EXPECT_NEAR(c[s].arrival_s, a[s].arrival_s, 1e-6) << "lazy, train " << i + 1;
          EXPECT_NEAR(c[s].departure_s, a[s].departure_s, 1e-6) << "lazy, train " << i + 1;
        }
      }
    }
    if (r.summary.followers_affected == 0) {
      DelayRecoveryOptions alone = o;
      alone.check_followers = false;
      const DelayRecoveryResult s =
          recover_delay(small_library(), plan, 0, j, d, alone, test_store());
      ASSERT_EQ(s.sections.size(), r.sections.size());
      for (std::size_t k = 0; k < s.sections.size(); ++k) {
        EXPECT_EQ(s.sections[k].new_time_s, r.sections[k].new_time_s);
        EXPECT_EQ(s.sections[k].new_energy_kJ, r.sections[k].new_energy_kJ);
      }
      EXPECT_EQ(s.summary.final_lateness_s, r.summary.final_lateness_s);
    }
  }
  // The draws reach both cases: followers held up, and chains that end.
  EXPECT_GT(held_up, 0);
  EXPECT_GT(free_chains, 0);
}

}  // namespace
}  // namespace ecorail::recovery
