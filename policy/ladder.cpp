#include "policy/ladder.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "dp/threads.hpp"

namespace ecorail::policy {

bool PolicyLadderOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(nominal_time_s > 0.0 && std::isfinite(nominal_time_s))) {
    return fail("nominal_time_s must be a running time in seconds > 0");
  }
  if (time_offsets_s.empty()) return fail("time_offsets_s must hold at least one offset");
  if (std::set<double>(time_offsets_s.begin(), time_offsets_s.end()).size() !=
      time_offsets_s.size()) {
    return fail("time_offsets_s must be distinct");
  }
  for (double d : time_offsets_s) {
    if (!(std::isfinite(d) && nominal_time_s + d > 0.0)) {
      return fail("time_offsets_s must leave a positive running time (nominal_time_s + offset)");
    }
  }
  return search.IsValid(error);
}

PolicyTable build_policy_ladder(const dp::SectionEngine& engine, const PolicyIdentity& identity,
                                const PolicyLadderOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const dp::ThreadScope threads(engine.options().threads);  // the layers' parallel parts
  PolicyTable table = make_policy_table(engine, identity.line_name, identity.line_checksum,
                                        identity.train_checksum);
  const int layers = static_cast<int>(options.time_offsets_s.size());
  dp::report_progress(options.progress, "layer", 0, layers);
  for (double offset : options.time_offsets_s) {
    const double target = options.nominal_time_s + offset;
    dp::TimeSearchResult found;
    try {
      found = dp::solve_for_time(engine, target, options.search);
    } catch (const dp::InfeasibleTimeError& e) {
      throw LadderTimeError(e, offset);
    } catch (const dp::TimeRequestError& e) {
      throw LadderRungError(e, offset);
    }
    PolicyLayer layer = build_policy_layer(engine, found.run.lambda);
    layer.time_offset_s = offset;
    layer.target_time_s = target;
    table.layers.push_back(std::move(layer));
    dp::report_progress(options.progress, "layer", static_cast<int>(table.layers.size()), layers);
  }
  return table;
}

}  // namespace ecorail::policy
