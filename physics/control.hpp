// The driving controls the engine chooses between, and the regimes a re-simulation reports.
// Pontryagin's principle says an energy-optimal run uses only full traction, speed holding
// (partial traction or partial braking), coasting and full braking; the DP searches over
// exactly these, and every other force the train applies comes from following the speed
// envelope (limits and the braking curves in front of them).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ecorail::physics {

enum class Control : std::uint8_t { MaxTraction = 0, Hold = 1, Coast = 2, MaxBrake = 3 };
inline constexpr int kControlCount = 4;

enum class Regime : std::uint8_t {
  FullTraction,
  PartialTraction,  // cruise, or following a limit upwards of coasting
  Coast,
  PartialBrake,
  FullBrake,
};

// Names to and from text, in one place each (reports, JSON, CSV, command-line flags).
std::string_view control_name(Control c);
std::string_view regime_name(Regime r);
std::optional<Control> control_from_name(std::string_view name);
std::optional<Regime> regime_from_name(std::string_view name);

}  // namespace ecorail::physics
