#include "fitting/parameters.hpp"

namespace ecorail::fitting {

namespace {
constexpr std::array<std::string_view, kParamCount> kNames = {
    "davis_A",        "davis_B", "davis_C",       "rotating_mass_factor",
    "gradient_scale", "mass_t",  "traction_scale"};
constexpr std::array<std::string_view, kParamCount> kUnits = {
    "N/kN", "N/kN per km/h", "N/kN per (km/h)^2", "-", "-", "t", "-"};
}  // namespace

std::string_view param_name(int p) {
  return kNames.at(static_cast<std::size_t>(p));
}
std::string_view param_unit(int p) {
  return kUnits.at(static_cast<std::size_t>(p));
}

std::optional<int> param_from_name(std::string_view name) {
  for (int p = 0; p < kParamCount; ++p) {
    if (kNames[static_cast<std::size_t>(p)] == name) return p;
  }
  return std::nullopt;
}

std::string param_list(const ParamFlags& which) {
  std::string s;
  for (int p = 0; p < kParamCount; ++p) {
    if (which[static_cast<std::size_t>(p)]) {
      s += (s.empty() ? "" : ", ") + std::string(param_name(p));
    }
  }
  return s;
}

ParamVector params_from_train(const physics::Train& train) {
  ParamVector p{};
  p[kDavisA] = train.davis.A;
  p[kDavisB] = train.davis.B;
  p[kDavisC] = train.davis.C;
  p[kRotatingMassFactor] = train.rotating_mass_factor;
  p[kGradientScale] = 1.0;
  p[kMassT] = train.mass_kg / 1000.0;
  p[kTractionScale] = 1.0;
  return p;
}

ParamVector default_lower_bounds(const physics::Train& base) {
  ParamVector lo{};
  lo[kDavisA] = 0.0;
  lo[kDavisB] = -0.5;
  lo[kDavisC] = 0.0;
  lo[kRotatingMassFactor] = 0.0;  // the train file rejects negative factors
  lo[kGradientScale] = -2.0;
  lo[kMassT] = 0.3 * base.mass_kg / 1000.0;
  lo[kTractionScale] = 0.3;
  return lo;
}

ParamVector default_upper_bounds(const physics::Train& base) {
  ParamVector hi{};
  hi[kDavisA] = 50.0;
  hi[kDavisB] = 1.0;
  hi[kDavisC] = 0.1;
  hi[kRotatingMassFactor] = 1.0;
  hi[kGradientScale] = 3.0;
  hi[kMassT] = 3.0 * base.mass_kg / 1000.0;
  hi[kTractionScale] = 3.0;
  return hi;
}

}  // namespace ecorail::fitting
