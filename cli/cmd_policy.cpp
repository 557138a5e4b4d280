// `ecorail policy`: writes the optimal feedback policy of one section (u*, force, cost-to-go and
// time-to-go on the DP grid) as a binary table for on-board advice, optionally as CSV, for the
// time price of one running time or a ladder of them; `--inspect` reads a table back, checks it
// against a line and train and prints the advice at given states. Format: docs/policy_format.md.
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/csv_reader.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "physics/units.hpp"
#include "policy/advisor.hpp"
#include "policy/ladder.hpp"
#include "policy/policy_table.hpp"

namespace ecorail::cli {

namespace {

struct PolicyArgs {
  ProblemOptions problem;
  double time_s = 0.0;
  std::string out, csv, inspect;
  std::vector<double> ladder_s;
  std::vector<std::string> at;
  bool quiet = false;
};

void check_target_dir(const std::string& path, const char* option) {
  if (path.empty()) return;
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir)) {
    throw data::InputError("command line", 0, option, "a file in an existing directory");
  }
}

void print_layers(const policy::PolicyTable& t) {
  std::printf("  %5s %9s %9s %16s %15s %18s\n", "layer", "offset_s", "target_s", "lambda_kJ_per_s",
              "planned_time_s", "planned_energy_kJ");
  for (std::size_t k = 0; k < t.layers.size(); ++k) {
    const auto& L = t.layers[k];
    std::printf("  %5zu %9.3f %9.3f %16.3f %15.3f %18.1f\n", k, L.time_offset_s, L.target_time_s,
                units::J_to_kJ(L.lambda_J_per_s), L.planned_time_s,
                units::J_to_kJ(L.planned_energy_J));
  }
}

