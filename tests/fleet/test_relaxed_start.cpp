// The start joined from a relaxation's maximisers (fleet/relaxed_start.hpp): it is a timetable of
// the problem (trains - 1 headways within the limits summing to the span), a join that already
// meets the span is taken as it is (checked against every join by brute force), and the seconds
// still missing are spread evenly (away from the limits no headway moves by more than its share,
// rounded up); the candidates the search prices are every join near the span.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <vector>

#include "fleet/relaxed_start.hpp"

namespace ecorail::fleet {
namespace {

long sum(const std::vector<int>& h) {
  return std::accumulate(h.begin(), h.end(), 0L);
}

// Deterministic draws for the property tests (splitmix64 keyed by the case).
std::uint64_t draw(std::uint64_t key) {
  std::uint64_t z = key + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

TEST(RelaxedStart, SpreadMeetsTheSpanWithinTheLimitsEvenly) {
  for (std::uint64_t c = 0; c < 200; ++c) {
    const int lo = 100, hi = 160, n = 3 + static_cast<int>(draw(c) % 30);
    std::vector<int> h(n);
    for (int k = 0; k < n; ++k) h[k] = lo + static_cast<int>(draw(c * 1000 + k) % (hi - lo + 1));
    const int span = n * lo + static_cast<int>(draw(c + 7777) % (n * (hi - lo) + 1));
    std::vector<int> spread = h;
    ASSERT_TRUE(spread_to_span(spread, span, lo, hi)) << c;
    EXPECT_EQ(sum(spread), span) << c;
    const long share = (std::labs(span - sum(h)) + n - 1) / n;
    bool at_a_limit = false;
    for (int k = 0; k < n; ++k) {
      EXPECT_GE(spread[k], lo);
      EXPECT_LE(spread[k], hi);
      at_a_limit |= spread[k] == lo || spread[k] == hi;
    }
    // Away from the limits every headway takes its share: none moves by more, rounded up.
    for (int k = 0; k < n && !at_a_limit; ++k)
      EXPECT_LE(std::abs(spread[k] - h[k]), share) << c << " " << k;
  }
  std::vector<int> h{120, 120, 120};
  EXPECT_FALSE(spread_to_span(h, 3 * 160 + 1, 100, 160));  // no room for the span
  EXPECT_EQ(h, (std::vector<int>{120, 120, 120}));         // unchanged
}

TEST(RelaxedStart, AJoinThatMeetsTheSpanIsTakenAsItIs) {
  FleetProblem p;
  p.trains = 9;  // 8 headways
  p.headway_min_s = 100;
  p.headway_max_s = 200;
  for (std::uint64_t c = 0; c < 100; ++c) {
    std::vector<std::vector<int>> m(3, std::vector<int>(8));
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int k = 0; k < 8; ++k)
        m[i][k] = 100 + static_cast<int>(draw(c * 100 + i * 10 + k) % 101);
    // The span of a join of the first two at a drawn point: some join meets it exactly.
    const int cut = static_cast<int>(draw(c + 99) % 9);
    std::vector<int> target(m[0].begin(), m[0].begin() + cut);
    target.insert(target.end(), m[1].begin() + cut, m[1].end());
    p.span_s = static_cast<int>(sum(target));
    const std::vector<int> h = relaxed_start_headways(m, p);
    ASSERT_EQ(h.size(), 8u) << c;
    EXPECT_EQ(sum(h), p.span_s) << c;
    // Brute force: h is one of the joins (a, b, k) that meet the span exactly.
    bool is_exact_join = false;
    for (const auto& a : m)
      for (const auto& b : m)
        for (int k = 0; k <= 8; ++k) {
          std::vector<int> j(a.begin(), a.begin() + k);
          j.insert(j.end(), b.begin() + k, b.end());
          is_exact_join |= j == h;
        }
    EXPECT_TRUE(is_exact_join) << c;
  }
}

// The candidates the search prices: each a timetable of the problem, no repeats, and, by brute
// force over every ordered pair and cut, every join within a second a headway of the span is
// among them (closed to the span), the nearest join included.
TEST(RelaxedStart, CandidatesAreEveryNearJoinClosedToTheSpan) {
  FleetProblem p;
  p.trains = 9;  // 8 headways
  p.headway_min_s = 100;
  p.headway_max_s = 200;
  int several = 0;
  for (std::uint64_t c = 0; c < 100; ++c) {
    std::vector<std::vector<int>> m(4, std::vector<int>(8));
    for (std::size_t i = 0; i < m.size(); ++i)
      for (int k = 0; k < 8; ++k)
        m[i][k] = (i % 2 ? 150 : 100) + static_cast<int>(draw(c * 100 + i * 10 + k) % 51);
    p.span_s = 8 * 125 + static_cast<int>(draw(c + 5) % 200);
    const std::vector<std::vector<int>> cands = relaxed_start_candidates(m, p);
    ASSERT_FALSE(cands.empty()) << c;
    for (std::size_t i = 0; i < cands.size(); ++i) {
      EXPECT_EQ(departures_problem(p, departures_from_headways(cands[i])), "") << c;
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(cands[i], cands[j]) << c;
    }
    EXPECT_NE(std::find(cands.begin(), cands.end(), relaxed_start_headways(m, p)), cands.end())
        << c << ": the nearest join";
    for (const auto& a : m)
      for (const auto& b : m) {
        // The first cut nearest the span for this pair.
        long best = -1;
        std::vector<int> join;
        for (int k = 0; k <= 8; ++k) {
          std::vector<int> j(a.begin(), a.begin() + k);
          j.insert(j.end(), b.begin() + k, b.end());
          const long miss = std::labs(sum(j) - p.span_s);
          if (best < 0 || miss < best) best = miss, join = j;
        }
        if (best > 8) continue;
        ASSERT_TRUE(spread_to_span(join, p.span_s, p.headway_min_s, p.headway_max_s));
        EXPECT_NE(std::find(cands.begin(), cands.end(), join), cands.end()) << c;
      }
    several += cands.size() > 1;
  }
  EXPECT_GT(several, 10) << "the brute force must see several candidates";
}

TEST(RelaxedStart, MaximisersMissingTheSpanGiveATimetableOfTheProblem) {
  FleetProblem p;  // question 2.1's limits: 99 headways of 120-660 s over 63 900 s
  const std::vector<std::vector<int>> m{std::vector<int>(99, 660), std::vector<int>(99, 600),
                                        std::vector<int>(98, 640)};  // the last is no sequence
  const std::vector<int> h = relaxed_start_headways(m, p);
  ASSERT_EQ(h.size(), 99u);
  EXPECT_EQ(departures_problem(p, departures_from_headways(h)), "");
  EXPECT_TRUE(relaxed_start_headways({std::vector<int>(98, 640)}, p).empty());
}

}  // namespace
}  // namespace ecorail::fleet
