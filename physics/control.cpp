#include "physics/control.hpp"

namespace ecorail::physics {

std::string_view control_name(Control c) {
  switch (c) {
    case Control::MaxTraction:
      return "max_traction";
    case Control::Hold:
      return "hold";
    case Control::Coast:
      return "coast";
    case Control::MaxBrake:
      return "max_brake";
  }
  return "?";
}

std::string_view regime_name(Regime r) {
  switch (r) {
    case Regime::FullTraction:
      return "full_traction";
    case Regime::PartialTraction:
      return "partial_traction";
    case Regime::Coast:
      return "coast";
    case Regime::PartialBrake:
      return "partial_brake";
    case Regime::FullBrake:
      return "full_brake";
  }
  return "?";
}

std::optional<Control> control_from_name(std::string_view name) {
  for (int c = 0; c < kControlCount; ++c) {
    if (control_name(static_cast<Control>(c)) == name) return static_cast<Control>(c);
  }
  return std::nullopt;
}

std::optional<Regime> regime_from_name(std::string_view name) {
  for (auto r : {Regime::FullTraction, Regime::PartialTraction, Regime::Coast, Regime::PartialBrake,
                 Regime::FullBrake}) {
    if (regime_name(r) == name) return r;
  }
  return std::nullopt;
}

}  // namespace ecorail::physics