void run_write(const PolicyArgs& a) {
  if (a.problem.from.empty() || a.problem.to.empty()) {
    throw data::InputError("command line", 0, a.problem.from.empty() ? "--from" : "--to",
                           "both stations of the section (--from and --to)");
  }
  if (!(a.time_s > 0.0)) {
    throw data::InputError("command line", 0, "--time", "a running time in seconds > 0");
  }
  if (a.out.empty()) throw data::InputError("command line", 0, "--out", "an output file");
  check_target_dir(a.out, "--out");
  check_target_dir(a.csv, "--csv");
  policy::PolicyLadderOptions ladder;
  ladder.nominal_time_s = a.time_s;
  if (!a.ladder_s.empty()) ladder.time_offsets_s = a.ladder_s;
  if (std::set<double>(ladder.time_offsets_s.begin(), ladder.time_offsets_s.end()).size() !=
      ladder.time_offsets_s.size()) {
    throw data::InputError("command line", 0, "--lambda-ladder", "distinct time offsets");
  }
  for (double d : ladder.time_offsets_s) {
    if (!(a.time_s + d > 0.0)) {
      throw data::InputError("command line", 0, "--lambda-ladder",
                             "offsets leaving a positive running time");
    }
  }
  const dp::EngineOptions engine_opts = engine_options(a.problem);
  require_valid(engine_opts);
  require_valid(ladder);

  const Problem p = load_problem(a.problem);
  const dp::SectionEngine engine(p.train, p.route, engine_opts);
  const policy::PolicyTable table = [&] {
    Progress progress("ecorail policy", a.quiet);  // cleared before the table is printed
    ladder.progress = progress.callback();
    return policy::build_policy_ladder(
        engine, {p.line.name, p.line.checksum(), data::train_checksum(p.train)}, ladder);
  }();
  const std::string bytes = policy::encode_policy(table);
  data::write_atomically(a.out, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
  if (!a.csv.empty()) {
    data::write_atomically(a.csv, [&](std::ostream& out) { policy::write_policy_csv(out, table); });
  }
  // Read the file back through the checks an on-board user would apply.
  const policy::Advisor advisor = policy::Advisor::load(a.out, p.line, p.train);
  std::printf(
      "ecorail policy %s -> %s (%.1f m), %s objective: %d stages, %d nodes, grid ds %g m, "
      "dv %g km/h, %zu layer(s)\n",
      table.from.c_str(), table.to.c_str(), table.route_length_m,
      std::string(dp::objective_name(table.objective)).c_str(), table.stage_count(),
      table.node_count(), table.grid_spec.ds_m, table.grid_spec.dv_kmh, table.layers.size());
  print_layers(table);
  std::printf("wrote %s (%zu bytes, format version %u), verified by reloading%s%s\n", a.out.c_str(),
              bytes.size(), policy::kPolicyFormatVersion, a.csv.empty() ? "" : "; CSV ",
              a.csv.c_str());
}

void parse_state(const std::string& text, double* s_m, double* v_kmh) {
  std::istringstream in(text);
  char comma = 0;
  if (!(in >> *s_m >> comma >> *v_kmh) || comma != ',' || !(in >> std::ws).eof()) {
    throw data::InputError("command line", 0, "--at",
                           "S_M,V_KMH (e.g. 300,60); got '" + text + "'");
  }
}

// The message of a library error without the "file: " prefix it starts with.
std::string without_prefix(const std::string& what, const std::string& file) {
  return what.rfind(file + ": ", 0) == 0 ? what.substr(file.size() + 2) : what;
}

void run_inspect(const PolicyArgs& a) {
  std::vector<std::pair<double, double>> states;  // (m, km/h)
  for (const std::string& text : a.at) {
    double s_m = 0.0, v_kmh = 0.0;
    parse_state(text, &s_m, &v_kmh);
    states.emplace_back(s_m, v_kmh);
  }
  const Problem p = load_problem(a.problem);
  policy::PolicyTable table;
  try {
    table = policy::load_policy(a.inspect);
  } catch (const policy::PolicyFormatError& e) {
    throw data::InputError(a.inspect, 0, "",
                           "a readable policy table (" + without_prefix(e.what(), a.inspect) + ")");
  }
  std::printf(
      "policy table %s: format version %u, %s -> %s (%.3f m), line '%s' (checksum 0x%016llx), "
      "train '%s' (checksum 0x%016llx), %s objective, grid ds %g m, dv %g km/h, substep %g m, "
      "%d stages, %d nodes, %zu layer(s)\n",
      a.inspect.c_str(), policy::kPolicyFormatVersion, table.from.c_str(), table.to.c_str(),
      table.route_length_m, table.line_name.c_str(),
      static_cast<unsigned long long>(table.line_checksum), table.train_name.c_str(),
      static_cast<unsigned long long>(table.train_checksum),
      std::string(dp::objective_name(table.objective)).c_str(), table.grid_spec.ds_m,
      table.grid_spec.dv_kmh, table.grid_spec.substep_m, table.stage_count(), table.node_count(),
      table.layers.size());
  print_layers(table);
  std::unique_ptr<policy::Advisor> advisor;
  try {
    advisor = std::make_unique<policy::Advisor>(std::move(table), p.line, p.train);
  } catch (const policy::PolicyMismatchError& e) {
    throw data::InputError(
        a.inspect, 0, "", std::string("a policy table for this line and train (") + e.what() + ")");
  }
  std::printf("matches line '%s' and train '%s'\n", p.line.name.c_str(), p.train.name.c_str());
  // A state outside the section or the train's speeds has no advice: an error, not a guess.
  for (std::size_t i = 0; i < states.size(); ++i) {
    const auto [s_m, v_kmh] = states[i];
    const double length_m = advisor->table().route_length_m;
    const double vmax_kmh = units::ms_to_kmh(p.train.max_speed_ms);
    if (!(s_m >= 0.0 && s_m <= length_m)) {
      throw data::InputError("command line", 0, "--at",
                             "a position from 0 to the section length " +
                                 data::format_number(length_m) + " m; got '" + a.at[i] + "'");
    }
    if (!(v_kmh >= 0.0 && v_kmh <= vmax_kmh)) {
      throw data::InputError("command line", 0, "--at",
                             "a speed from 0 to the train's maximum speed " +
                                 data::format_number(vmax_kmh) + " km/h; got '" + a.at[i] + "'");
    }
  }
  for (const auto& [s_m, v_kmh] : states) {
    for (std::size_t k = 0; k < advisor->table().layers.size(); ++k) {
      const policy::Advice adv = advisor->advise(static_cast<int>(k), s_m, units::kmh_to_ms(v_kmh));
      if (!adv.feasible) {
        std::printf("at %.2f m, %.2f km/h, layer %zu: no control reaches the stop\n", s_m, v_kmh,
                    k);
        continue;
      }
      std::printf(
          "at %.2f m, %.2f km/h, layer %zu: %s (%s, %.2f kN); expected time to go %.3f s, "
          "energy to go %.1f kJ, cost to go %.1f kJ\n",
          s_m, v_kmh, k, std::string(physics::control_name(adv.control)).c_str(),
          std::string(physics::regime_name(adv.regime)).c_str(), units::N_to_kN(adv.force_N),
          adv.time_to_go_s, units::J_to_kJ(adv.energy_to_go_J), units::J_to_kJ(adv.cost_to_go_J));
    }
  }
}

}  // namespace

void add_policy_command(CLI::App& app) {
  auto args = std::make_shared<PolicyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "policy", "optimal feedback policy table of a section (for on-board advice)");
  add_problem_options(cmd, args->problem, false);
  auto* time = cmd->add_option("--time", args->time_s, "nominal running time in s");
  auto* out = cmd->add_option("--out", args->out, "binary policy table to write");
  auto* csv = cmd->add_option("--csv", args->csv, "also write the table as CSV");
  auto* ladder =
      cmd->add_option("--lambda-ladder", args->ladder_s,
                      "time offsets in s, e.g. --lambda-ladder -5,0,5: one layer per running "
                      "time --time + offset (a late train uses a negative offset)")
          ->delimiter(',');
  auto* inspect = cmd->add_option("--inspect", args->inspect,
                                  "read a policy table, check it against --line/--train, print it");
  inspect->excludes(time)->excludes(out)->excludes(csv)->excludes(ladder);
  input_files(cmd, {"--inspect"});
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr");
  cmd->add_option("--at", args->at, "with --inspect: advice at S_M,V_KMH (repeatable)")
      ->needs(inspect);
  cmd->callback([args] {
    if (!args->inspect.empty()) {
      run_inspect(*args);
    } else {
      run_write(*args);
    }
  });
}

}  // namespace ecorail::cli
