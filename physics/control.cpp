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

}  // namespace ecorail::physics
