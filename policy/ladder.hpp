// Policy ladders: a policy table of one section with one layer per running time, built from an
// engine. The nominal running time and a list of offsets (a late train follows a negative
// offset) each get their time price searched on re-simulated runs and a full layer of u*,
// cost-to-go and time-to-go (build_policy_layer). This is the computation behind `ecorail
// policy --lambda-ladder`; the CLI only parses the offsets and prints the table.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dp/section_engine.hpp"
#include "dp/time_target.hpp"
#include "policy/policy_table.hpp"

namespace ecorail::policy {

inline constexpr double kLayerLambdaTolerance_s = 0.05;
inline dp::TimeSearchOptions layer_search() {
  dp::TimeSearchOptions o;
  o.lambda_tolerance_s = kLayerLambdaTolerance_s;
  return o;
}

struct PolicyLadderOptions {
  double nominal_time_s = 0.0;              // running time of the layer with offset 0
  std::vector<double> time_offsets_s{0.0};  // one layer per nominal_time_s + offset
  // A layer is the value function of its price, driven by feedback, not a trimmed program: the
  // price itself must give the running time, so it is searched to kLayerLambdaTolerance_s (the
  // section search's default leaves half a second to its trim).
  dp::TimeSearchOptions search = layer_search();
  // Called with ("layer", layers done, layers) as the ladder is built (cli/progress_line.hpp).
  dp::ProgressFn progress;
  // Checks every field (offsets distinct, each leaving a positive running time); on failure
  // writes one sentence naming the field into *error.
  bool IsValid(std::string* error) const;
};

// One rung of the ladder asks for a running time below the flat-out run: an
// InfeasibleTimeError that also says which offset it was.
class LadderTimeError : public dp::InfeasibleTimeError {
 public:
  LadderTimeError(const dp::InfeasibleTimeError& cause, double offset_s)
      : dp::InfeasibleTimeError(cause), offset_s_(offset_s) {}
  double offset_s() const { return offset_s_; }

 private:
  double offset_s_;
};

// Any other running time of a rung the engine cannot solve (a time longer than it solves
// reliably): the cause's message, and which offset it was.
class LadderRungError : public dp::TimeRequestError {
 public:
  LadderRungError(const dp::TimeRequestError& cause, double offset_s)
      : dp::TimeRequestError(cause), offset_s_(offset_s) {}
  double offset_s() const { return offset_s_; }

 private:
  double offset_s_;
};

// Who the table is for (written into its header and checked by the Advisor).
struct PolicyIdentity {
  std::string line_name;
  std::uint64_t line_checksum = 0;
  std::uint64_t train_checksum = 0;
};

// The table with one layer per offset, in the order given. std::invalid_argument for invalid
// options, LadderTimeError for a rung below the flat-out run, LadderRungError for any other
// running time of a rung the engine cannot solve.
PolicyTable build_policy_ladder(const dp::SectionEngine& engine, const PolicyIdentity& identity,
                                const PolicyLadderOptions& options);

}  // namespace ecorail::policy
