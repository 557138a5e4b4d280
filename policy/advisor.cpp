#include "policy/advisor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "data/line.hpp"
#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "dp/backward_sweep.hpp"
#include "physics/speed_envelope.hpp"

namespace ecorail::policy {

namespace {

// The energy to go, cost_to_go - lambda * time_to_go: a difference of two numbers of millions of
// joules, so a difference within the rounding of its operands (a few units in the last place)
// is no energy at all (on the final braking curve the two are equal, but came out 9.3e-10 J
// apart) and is reported as 0.
double energy_to_go_J(double cost_to_go_J, double time_price_J) {
  constexpr double kRoundingUlps = 16.0;
  const double difference = cost_to_go_J - time_price_J;
  const double scale = std::max(std::abs(cost_to_go_J), std::abs(time_price_J));
  return std::abs(difference) <= kRoundingUlps * std::numeric_limits<double>::epsilon() * scale
             ? 0.0
             : difference;
}

// Preference among controls whose look-ahead scores tie (several controls clamped onto the same
// braking curve, or hold and traction on a limit): the least traction first, so the advice on a
// braking curve reads "brake" and on a limit "hold".
constexpr std::array<physics::Control, physics::kControlCount> kPreference = {
    physics::Control::MaxBrake, physics::Control::Coast, physics::Control::Hold,
    physics::Control::MaxTraction};
constexpr double kTieRelative = 1e-9;
constexpr double kTieAbsolute_J = 1e-3;

}  // namespace

struct Advisor::Model {
  physics::Train train;
  physics::Route route;
  physics::SpeedEnvelope envelope;
  physics::Motion motion;
  physics::StepSettings step;

  Model(const physics::Train& t, physics::Route r, double resolution_m, double substep_m)
      : train(t),
        route(std::move(r)),
        envelope(train, route, resolution_m),
        motion(train, route, envelope),
        step{substep_m, 2} {}
};

Advisor::Advisor(PolicyTable table, const data::Line& line, const physics::Train& train)
    : table_(std::move(table)) {
  table_.validate();
  const std::uint64_t line_sum = line.checksum();
  const std::uint64_t train_sum = data::train_checksum(train);
  std::string mismatch;
  if (line_sum != table_.line_checksum) {
    mismatch += "line checksum differs: the table was made for line '" + table_.line_name + "' (" +
                "0x" + data::hex64(table_.line_checksum) + "), this is line '" + line.name + "' (" +
                "0x" + data::hex64(line_sum) + ")";
  }
  if (train_sum != table_.train_checksum) {
    if (!mismatch.empty()) mismatch += "; ";
    mismatch += "train checksum differs: the table was made for train '" + table_.train_name +
                "' (" + "0x" + data::hex64(table_.train_checksum) + "), this is train '" +
                train.name + "' (" + "0x" + data::hex64(train_sum) + ")";
  }
  if (!mismatch.empty()) {
    throw PolicyMismatchError("policy table " + table_.from + " -> " + table_.to +
                              " refused: " + mismatch);
  }
  model_ =
      std::make_shared<const Model>(train, data::build_route(line, table_.from, table_.to, train),
                                    table_.envelope_resolution_m, table_.grid_spec.substep_m);
  if (std::abs(model_->route.length_m() - table_.route_length_m) > 1e-6) {
    throw PolicyMismatchError("policy table refused: route length differs from the table's");
  }
  for (int i = 0; i < table_.stage_count(); ++i) {
    const double top = table_.speed_ms[table_.stage_offset[i + 1] - 1];
    if (std::abs(model_->envelope.v_at(table_.position_m[i]) - top) > 1e-9) {
      throw PolicyMismatchError(
          "policy table refused: its grid does not match the speed envelope rebuilt from this "
          "line and train (stage " +
          std::to_string(i) + "); was it made by another version of the engine?");
    }
  }
  layer_ = table_.nominal_layer();
}

Advisor Advisor::load(const std::filesystem::path& path, const data::Line& line,
                      const physics::Train& train) {
  return Advisor(load_policy(path), line, train);
}

const physics::Route& Advisor::route() const {
  return model_->route;
}
const physics::Motion& Advisor::motion() const {
  return model_->motion;
}

void Advisor::select_layer(int layer) {
  if (layer < 0 || layer >= static_cast<int>(table_.layers.size())) {
    throw std::out_of_range("policy table has no layer " + std::to_string(layer));
  }
  layer_ = layer;
}

Advice Advisor::advise(int layer, double s_m, double v_ms) const {
  const PolicyLayer& L = table_.layers.at(layer);
  const double length = table_.route_length_m;
  const double s = std::max(0.0, s_m);
  const double v = std::isfinite(v_ms) ? std::max(0.0, v_ms) : 0.0;
  Advice best;
  if (s >= length - 1e-9) {
    best.control = physics::Control::MaxBrake;
    best.regime = physics::Regime::FullBrake;
    return best;  // at the stop: nothing left to do
  }
  const int next = table_.next_stage_after(s);
  const double target = table_.position_m[next];
  const double e = 0.5 * v * v;
  const dp::Objective objective = table_.objective;
  const physics::Train& train = model_->train;

  double best_q = dp::kInfeasible;
  double best_t = dp::kInfeasible;
  physics::Control best_c = physics::Control::MaxTraction;
  bool found = false;
  for (physics::Control c : kPreference) {
    const physics::Advance adv = model_->motion.advance(s, e, target, c, model_->step);
    if (adv.stalled) continue;
    const double v_end = physics::speed_from_e(adv.e_end);
    const double rest = table_.interpolate(L.cost_to_go_J, next, v_end);
    if (!dp::is_feasible(rest)) continue;
    const double q = dp::energy_cost_J(objective, train, adv.traction_work_J, adv.brake_work_J,
                                       adv.traction_input_J, adv.regen_J) +
                     L.lambda_J_per_s * adv.time_s + rest;
    // Strictly better beyond the tie tolerance: earlier (preferred) controls win ties.
    if (!found || q < best_q - (kTieRelative * std::abs(best_q) + kTieAbsolute_J)) {
      found = true;
      best_q = q;
      best_c = c;
      best_t = adv.time_s + table_.interpolate(L.time_to_go_s, next, v_end);
    }
  }
  best.control = best_c;
  best.feasible = found;
  const physics::Substep probe = control_probe(model_->motion, s, v, best_c, target);
  best.regime = probe.regime;
  best.force_N = probe.mean_force_N;
  best.cost_to_go_J = best_q;
  best.time_to_go_s = best_t;
  best.energy_to_go_J = found ? energy_to_go_J(best_q, L.lambda_J_per_s * best_t) : dp::kInfeasible;
  return best;
}

int Advisor::layer_for_time(double s_m, double v_ms, double time_left_s) const {
  int best = layer_;
  double best_gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k < static_cast<int>(table_.layers.size()); ++k) {
    const Advice a = advise(k, s_m, v_ms);
    if (!a.feasible) continue;
    const double gap = std::abs(a.time_to_go_s - time_left_s);
    if (gap < best_gap) {
      best_gap = gap;
      best = k;
    }
  }
  return best;
}

physics::ControlLaw Advisor::law() const {
  return [this](double s_m, double v_ms) { return advise(s_m, v_ms).control; };
}

}  // namespace ecorail::policy
