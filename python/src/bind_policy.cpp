// ecorail.policy_table: the on-board policy table of one section (one layer per running time),
// as `ecorail policy --out` writes it; its bytes are the file's (docs/policy_format.md).
#include <sstream>

#include "data/route_builder.hpp"
#include "data/train_io.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"
#include "policy/policy_table.hpp"
#include "python/src/common.hpp"

namespace ecorail::python {

namespace {

struct PyPolicy {
  policy::PolicyTable table;
  data::Line line;
  physics::Train train;
};

PyPolicy policy_table_py(const PyLine& line, const PyTrain& train, const std::string& from,
                         const std::string& to, double time_s, const std::vector<double>& ladder_s,
                         double ds_m, double dv_kmh, const std::string& objective,
                         const std::string& cruise, int threads, const py::object& progress) {
  if (!(time_s > 0.0))
    bad_argument("time_s", "a running time in seconds > 0", std::to_string(time_s));
  policy::PolicyLadderOptions ladder;
  ladder.nominal_time_s = time_s;
  if (!ladder_s.empty()) ladder.time_offsets_s = ladder_s;
  const dp::EngineOptions engine_opts =
      engine_options({ds_m, dv_kmh, objective, cruise, threads}, train);
  require_valid(engine_opts);
  require_valid(ladder);
  const physics::Route route = data::build_route(line.line, from, to, train.train);
  Interruptible guard(progress);
  ladder.progress = guard.callback();
  policy::PolicyTable table = guard.run([&] {
    const dp::SectionEngine engine(train.train, route, engine_opts);
    return policy::build_policy_ladder(
        engine, {line.line.name, line.line.checksum(), data::train_checksum(train.train)}, ladder);
  });
  return {std::move(table), line.line, train.train};
}

}  // namespace

void bind_policy(py::module_& m) {
  py::class_<PyPolicy>(m, "PolicyTable",
                       "An optimal feedback policy of one section on the DP grid: per layer "
                       "(running time) the control, force, cost-to-go and time-to-go at every "
                       "node. to_bytes() is the binary table `ecorail policy --out` writes.")
      .def(
          "to_bytes", [](const PyPolicy& p) { return py::bytes(policy::encode_policy(p.table)); },
          "The binary table (docs/policy_format.md), byte for byte the program's file.")
      .def(
          "save",
          [](const PyPolicy& p, const std::string& path) { policy::save_policy(p.table, path); },
          py::arg("path"), "Writes the binary table atomically.")
      .def(
          "to_csv",
          [](const PyPolicy& p) {
            std::ostringstream out;
            policy::write_policy_csv(out, p.table);
            return out.str();
          },
          "The table as CSV text (as `ecorail policy --csv`).")
      .def_property_readonly("from_", [](const PyPolicy& p) { return p.table.from; })
      .def_property_readonly("to", [](const PyPolicy& p) { return p.table.to; })
      .def_property_readonly("route_length_m",
                             [](const PyPolicy& p) { return p.table.route_length_m; })
      .def_property_readonly("stage_count", [](const PyPolicy& p) { return p.table.stage_count(); })
      .def_property_readonly("node_count", [](const PyPolicy& p) { return p.table.node_count(); })
      .def_property_readonly(
          "stage_position_m", [](const PyPolicy& p) { return to_numpy(p.table.position_m); },
          "Decision positions in m (float64).")
      .def_property_readonly(
          "layers",
          [](const PyPolicy& p) {
            py::list list;
            for (const auto& L : p.table.layers) {
              py::dict d;
              d["time_offset_s"] = L.time_offset_s;
              d["target_time_s"] = L.target_time_s;
              d["lambda_kJ_per_s"] = units::J_to_kJ(L.lambda_J_per_s);
              d["planned_time_s"] = L.planned_time_s;
              d["planned_energy_kJ"] = units::J_to_kJ(L.planned_energy_J);
              list.append(d);
            }
            return list;
          },
          "One dict per layer: time_offset_s, target_time_s, lambda_kJ_per_s, planned_time_s, "
          "planned_energy_kJ.")
      .def(
          "advise",
          [](const PyPolicy& p, double s_m, double speed_kmh, int layer) {
            const policy::Advisor advisor(p.table, p.line, p.train);
            const int k = layer < 0 ? p.table.nominal_layer() : layer;
            if (k >= static_cast<int>(p.table.layers.size())) {
              bad_argument("layer", "0 to " + std::to_string(p.table.layers.size() - 1),
                           std::to_string(layer));
            }
            if (!(s_m >= 0.0 && s_m <= p.table.route_length_m)) {
              bad_argument("s_m", "a position from 0 to the section length", std::to_string(s_m));
            }
            if (!(speed_kmh >= 0.0 && speed_kmh <= units::ms_to_kmh(p.train.max_speed_ms))) {
              bad_argument("speed_kmh", "a speed from 0 to the train's maximum",
                           std::to_string(speed_kmh));
            }
            const policy::Advice a = advisor.advise(k, s_m, units::kmh_to_ms(speed_kmh));
            py::dict d;
            d["feasible"] = a.feasible;
            d["control"] = std::string(physics::control_name(a.control));
            d["regime"] = std::string(physics::regime_name(a.regime));
            d["force_kN"] = units::N_to_kN(a.force_N);
            d["time_to_go_s"] = a.time_to_go_s;
            d["energy_to_go_kJ"] = units::J_to_kJ(a.energy_to_go_J);
            d["cost_to_go_kJ"] = units::J_to_kJ(a.cost_to_go_J);
            return d;
          },
          py::arg("s_m"), py::arg("speed_kmh"), py::arg("layer") = -1,
          "Advice at position s_m (m) and speed speed_kmh (km/h) from a layer (default: the "
          "nominal one), as `ecorail policy --inspect --at`.");

  m.def("policy_table", &policy_table_py, py::arg("line"), py::arg("train"), py::kw_only(),
        py::arg("from_"), py::arg("to"), py::arg("time_s"),
        py::arg("ladder_s") = std::vector<double>{}, py::arg("ds_m") = 5.0, py::arg("dv_kmh") = 0.2,
        py::arg("objective") = "traction", py::arg("cruise") = "hold", py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        "The policy table of section from_ -> to for running time time_s (s), as `ecorail "
        "policy`: one layer per offset in ladder_s (s; default [0]; a late train follows a "
        "negative offset). Grid, objective, cruise and threads as in solve.");
}

}  // namespace ecorail::python
