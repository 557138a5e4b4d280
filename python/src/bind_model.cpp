// ecorail.Line and ecorail.Train: the reference data compiled in, or files in any format the
// program reads (a line: TOML, a directory of CSVs, a TTOBench track JSON; a train: TOML or a
// TTOBench train JSON).
#include <filesystem>

#include "data/line_loader.hpp"
#include "data/train_io.hpp"
#include "physics/units.hpp"
#include "python/src/common.hpp"

namespace ecorail::python {

namespace {

data::CurveFormula curve_formula(const std::string& name) {
  if (name == "600/R") return data::CurveFormula::Inverse600;
  if (name == "roeckl") return data::CurveFormula::Roeckl;
  bad_argument("curve_resistance", "'600/R' or 'roeckl'", "'" + name + "'");
}

}  // namespace

void bind_model(py::module_& m) {
  py::class_<PyLine>(m, "Line",
                     "A line: stations (km posts in m), gradients (per mille), speed limits "
                     "(km/h) and curves (radius in m).")
      .def_static(
          "reference",
          [](const std::string& curve_resistance) {
            PyLine l{data::default_line(), "embedded"};
            l.line.curve_formula = curve_formula(curve_resistance);
            return l;
          },
          py::arg("curve_resistance") = "600/R",
          "The reference line compiled into the library (data/contest/), as the program's "
          "default.\n\ncurve_resistance: '600/R' or 'roeckl' (500/(R-30) from 300 m, 650/(R-55) "
          "below).")
      .def_static(
          "from_file",
          [](const py::object& path, const std::string& curve_resistance) {
            const std::string p = fspath(path);
            PyLine l{data::load_line(p), p};
            l.line.curve_formula = curve_formula(curve_resistance);
            return l;
          },
          py::arg("path"), py::arg("curve_resistance") = "600/R",
          "A line from a TOML file, a directory of stations/gradients/speed_limits/curves CSVs "
          "or a TTOBench track JSON (docs/formats.md). Bad input raises ValueError naming file, "
          "row and field.")
      .def_property_readonly("name", [](const PyLine& l) { return l.line.name; })
      .def_property_readonly(
          "source", [](const PyLine& l) { return l.source; },
          "'embedded' or the path it was read from (as the reports name it).")
      .def_property_readonly(
          "stations",
          [](const PyLine& l) {
            std::vector<std::string> names;
            for (const auto& s : l.line.stations) names.push_back(s.name);
            return names;
          },
          "Station names in file order.")
      .def_property_readonly(
          "station_km_posts_m",
          [](const PyLine& l) {
            std::vector<double> posts;
            for (const auto& s : l.line.stations) posts.push_back(s.km_post_m);
            return to_numpy(posts);
          },
          "Kilometre posts of the stations in m (float64 array).")
      .def_property_readonly("checksum",
                             [](const PyLine& l) { return data::hex64(l.line.checksum()); })
      .def("__repr__", [](const PyLine& l) {
        return "<ecorail.Line '" + l.line.name + "' from " + l.source + ", " +
               std::to_string(l.line.stations.size()) + " stations>";
      });

  py::class_<PyTrain>(m, "Train", "A train: mass, resistance, traction and braking envelopes.")
      .def_static(
          "reference",
          [] {
            return PyTrain{data::default_train(), "embedded"};
          },
          "The reference train compiled into the library (data/contest/train.toml).")
      .def_static(
          "from_file",
          [](const py::object& path) {
            const std::string p = fspath(path);
            return PyTrain{data::load_train(p), p};
          },
          py::arg("path"),
          "A train from a TOML file or a TTOBench train JSON. Bad input raises ValueError.")
      .def_static(
          "from_toml",
          [](const std::string& text, const std::string& label) {
            return PyTrain{data::parse_train_toml(text, label), label};
          },
          py::arg("text"), py::arg("label") = "<toml>",
          "A train from TOML text (as Train.to_toml writes it); label names it in errors and "
          "reports.")
      .def(
          "to_toml", [](const PyTrain& t) { return data::train_to_toml(t.train); },
          "The train as TOML text (the program's train file format).")
      .def_property_readonly("name", [](const PyTrain& t) { return t.train.name; })
      .def_property_readonly("source", [](const PyTrain& t) { return t.source; })
      .def_property_readonly(
          "mass_t", [](const PyTrain& t) { return t.train.mass_kg / 1000.0; }, "Mass in t.")
      .def_property_readonly(
          "max_speed_kmh", [](const PyTrain& t) { return units::ms_to_kmh(t.train.max_speed_ms); },
          "Maximum speed in km/h.")
      .def_property_readonly(
          "checksum", [](const PyTrain& t) { return data::hex64(data::train_checksum(t.train)); })
      .def("__repr__", [](const PyTrain& t) {
        return "<ecorail.Train '" + t.train.name + "' from " + t.source + ">";
      });
}

}  // namespace ecorail::python
