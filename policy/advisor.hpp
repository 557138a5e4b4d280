// Advisor: answers "what now?" on board from a policy table. It is built from a table and the
// Line and Train it is used with, and refuses (PolicyMismatchError) a table made for another line
// or train, naming which checksum differs, or whose grid does not match the speed envelope
// rebuilt from them. For any state (s, v) it does a one-step look-ahead on the table: each
// control is integrated with the table's own model (train, route, DP substep) from s to the next
// grid position, and scored by its energy plus lambda times its time plus the cost-to-go there,
// interpolated linearly in speed from the table. The best control is the advice; its first metre
// gives the regime and force (including the envelope clamp, so on a braking curve the regime is
// braking whatever the control), and the score is the expected cost-to-go. At a grid node this
// reproduces the table's own u* and cost-to-go; between nodes it is exact in position and
// interpolates only in speed. A ladder file holds several layers (time prices); the advisor
// follows one, chosen by select_layer or, for time keeping, by the time left (layer_for_time).
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "base/error.hpp"
#include "data/line.hpp"
#include "physics/simulator.hpp"
#include "physics/train.hpp"
#include "policy/policy_table.hpp"

namespace ecorail::policy {

// The table was made for another line or train (or by an incompatible engine).
class PolicyMismatchError : public std::runtime_error, public Error {
 public:
  explicit PolicyMismatchError(const std::string& what)
      : std::runtime_error(what), Error(ErrorKind::kPolicyMismatch) {}
};

struct Advice {
  physics::Control control = physics::Control::Coast;
  physics::Regime regime = physics::Regime::Coast;  // what the train does over the next metre
  double force_N = 0.0;         // mean applied force over the next metre, traction positive
  double cost_to_go_J = 0.0;    // expected energy + lambda * time to the stop
  double time_to_go_s = 0.0;    // expected running time to the stop
  double energy_to_go_J = 0.0;  // cost_to_go - lambda * time_to_go
  bool feasible = true;         // false: no control reaches the next grid position
};

class Advisor {
 public:
  Advisor(PolicyTable table, const data::Line& line, const physics::Train& train);
  // Loads a table file (PolicyFormatError if it is unreadable) and checks it as above.
  static Advisor load(const std::filesystem::path& path, const data::Line& line,
                      const physics::Train& train);

  // The advice at position s (m from the departure stop) and measured speed v (m/s).
  Advice advise(double s_m, double v_ms) const { return advise(layer_, s_m, v_ms); }
  Advice advise(int layer, double s_m, double v_ms) const;

  // The layer advice follows; starts at the table's nominal layer (time offset 0).
  void select_layer(int layer);
  int layer() const { return layer_; }
  // The layer whose expected time-to-go at (s, v) is closest to time_left_s (time keeping with a
  // lambda ladder: a late train moves to a faster layer).
  int layer_for_time(double s_m, double v_ms, double time_left_s) const;

  // A feedback law for physics::simulate that follows the advice; the advisor must outlive it.
  physics::ControlLaw law() const;

  const PolicyTable& table() const { return table_; }
  const physics::Route& route() const;
  const physics::Motion& motion() const;

 private:
  struct Model;
  PolicyTable table_;
  std::shared_ptr<const Model> model_;
  int layer_ = 0;
};

}  // namespace ecorail::policy
