// TTOBench train JSON -> physics::Train (the mapping is documented in docs/formats.md).
#include <cmath>
#include <limits>

#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/ttobench_io.hpp"
#include "data/ttobench_json.hpp"
#include "data/ttobench_units.hpp"

namespace ecorail::data {

namespace {

using nlohmann::json;
using ttobench::index;
using ttobench::join;
using ttobench::JsonReader;

// A required or optional positive quantity; `allow_zero` admits 0.
double positive(const JsonReader& r, const json& root, const std::string& key,
                const ttobench::UnitTable& units, bool allow_zero = false) {
  const double v = r.quantity(root, key, units);
  if (allow_zero ? !(v >= 0.0) : !(v > 0.0)) {
    r.fail(join(key, "value"),
           std::string(allow_zero ? "a value of at least 0" : "a value above 0") + "; got " +
               format_number(v));
  }
  return v;
}

double efficiency(const JsonReader& r, const json& root, const std::string& key) {
  const json& q = r.object(root, key, "");
  if (q.contains("values") || q.contains("units")) {
    r.fail(key,
           "a single efficiency {\"unit\", \"value\"}; efficiency maps over speed and force "
           "are not modelled yet and are refused rather than approximated");
  }
  const double v = r.quantity(root, key, ttobench::kRatio);
  if (!(v > 0.0 && v <= 1.0)) {
    r.fail(join(key, "value"),
           "an efficiency in (0, 100] %; got " + format_number(100.0 * v) + " %");
  }
  return v;
}

}  // namespace

physics::Train train_from_ttobench(const std::string& text, const std::string& file) {
  const JsonReader r(file);
  const json root =
      r.parse_root(text, ttobench::Kind::Train, "a TTOBench train (an object with \"mass\")");
  r.check_keys(root,
               {"metadata",
                "num seats",
                "num coaches",
                "length",
                "mass",
                "rho",
                "max traction power",
                "max reg braking power",
                "max traction force",
                "max reg braking force",
                "max pn braking force",
                "max acceleration",
                "max deceleration",
                "max speed",
                "rolling resistance r0",
                "rolling resistance r1",
                "rolling resistance r2",
                "efficiency traction",
                "efficiency reg brake",
                "tunnel resistance",
                "auxiliary power",
                "ETCS braking data"},
               "");
  r.metadata(root, ttobench::kTrainMetadataKeys);  // other keys: ttobench_metadata_warnings
  const json& meta = r.object(root, "metadata", "");

  physics::Train t;
  t.name = r.string(meta, "id", "metadata");
  t.gravity_m_s2 = ttobench::kGravity_m_s2;
  for (const char* key : {"num seats", "num coaches"}) {
    if (root.contains(key)) positive(r, root, key, {{"-", 1.0}}, true);  // informational
  }
  if (root.contains("length")) t.length_m = positive(r, root, "length", ttobench::kLength);
  t.mass_kg = positive(r, root, "mass", ttobench::kMass);
  if (root.contains("rho")) {
    t.rotating_mass_factor = positive(r, root, "rho", ttobench::kRatio, true);
  }
  // Constant force under a power cap: a one-point table (kN) with the cap (kW).
  const double traction_kW = positive(r, root, "max traction power", ttobench::kPowerKW);
  const double regen_kW = positive(r, root, "max reg braking power", ttobench::kPowerKW);
  const double traction_kN = positive(r, root, "max traction force", ttobench::kForceKN);
  const double regen_kN = positive(r, root, "max reg braking force", ttobench::kForceKN);
  t.traction = physics::ForceEnvelope::table({{0.0, traction_kN}}, traction_kW);
  t.braking = physics::ForceEnvelope::table({{0.0, regen_kN}}, regen_kW);
  if (root.contains("max pn braking force")) {
    t.pneumatic_brake_N = positive(r, root, "max pn braking force", ttobench::kForce, true);
  }
  // Absent comfort limits are no limits: the forces alone bound the acceleration.
  t.max_accel_m_s2 = root.contains("max acceleration")
                         ? positive(r, root, "max acceleration", ttobench::kAcceleration)
                         : std::numeric_limits<double>::infinity();
  t.max_decel_m_s2 = root.contains("max deceleration")
                         ? positive(r, root, "max deceleration", ttobench::kAcceleration)
                         : std::numeric_limits<double>::infinity();
  t.max_speed_ms = ttobench::kmh_to_ms(positive(r, root, "max speed", ttobench::kSpeedKmh));

  const double r0_N = positive(r, root, "rolling resistance r0", ttobench::kForce, true);
  const double r1 = positive(r, root, "rolling resistance r1", ttobench::kLinearDrag, true);
  const double r2 = positive(r, root, "rolling resistance r2", ttobench::kQuadraticDrag, true);
  t.davis.A = ttobench::force_to_specific(r0_N, t);
  t.davis.B = ttobench::force_to_specific(r1, t);
  t.davis.C = ttobench::force_to_specific(r2, t);

  const bool has_traction_eff = root.contains("efficiency traction");
  const bool has_regen_eff = root.contains("efficiency reg brake");
  if (has_traction_eff != has_regen_eff) {
    r.fail(has_traction_eff ? "efficiency reg brake" : "efficiency traction",
           "both efficiencies or neither (TTOBench's rule); got only one");
  }
  // Without efficiencies the energies are mechanical (work at the wheel).
  t.traction_efficiency = has_traction_eff ? efficiency(r, root, "efficiency traction") : 1.0;
  t.regen_efficiency = has_regen_eff ? efficiency(r, root, "efficiency reg brake") : 1.0;

  // Constant auxiliary power, drawn at all times (reported; it changes no optimum at a fixed
  // running time, see physics/train.hpp).
  if (root.contains("auxiliary power")) {
    t.auxiliary_power_W = positive(r, root, "auxiliary power", ttobench::kPower, true);
  }
  if (root.contains("tunnel resistance")) {
    const json& tr = r.object(root, "tunnel resistance", "");
    r.check_keys(tr, {"units", "values"}, "tunnel resistance");
    const json& units = r.object(tr, "units", "tunnel resistance");
    r.check_keys(units, {"cross section", "coefficient"}, "tunnel resistance.units");
    for (const char* k : {"cross section", "coefficient"}) {
      if (!units.contains(k)) r.fail(join("tunnel resistance.units", k), "a unit; got nothing");
    }
    const double area_f = r.unit_factor(units.at("cross section"),
                                        "tunnel resistance.units.cross section", ttobench::kArea);
    const double coef_f = r.unit_factor(
        units.at("coefficient"), "tunnel resistance.units.coefficient", ttobench::kQuadraticDragKN);
    if (!tr.contains("values")) r.fail("tunnel resistance.values", "an array of rows");
    const json& values = r.array(tr.at("values"), "tunnel resistance.values");
    if (values.empty()) r.fail("tunnel resistance.values", "at least one row");
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::string rp = index("tunnel resistance.values", i);
      const json& row = r.array(values[i], rp);
      if (row.size() != 2) r.fail(rp, "a pair [cross section, coefficient]");
      physics::TunnelDrag d;
      d.cross_section_m2 = r.number(row[0], index(rp, 0)) * area_f;
      d.C_kN_per_kmh2 = r.number(row[1], index(rp, 1)) * coef_f;
      if (!(d.cross_section_m2 > 0.0)) r.fail(index(rp, 0), "a cross-section above 0 m^2");
      if (!(d.C_kN_per_kmh2 >= 0.0)) r.fail(index(rp, 1), "a coefficient of at least 0");
      if (!t.tunnel_drag.empty() && !(d.cross_section_m2 > t.tunnel_drag.back().cross_section_m2)) {
        r.fail(index(rp, 0), "cross-sections in increasing order");
      }
      t.tunnel_drag.push_back(d);
    }
  }
  return t;
}

}  // namespace ecorail::data
