#include "output/profile_writers.hpp"

#include <xlsxwriter.h>

#include <cstdio>
#include <stdexcept>

#include "data/atomic_file.hpp"
#include "physics/units.hpp"

namespace ecorail::output {

namespace {

const std::vector<std::string> kColumns = {"time_hms",
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
                                           "dwelling"};

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

}  // namespace

void write_profile_csv(const std::filesystem::path& path, const Timeline& rows) {
  data::write_atomically(path, [&](std::ostream& out) {
    for (std::size_t i = 0; i < kColumns.size(); ++i) out << (i ? "," : "") << kColumns[i];
    out << "\n";
    char buf[512];
    for (const auto& r : rows) {
      const Cells c = cells(r);
      std::snprintf(
          buf, sizeof buf, "%s,%.1f,%.2f,%.3f,%.2f,%.2f,%.3f,%.2f,%.1f,%.3f,%.2f,%.1f,%s,%d,%d\n",
          format_hms(r.t_s).c_str(), c.speed_cm_s, c.speed_kmh, r.accel_m_s2, r.s_m, r.km_post_m,
          r.gradient_permille, c.traction_kN, c.power_kW, r.t_s, c.braking_kN, c.limit_kmh,
          regime_label(r).c_str(), r.section + 1, r.dwelling ? 1 : 0);
      out << buf;
    }
  });
}

void write_profile_xlsx(const std::filesystem::path& path, const Timeline& rows,
                        const SummaryRows& summary) {
  data::produce_atomically(path, [&](const std::filesystem::path& tmp) {
    lxw_workbook* book = workbook_new(tmp.c_str());
    if (!book) throw std::runtime_error("libxlsxwriter could not create the workbook");
    lxw_worksheet* sheet = workbook_add_worksheet(book, "profile");
    lxw_format* bold = workbook_add_format(book);
    format_set_bold(bold);
    for (std::size_t i = 0; i < kColumns.size(); ++i) {
      worksheet_write_string(sheet, 0, static_cast<lxw_col_t>(i), kColumns[i].c_str(), bold);
    }
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
      ++row;
    }
    lxw_worksheet* info = workbook_add_worksheet(book, "summary");
    lxw_row_t i = 0;
    for (const auto& [key, value] : summary) {
      worksheet_write_string(info, i, 0, key.c_str(), bold);
      worksheet_write_string(info, i, 1, value.c_str(), nullptr);
      ++i;
    }
    if (workbook_close(book) != LXW_NO_ERROR) {
      throw std::runtime_error("libxlsxwriter could not write the workbook");
    }
  });
}

}  // namespace ecorail::output
