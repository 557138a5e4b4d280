// Summary::BriefReport and Summary::FullReport: the calibration report in the manner of Ceres'
// solver summary (docs/calibration.md shows one).
#include <algorithm>
#include <cmath>
#include <string>

#include "base/format_text.hpp"
#include "fitting/calibration.hpp"
#include "physics/units.hpp"

namespace ecorail::fitting {

namespace {

std::string pad(std::string s, std::size_t w) {
  if (s.size() < w) s.append(w - s.size(), ' ');
  return s;
}

std::string lpad(std::string s, std::size_t w) {
  if (s.size() < w) s.insert(0, w - s.size(), ' ');
  return s;
}

std::string value_se(const ParameterEstimate& e) {
  std::string s = format_text("%.6g", e.value);
  if (e.fixed) return s + " (fixed)";
  if (std::isnan(e.se)) return s + " +- ?";
  return s + " +- " + format_text("%.2g", e.se);
}

std::string row_ref(const Summary& s, const DiscountedRow& d) {
  return s.logs.at(static_cast<std::size_t>(d.log_index)) + ":" + std::to_string(d.source_row);
}

}  // namespace

std::string Summary::BriefReport() const {
  std::string out;
  for (const auto& r : results) {
    out += "Calibration (" + std::string(method_name(r.method)) + "): ";
    out += std::to_string(r.fit.residual_count) + " residuals, ";
    out += std::to_string(r.fit.discounted.size()) + " rows discounted, ";
    bool first = true;
    for (int p = 0; p < kParamCount; ++p) {
      const auto& e = r.params[static_cast<std::size_t>(p)];
      if (e.fixed) continue;
      out += (first ? "" : ", ") + std::string(param_name(p)) + " " + value_se(e);
      first = false;
    }
    out += ", sigma " + format_text("%.3g", r.fit.sigma) + " " + r.residual_unit;
    out += ", " + std::string(dp::termination_name(r.fit.termination)) + "\n";
  }
  return out;
}

std::string Summary::FullReport() const {
  std::string out = "\nCalibration report\n\n";
  out += "Logs\n";
  for (std::size_t i = 0; i < data.logs.size(); ++i) {
    out += "  " + logs[i] + ": " + std::to_string(data.logs[i].rows.size()) + " rows\n";
  }
  out += "Intervals between consecutive rows: " + std::to_string(data.used_intervals) + " used";
  for (int st = 1; st < kIntervalStatusCount; ++st) {
    if (data.status_counts[st] == 0) continue;
    out += ", " + std::to_string(data.status_counts[st]) + " excluded (" +
           std::string(interval_status_name(static_cast<IntervalStatus>(st))) + ")";
  }
  out += "\n";
  if (data.inferred_braking_rows > 0) {
    out += "  " + std::to_string(data.inferred_braking_rows) +
           " zero-traction rows decelerate beyond coasting and the log has no braking force: "
           "taken as braking with unknown force\n";
  }
  out += "  speeds " + format_text("%.1f", data.min_speed_kmh) + " to " +
         format_text("%.1f", data.max_speed_kmh) + " km/h; gradient " +
         format_text("%.1f", data.min_gradient_permille) + " to " +
         format_text("%.1f", data.max_gradient_permille) + " per mille (" +
         std::to_string(data.gradient_intervals) + " intervals on a gradient); " +
         std::to_string(data.force_intervals) + " intervals with known traction or braking force\n";
  if (!data.position_issues.empty()) {
    out += "Positions that disagree with the logged speeds (" +
           std::to_string(data.position_issues.size()) + " intervals; not used by the fit):\n";
    const std::size_t shown = std::min<std::size_t>(data.position_issues.size(), 12);
    for (std::size_t i = 0; i < shown; ++i) {
      const auto& p = data.position_issues[i];
      out += "  " + logs.at(static_cast<std::size_t>(p.log_index)) + ": rows " +
             std::to_string(p.row_from) + "-" + std::to_string(p.row_to) + ": advances " +
             format_text("%.1f", p.logged_m) + " m, speeds cover " +
             format_text("%.1f", p.expected_m) + " m";
      if (p.suspect_row > 0) out += " (row " + std::to_string(p.suspect_row) + " out of line)";
      out += "\n";
    }
    if (shown < data.position_issues.size()) {
      out += "  ... and " + std::to_string(data.position_issues.size() - shown) + " more\n";
    }
  }
  out += "Robust loss: " + std::string(loss_name(options.loss)) + " at " +
         format_text("%.3g", options.loss_scale) + " sigma; rows weighted below " +
         format_text("%.2g", options.discount_weight) + " are reported as discounted\n";

  for (const auto& r : results) {
    out += "\n" + std::string(method_name(r.method)) + " (residual: " +
           (r.method == Method::EquationError ? "mean acceleration over an interval"
                                              : "speed at a row") +
           ", " + r.residual_unit + ")\n";
    out += "  " + pad("parameter", 22) + lpad("value", 13) + lpad("std. error", 12) +
           lpad("start", 12) + "   bounds\n";
    for (int p = 0; p < kParamCount; ++p) {
      const auto& e = r.params[static_cast<std::size_t>(p)];
      std::string line =
          "  " + pad(std::string(param_name(p)), 22) + lpad(format_text("%.6g", e.value), 13);
      line += lpad(e.fixed ? "fixed" : std::isnan(e.se) ? "?" : format_text("%.3g", e.se), 12);
      line += lpad(format_text("%.6g", e.start), 12);
      if (!e.fixed) {
        line += "   [" + format_text("%.4g", e.lower) + ", " + format_text("%.4g", e.upper) + "]";
        if (e.at_bound) line += " at bound";
      }
      out += line + "  " + std::string(param_unit(p)) + "\n";
    }
    out += "  noise scale sigma " + format_text("%.4g", r.fit.sigma) + " " + r.residual_unit +
           " (1.4826 x median |residual|); rms " + format_text("%.4g", r.fit.rms) +
           ", max |residual| " + format_text("%.4g", r.fit.max_abs) + " over " +
           std::to_string(r.fit.residual_count) + " residuals; " +
           std::to_string(r.fit.discounted_residuals) + " discounted\n";
    out += "  discounted rows (" + std::to_string(r.fit.discounted.size()) + ")";
    const std::size_t shown = std::min<std::size_t>(r.fit.discounted.size(), 30);
    for (std::size_t i = 0; i < shown; ++i) {
      const auto& d = r.fit.discounted[i];
      out += (i % 3 == 0 ? "\n    " : "   ") + row_ref(*this, d) + " (t " +
             format_text("%.0f", d.time_s) + " s, " + format_text("%+.1f", d.z) + " sigma)";
    }
    if (shown < r.fit.discounted.size()) {
      out += "\n    ... and " + std::to_string(r.fit.discounted.size() - shown) + " more";
    }
    out += "\n  coasting deceleration on level track, m/s^2 (fitted / base train):";
    for (double v = 30.0; v <= 70.0 + 1e-9; v += 10.0) {
      const double base_d = base.gravity_m_s2 * base.davis_N_per_kN(units::kmh_to_ms(v)) / 1000.0 /
                            (1.0 + base.rotating_mass_factor);
      out += "  " + format_text("%.0f", v) + " km/h " +
             format_text("%.4f", r.coasting_decel_m_s2(v, base.gravity_m_s2)) + "/" +
             format_text("%.4f", base_d);
    }
    out += "\n  Ceres: " + r.fit.ceres_brief + "\n";
    out += "  " + std::to_string(r.fit.iterations) + " iterations over all passes, " +
           format_text("%.3f", r.fit.solve_time_s) + " s\n";
  }
  if (!notes.empty()) {
    out += "\nNotes\n";
    for (const auto& n : notes) out += "  - " + n + "\n";
  }
  out += "\nTotal time " + format_text("%.3f", total_time_s) + " s\n";
  return out;
}

}  // namespace ecorail::fitting
