#include "fitting/fit_json.hpp"

#include <cmath>

#include "physics/units.hpp"

namespace ecorail::fitting {

namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string method_key(Method m) {
  return m == Method::EquationError ? "equation_error" : "output_error";
}

nlohmann::json formulation_json(const Summary& s, const FormulationSummary& r) {
  nlohmann::json j;
  j["method"] = method_key(r.method);
  nlohmann::json fixed = nlohmann::json::array();
  for (int p = 0; p < kParamCount; ++p) {
    const auto& e = r.params[static_cast<std::size_t>(p)];
    const std::string name(param_name(p));
    j[name] = e.value;
    j[name + "_se"] = e.fixed ? nlohmann::json(nullptr) : number_or_null(e.se);
    if (e.fixed) fixed.push_back(name);
    if (e.at_bound) j[name + "_at_bound"] = true;
  }
  j["fixed_parameters"] = fixed;
  nlohmann::json cov = nlohmann::json::array();
  for (int a = 0; a < kParamCount; ++a) {
    nlohmann::json row = nlohmann::json::array();
    for (int b = 0; b < kParamCount; ++b) {
      row.push_back(number_or_null(r.covariance[static_cast<std::size_t>(a * kParamCount + b)]));
    }
    cov.push_back(row);
  }
  j["covariance"] = cov;
  j["residual_unit"] = r.residual_unit;
  j["sigma"] = r.fit.sigma;
  j["rms"] = r.fit.rms;
  j["max_abs_residual"] = r.fit.max_abs;
  j["residual_count"] = r.fit.residual_count;
  j["discounted_residuals"] = r.fit.discounted_residuals;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& d : r.fit.discounted) {
    rows.push_back({{"log", s.logs.at(static_cast<std::size_t>(d.log_index))},
                    {"row", d.source_row},
                    {"time_s", d.time_s},
                    {"z", d.z},
                    {"weight", d.weight}});
  }
  j["discounted_rows"] = rows;
  nlohmann::json coast = nlohmann::json::array();
  for (double v = 30.0; v <= 70.0 + 1e-9; v += 5.0) {
    const double base = s.base.gravity_m_s2 * s.base.davis_N_per_kN(units::kmh_to_ms(v)) / 1000.0 /
                        (1.0 + s.base.rotating_mass_factor);
    coast.push_back({{"speed_kmh", v},
                     {"fitted_m_s2", r.coasting_decel_m_s2(v, s.base.gravity_m_s2)},
                     {"base_m_s2", base}});
  }
  j["coasting_decel_level"] = coast;
  j["iterations"] = r.fit.iterations;
  j["converged"] = r.fit.converged();
  j["termination"] = std::string(dp::termination_name(r.fit.termination));
  j["solve_time_s"] = r.fit.solve_time_s;
  return j;
}

nlohmann::json form_json(const FormFit& f) {
  nlohmann::json j;
  j["form"] = form_name(f.form);
  j["force_max_kN"] = f.force_max_kN;
  j["force_max_kN_se"] = number_or_null(f.force_max_kN_se);
  j["breakpoint_kmh"] = f.breakpoint_kmh;
  j["breakpoint_kmh_se"] = number_or_null(f.breakpoint_kmh_se);
  if (f.form == EnvelopeForm::Piecewise) {
    nlohmann::json c = nlohmann::json::array(), cse = nlohmann::json::array();
    for (std::size_t i = 0; i < f.coeffs_kN.size(); ++i) {
      c.push_back(f.coeffs_kN[i]);
      cse.push_back(number_or_null(f.coeffs_kN_se[i]));
    }
    j["coeffs_kN"] = c;
    j["coeffs_kN_se"] = cse;
    nlohmann::json l = nlohmann::json::array(), lse = nlohmann::json::array();
    for (std::size_t i = 0; i < f.local_kN.size(); ++i) {
      l.push_back(f.local_kN[i]);
      lse.push_back(number_or_null(f.local_kN_se[i]));
    }
    j["local_coeffs_kN"] = l;
    j["local_coeffs_kN_se"] = lse;
    j["degree"] = static_cast<int>(f.local_kN.size());
  } else {
    j["power_kW"] = f.power_kW;
    j["power_kW_se"] = number_or_null(f.power_kW_se);
  }
  j["parameters"] = f.parameters;
  j["rms_kN"] = f.rms_kN;
  j["max_abs_residual_kN"] = f.max_abs_kN;
  j["rss_kN2"] = f.rss_kN2;
  j["aic"] = f.aic;
  j["bic"] = f.bic;
  j["converged"] = f.converged();
  return j;
}

}  // namespace

nlohmann::json calibration_to_json(const Summary& s) {
  nlohmann::json j = formulation_json(s, s.primary());
  j["logs"] = s.logs;
  nlohmann::json forms;
  for (const auto& r : s.results) forms[method_key(r.method)] = formulation_json(s, r);
  j["formulations"] = forms;
  nlohmann::json intervals;
  intervals["used"] = s.data.used_intervals;
  for (int st = 1; st < kIntervalStatusCount; ++st) {
    intervals[std::string(interval_status_name(static_cast<IntervalStatus>(st)))] =
        s.data.status_counts[st];
  }
  j["intervals"] = intervals;
  j["inferred_braking_rows"] = s.data.inferred_braking_rows;
  nlohmann::json pos = nlohmann::json::array();
  for (const auto& p : s.data.position_issues) {
    pos.push_back({{"log", s.logs.at(static_cast<std::size_t>(p.log_index))},
                   {"row_from", p.row_from},
                   {"row_to", p.row_to},
                   {"logged_m", p.logged_m},
                   {"expected_m", p.expected_m},
                   {"suspect_row",
                    p.suspect_row > 0 ? nlohmann::json(p.suspect_row) : nlohmann::json(nullptr)}});
  }
  j["position_inconsistencies"] = pos;
  j["loss"] = loss_name(s.options.loss);
  j["loss_scale_sigma"] = s.options.loss_scale;
  j["notes"] = s.notes;
  j["total_time_s"] = s.total_time_s;
  j["units"] = {{"davis_A", "N/kN"},
                {"davis_B", "N/kN per km/h"},
                {"davis_C", "N/kN per (km/h)^2"},
                {"mass_t", "t"},
                {"speed", "km/h"}};
  return j;
}

nlohmann::json envelope_fit_to_json(const EnvelopeFitResult& r, EnvelopeKind kind,
                                    EnvelopeForm written) {
  nlohmann::json j = form_json(r.form(written));
  j["kind"] = kind_name(kind);
  j["better_form"] = form_name(r.better);
  j["forms"] = {{"piecewise", form_json(r.piecewise)}, {"constant_power", form_json(r.power)}};
  nlohmann::json res = nlohmann::json::array();
  const FormFit& f = r.form(written);
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    res.push_back({{"row", r.points[i].source_row},
                   {"speed_kmh", r.points[i].speed_kmh},
                   {"force_kN", r.points[i].force_kN},
                   {"fitted_kN", f.fitted_kN[i]},
                   {"residual_kN", r.points[i].force_kN - f.fitted_kN[i]}});
  }
  j["residuals"] = res;
  return j;
}

}  // namespace ecorail::fitting
