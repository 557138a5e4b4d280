#include "output/profile_writers.hpp"

#include <xlsxwriter.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "data/atomic_file.hpp"
#include "data/version.hpp"
#include "output/quiet_stderr.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

struct Cells {
  double speed_cm_s, speed_kmh, traction_kN, power_kW, braking_kN, limit_kmh;
};

Cells cells(const TimelinePoint& r) {
  const double traction_N = std::max(0.0, r.force_N);
  return {r.v_ms * 100.0,
          units::ms_to_kmh(r.v_ms),
          units::N_to_kN(traction_N),
          traction_N * r.v_ms / 1000.0,
          units::N_to_kN(std::max(0.0, -r.force_N)),
          units::ms_to_kmh(r.speed_limit_ms)};
}

std::string regime_label(const TimelinePoint& r) {
  return r.dwelling ? "dwell" : std::string(physics::regime_name(r.regime));
}

// Column width in characters: the header's, at least 10 (wide enough for the numbers).
double column_width(const std::string& header) {
  return std::max<double>(10.0, static_cast<double>(header.size()) + 2.0);
}

}  // namespace

const std::vector<std::string>& profile_columns() {
  static const std::vector<std::string> columns = {"time_hms",
                                                   "speed_cm_s",
                                                   "speed_kmh",
                                                   "accel_m_s2",
                                                   "distance_m",
                                                   "km_post_m",
                                                   "gradient_permille",
                                                   "traction_force_kN",
                                                   "traction_power_kW",
                                                   "time_s",
                                                   "braking_force_kN",
                                                   "speed_limit_kmh",
                                                   "regime",
                                                   "section",
                                                   "dwelling",
                                                   "curve_radius_m"};
  return columns;
}

void write_profile_csv(std::ostream& out, const Timeline& rows) {
  const auto& columns = profile_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  char buf[512];
  for (const auto& r : rows) {
    const Cells c = cells(r);
    std::snprintf(buf, sizeof buf,
                  "%s,%.1f,%.2f,%.3f,%.2f,%.2f,%.3f,%.2f,%.1f,%.3f,%.2f,%.1f,%s,%d,%d,%.1f\n",
                  format_hms(r.t_s).c_str(), c.speed_cm_s, c.speed_kmh, r.accel_m_s2, r.s_m,
                  r.km_post_m, r.gradient_permille, c.traction_kN, c.power_kW, r.t_s, c.braking_kN,
                  c.limit_kmh, regime_label(r).c_str(), r.section + 1, r.dwelling ? 1 : 0,
                  r.curve_radius_m);
    out << buf;
  }
}

void write_profile_xlsx_file(const std::filesystem::path& file, const Timeline& rows,
                             const SummaryRows& summary) {
  lxw_workbook* book = workbook_new(file.c_str());
  if (!book) throw std::runtime_error("libxlsxwriter could not create the workbook");
  lxw_worksheet* sheet = workbook_add_worksheet(book, "profile");
  lxw_format* bold = workbook_add_format(book);
  format_set_bold(bold);
  const auto& columns = profile_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const auto col = static_cast<lxw_col_t>(i);
    worksheet_write_string(sheet, 0, col, columns[i].c_str(), bold);
    worksheet_set_column(sheet, col, col, column_width(columns[i]), nullptr);
  }
  worksheet_freeze_panes(sheet, 1, 0);  // the header stays visible while scrolling
  lxw_row_t row = 1;
  for (const auto& r : rows) {
    const Cells c = cells(r);
    const double values[] = {c.speed_cm_s, c.speed_kmh,         r.accel_m_s2,  r.s_m,
                             r.km_post_m,  r.gradient_permille, c.traction_kN, c.power_kW,
                             r.t_s,        c.braking_kN,        c.limit_kmh};
    worksheet_write_string(sheet, row, 0, format_hms(r.t_s).c_str(), nullptr);
    for (std::size_t i = 0; i < std::size(values); ++i) {
      worksheet_write_number(sheet, row, static_cast<lxw_col_t>(i + 1), values[i], nullptr);
    }
    worksheet_write_string(sheet, row, 12, regime_label(r).c_str(), nullptr);
    worksheet_write_number(sheet, row, 13, r.section + 1, nullptr);
    worksheet_write_number(sheet, row, 14, r.dwelling ? 1 : 0, nullptr);
    worksheet_write_number(sheet, row, 15, r.curve_radius_m, nullptr);
    ++row;
  }

  lxw_worksheet* info = workbook_add_worksheet(book, "summary");
  worksheet_write_string(info, 0, 0, "quantity", bold);
  worksheet_write_string(info, 0, 1, "value", bold);
  worksheet_freeze_panes(info, 1, 0);
  std::size_t key_width = 8, text_width = 12;
  lxw_row_t i = 1;
  auto write_row = [&](const SummaryRow& r) {
    worksheet_write_string(info, i, 0, r.key.c_str(), bold);
    key_width = std::max(key_width, r.key.size());
    if (const auto* text = std::get_if<std::string>(&r.value)) {
      worksheet_write_string(info, i, 1, text->c_str(), nullptr);
      text_width = std::max(text_width, text->size());
    } else if (const auto* number = std::get_if<double>(&r.value)) {
      worksheet_write_number(info, i, 1, *number, nullptr);
    } else {
      worksheet_write_number(info, i, 1, static_cast<double>(std::get<std::int64_t>(r.value)),
                             nullptr);
    }
    ++i;
  };
  for (const auto& r : summary) write_row(r);
  write_row({"program", data::version_string()});
  worksheet_set_column(info, 0, 0, static_cast<double>(key_width) + 2.0, nullptr);
  worksheet_set_column(info, 1, 1, static_cast<double>(std::min<std::size_t>(text_width, 60)) + 2.0,
                       nullptr);

  lxw_error closed;
  {
    const QuietStderr quiet;  // libxlsxwriter prints its own "[ERROR]" lines; we report once
    closed = workbook_close(book);
  }
  if (closed != LXW_NO_ERROR) {
    throw std::runtime_error(std::string("libxlsxwriter could not write the workbook: ") +
                             lxw_strerror(closed));
  }
}

void write_profile_csv(const std::filesystem::path& path, const Timeline& rows) {
  data::write_atomically(path, [&](std::ostream& out) { write_profile_csv(out, rows); });
}

void write_profile_xlsx(const std::filesystem::path& path, const Timeline& rows,
                        const SummaryRows& summary) {
  data::produce_atomically(
      path, [&](const std::filesystem::path& tmp) { write_profile_xlsx_file(tmp, rows, summary); });
}

}  // namespace ecorail::output
