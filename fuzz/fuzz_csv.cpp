// The CSV reader every table goes through (timetable headways and departures, logs, points,
// line tables): parsed, every field read as text and as a number, column lookup by name.
#include "data/csv_reader.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::refuse_cleanly([&] {
    const data::CsvTable t = data::CsvTable::parse(fuzz::as_text(data, size), "table.csv");
    for (const auto& row : t.rows()) {
      for (std::size_t c = 0; c < t.header().size(); ++c) {
        t.text(row, c);
        fuzz::refuse_cleanly([&] { t.number(row, c); });
      }
    }
    t.column("headway_s");
  });
  return 0;
}
