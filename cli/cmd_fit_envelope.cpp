// `ecorail fit-envelope`: fits the piecewise and the constant-power forms of a traction or
// braking envelope to (speed, force) points, prints both with standard errors and information
// criteria, and writes the chosen form into a train file the engine reads (docs/calibration.md).
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/output_options.hpp"
#include "data/atomic_file.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "fitting/envelope_fit.hpp"
#include "fitting/fit_json.hpp"
#include "output/run_json.hpp"
#include "physics/units.hpp"

namespace ecorail::cli {

namespace {

struct FitEnvelopeArgs {
  std::string points;
  std::string kind;
  std::string out;
  std::string train;
  std::string json;
  std::string form = "best";
  int degree = 0;  // 0: 3 for traction, 2 for braking
};

void run_fit_envelope(const FitEnvelopeArgs& a) {
  using namespace fitting;
  check_output_targets({{"--out", a.out, false}, {"--json", a.json, false}});
  // With an output on standard output ("-") the report goes to standard error.
  std::ostream& report =
      data::is_stdout_path(a.out) || data::is_stdout_path(a.json) ? std::cerr : std::cout;
  const EnvelopeKind kind = a.kind == "braking" ? EnvelopeKind::Braking : EnvelopeKind::Traction;
  const physics::Train base = a.train.empty() ? data::default_train() : data::load_train(a.train);
  const std::vector<EnvelopePoint> points = read_envelope_points(a.points);
  EnvelopeFitOptions options;
  options.degree = a.degree > 0 ? a.degree : (kind == EnvelopeKind::Traction ? 3 : 2);
  options.label = a.points;
  const EnvelopeFitResult result = fit_envelope(points, options);
  const EnvelopeForm written = a.form == "piecewise" ? EnvelopeForm::Piecewise
                               : a.form == "power"   ? EnvelopeForm::ConstantPower
                                                     : result.better;
  report << result.report(kind);
  report << "form written: " << form_name(written) << "\n";
  const FormFit& fit = result.form(written);
  if (!fit.converged()) {
    throw std::runtime_error(std::string(form_name(written)) +
                             " fit did not converge: nothing written");
  }

  // The train the fit makes, read back through the loader `solve` uses: a fit that converged
  // to an envelope no run can use (forces all 0, a train that cannot start) is bad input, and
  // neither file is written.
  const physics::Train t = train_with_envelope(base, points, fit, kind);
  const std::string toml = data::train_to_toml(t);
  const std::string label =
      a.out.empty() || data::is_stdout_path(a.out) ? "the fitted train" : a.out;
  try {
    data::parse_train_toml(toml, label);
  } catch (const data::InputError& e) {
    throw data::InputError(a.points, 0, "force_kN",
                           "points whose fitted " + std::string(a.kind) +
                               " envelope makes a train the program can run; the " +
                               std::string(form_name(written)) + " fit gives one that " + label +
                               " would refuse (field '" + e.field() + "': " + e.expected() +
                               "); nothing written");
  }

  data::OutputBatch batch;  // both files or neither
  if (!a.out.empty()) {
    batch.add(a.out, [&](std::ostream& out) { out << toml; });
  }
  if (!a.json.empty()) {
    const nlohmann::json j = envelope_fit_to_json(result, kind, written);
    batch.add(a.json, [&](std::ostream& out) { output::write_json(out, j); });
  }
  batch.commit();
  if (!a.out.empty()) report << "wrote " << a.out << "\n";
  if (!a.json.empty()) report << "wrote " << a.json << "\n";
}

}  // namespace

void add_fit_envelope_command(CLI::App& app) {
  auto args = std::make_shared<FitEnvelopeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "fit-envelope",
      "fit a traction or braking envelope (piecewise and constant-power forms) to (speed, force) "
      "points and write it into a train file");
  cmd->add_option("--points", args->points, "CSV of points with columns speed_kmh, force_kN")
      ->required();
  cmd->add_option("--kind", args->kind, "which envelope the points describe: traction or braking")
      ->required()
      ->check(CLI::IsMember({"traction", "braking"}));
  cmd->add_option("--out", args->out,
                  "train file to write: the base train with the fitted envelope (TOML)");
  cmd->add_option("--train", args->train, "base train (default: the reference train)");
  cmd->add_option("--json", args->json,
                  "write the fit as JSON (breakpoint_kmh, coefficients, standard errors, "
                  "residuals)");
  cmd->add_option("--degree", args->degree,
                  "degree of the polynomial above the breakpoint (default 3 for traction, 2 for "
                  "braking)");
  cmd->add_option("--form", args->form,
                  "form written: best (lower BIC), piecewise or power (default best)")
      ->check(CLI::IsMember({"best", "piecewise", "power"}));
  input_files(cmd, {"--points", "--train"});
  cmd->callback([args] { run_fit_envelope(*args); });
}

}  // namespace ecorail::cli
