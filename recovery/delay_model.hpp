// The random delays of question 3.2: a train's departure from a station is late by nothing
// with probability p_none (0.7), by a delay uniform in (0, small_max_s] (10 s) with p_small
// (0.2), and by more than small_max_s with the rest (0.1), drawn from the tail distribution,
// which is an option: exponential (small_max_s + an exponential of mean tail_mean_s, 30 s by
// default) or uniform over (tail_low_s, tail_high_s]. Every draw comes from the project's
// counter-based generator (fleet/search_support.hpp) keyed by (seed, day, train, station),
// so it depends only on what it is for: the same key gives the same delay whichever thread,
// process or machine makes it, in whatever order.
#pragma once

#include <cstdint>
#include <string>

namespace ecorail::recovery {

enum class DelayTail { Exponential, Uniform };

struct DelayDistribution {
  double p_none = 0.7;
  double p_small = 0.2;  // the rest (1 - p_none - p_small) is the tail
  double small_max_s = 10.0;
  DelayTail tail = DelayTail::Exponential;
  double tail_mean_s = 30.0;  // exponential: the mean of the excess over small_max_s
  double tail_low_s = 10.0, tail_high_s = 120.0;  // uniform tail
  // Checks every field; on failure writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
  // "exponential:30" or "uniform:10:120" (the --tail option).
  std::string tail_text() const;
};

// Parses the --tail option into d ("exponential:MEAN" or "uniform:LOW:HIGH", LOW >= small_max_s);
// false with a sentence in *error when it does not parse.
bool parse_delay_tail(const std::string& text, DelayDistribution& d, std::string* error);

// Which part of the distribution a draw fell in.
enum class DelayKind { None, Small, Tail };

struct DelayDraw {
  DelayKind kind = DelayKind::None;
  double delay_s = 0.0;
};

// The delay of `train`'s departure from `station` on `day` (all 0-based).
DelayDraw draw_delay(const DelayDistribution& d, std::uint64_t seed, std::uint64_t day,
                     std::uint64_t train, std::uint64_t station);

}  // namespace ecorail::recovery
