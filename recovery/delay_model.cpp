#include "recovery/delay_model.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fleet/search_support.hpp"

namespace ecorail::recovery {

namespace {

// Names the generator's stream, so these draws share no key with the fleet searches'.
constexpr std::uint64_t kDelaySalt = 0x6465'6c61'7973'3332ULL;  // "delays32"

// Draw k of the key (seed, day, train, station): one SplitMix64 finaliser per key field.
std::uint64_t key_draw(std::uint64_t seed, std::uint64_t day, std::uint64_t train,
                       std::uint64_t station, std::uint64_t k) {
  using fleet::counter_mix;
  const std::uint64_t h =
      counter_mix(counter_mix(counter_mix(counter_mix(seed ^ kDelaySalt) ^ day) ^ train) ^ station);
  return counter_mix(h ^ k);
}

bool parse_number(const std::string& text, double* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

}  // namespace

bool DelayDistribution::IsValid(std::string* error) const {
  auto fail = [&](const char* text) {
    if (error != nullptr) *error = text;
    return false;
  };
  if (!(p_none >= 0.0 && p_small >= 0.0 && p_none + p_small <= 1.0 + 1e-12))
    return fail("the delay shares (none, small) must be >= 0 and add up to at most 1");
  if (!(small_max_s > 0.0 && small_max_s <= 3600.0))
    return fail("the largest small delay must lie in (0, 3600] s");
  if (tail == DelayTail::Exponential && !(tail_mean_s > 0.0 && tail_mean_s <= 3600.0))
    return fail("--tail: the exponential mean must lie in (0, 3600] s");
  if (tail == DelayTail::Uniform &&
      !(tail_low_s >= small_max_s && tail_high_s > tail_low_s && tail_high_s <= 86400.0))
    return fail(
        "--tail: a uniform tail needs its low end at or above the largest small delay and "
        "below its high end, at most 86400 s");
  return true;
}

std::string DelayDistribution::tail_text() const {
  char buf[100];
  if (tail == DelayTail::Exponential)
    std::snprintf(buf, sizeof buf, "exponential:%g", tail_mean_s);
  else
    std::snprintf(buf, sizeof buf, "uniform:%g:%g", tail_low_s, tail_high_s);
  return buf;
}

bool parse_delay_tail(const std::string& text, DelayDistribution& d, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  const std::string expected =
      "exponential:MEAN (seconds above " + std::to_string(static_cast<int>(d.small_max_s)) +
      " s) or uniform:LOW:HIGH (LOW >= " + std::to_string(static_cast<int>(d.small_max_s)) +
      " s); got '" + text + "'";
  const auto colon = text.find(':');
  if (colon == std::string::npos) return fail(expected);
  const std::string kind = text.substr(0, colon), rest = text.substr(colon + 1);
  DelayDistribution out = d;
  if (kind == "exponential") {
    if (!parse_number(rest, &out.tail_mean_s)) return fail(expected);
    out.tail = DelayTail::Exponential;
  } else if (kind == "uniform") {
    const auto c2 = rest.find(':');
    if (c2 == std::string::npos || !parse_number(rest.substr(0, c2), &out.tail_low_s) ||
        !parse_number(rest.substr(c2 + 1), &out.tail_high_s))
      return fail(expected);
    out.tail = DelayTail::Uniform;
  } else {
    return fail(expected);
  }
  if (!out.IsValid(nullptr)) return fail(expected);
  d = out;
  return true;
}

DelayDraw draw_delay(const DelayDistribution& d, std::uint64_t seed, std::uint64_t day,
                     std::uint64_t train, std::uint64_t station) {
  using fleet::uniform01;
  const double u = uniform01(key_draw(seed, day, train, station, 0));
  DelayDraw out;
  if (u < d.p_none) return out;
  // (0, 1]: 1 - uniform01 never gives 0, so a drawn delay is never 0.
  const double v = 1.0 - uniform01(key_draw(seed, day, train, station, 1));
  if (u < d.p_none + d.p_small) {
    out.kind = DelayKind::Small;
    out.delay_s = d.small_max_s * v;
    return out;
  }
  out.kind = DelayKind::Tail;
  if (d.tail == DelayTail::Exponential)
    out.delay_s = d.small_max_s - d.tail_mean_s * std::log(v);  // v in (0, 1]: excess >= 0
  else
    out.delay_s = d.tail_high_s - (d.tail_high_s - d.tail_low_s) * (1.0 - v);
  // The tail is "over small_max_s": an excess of exactly 0 (v = 1) is pushed just above it.
  if (out.delay_s <= d.small_max_s) out.delay_s = std::nextafter(d.small_max_s, 1e300);
  return out;
}

}  // namespace ecorail::recovery
