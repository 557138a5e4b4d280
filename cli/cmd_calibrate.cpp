// `ecorail calibrate`: estimates the Davis coefficients, the rotating-mass factor and a gradient
// scale (optionally mass and a traction scale) from per-second logs by equation error and by
// output error with Ceres, prints a report in the manner of Ceres' summary, and writes a
// calibrated train file and a JSON record of the fit (docs/calibration.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output_options.hpp"
#include "cli/progress_line.hpp"
#include "data/atomic_file.hpp"
#include "data/input_error.hpp"
#include "data/train_io.hpp"
#include "dp/threads.hpp"
#include "fitting/calibration.hpp"
#include "fitting/fit_json.hpp"
#include "fitting/log_reader.hpp"
#include "output/run_json.hpp"

namespace ecorail::cli {

namespace {

struct CalibrateArgs {
  bool quiet = false;
  std::vector<std::string> logs;
  std::string train;
  std::string out;
  std::string json;
  std::string method = "both";
  std::vector<std::string> fix;
  bool fit_mass = false;
  bool fit_traction_scale = false;
  std::string gradient_scale = "auto";
  std::string loss = "cauchy";
  double loss_scale = 2.5;
  int segment_rows = 10;
  int max_iterations = fitting::CalibrationOptions{}.max_iterations;  // per pass
  int threads = 1;
  bool brief = false;
  bool no_accel_limits = false;
};

void run_calibrate(const CalibrateArgs& a) {
  using namespace fitting;
  // Before the fit, which can take minutes: a bad --out or --json is known now.
  check_output_targets({{"--out", a.out, false}, {"--json", a.json, false}});
  // With an output on standard output ("-") the report goes to standard error.
  std::ostream& report =
      data::is_stdout_path(a.out) || data::is_stdout_path(a.json) ? std::cerr : std::cout;
  CalibrationOptions o;
  o.method = a.method == "equation" ? Method::EquationError
             : a.method == "output" ? Method::OutputError
                                    : Method::Both;
  o.loss = a.loss == "huber"  ? LossKind::Huber
           : a.loss == "none" ? LossKind::None
                              : LossKind::Cauchy;
  if (!(a.loss_scale > 0.0)) {
    throw data::InputError("command line", 0, "--loss-scale", "a loss scale above 0 (sigmas)");
  }
  o.loss_scale = a.loss_scale;
  for (const auto& name : a.fix) {
    const auto p = param_from_name(name);
    if (!p) {
      ParamFlags all{};
      all.fill(true);
      throw data::InputError("command line", 0, "--fix",
                             "one of " + param_list(all) + "; got '" + name + "'");
    }
    o.fixed[static_cast<std::size_t>(*p)] = true;
  }
  o.fit_mass = a.fit_mass;
  o.fit_traction_scale = a.fit_traction_scale;
  o.gradient_scale = a.gradient_scale == "fit"     ? GradientScaleMode::Fit
                     : a.gradient_scale == "fixed" ? GradientScaleMode::Fixed
                                                   : GradientScaleMode::Auto;
  if (a.segment_rows < 1) {
    throw data::InputError("command line", 0, "--segment-rows", "at least 1 row per segment");
  }
  o.output_error.segment_rows = a.segment_rows;
  if (a.max_iterations < 1) {
    throw data::InputError("command line", 0, "--max-iterations", "at least 1 iteration");
  }
  o.max_iterations = a.max_iterations;
  if (a.threads > dp::kMaxThreads) {
    throw data::InputError("command line", 0, "--threads",
                           "at most " + std::to_string(dp::kMaxThreads) +
                               " threads (the bound on threads); got " + std::to_string(a.threads));
  }
  o.num_threads = std::max(1, a.threads);
  o.apply_accel_limits = !a.no_accel_limits;

  const physics::Train base = a.train.empty() ? data::default_train() : data::load_train(a.train);
  std::vector<Log> logs;
  for (const auto& path : a.logs) logs.push_back(read_log(path));
  const Summary s = [&] {
    Progress progress("ecorail calibrate", a.quiet);  // cleared before the report
    o.progress = progress.callback();
    return calibrate(logs, base, o);
  }();
  report << (a.brief ? s.BriefReport() : s.FullReport());
  // The report above shows how the fit ended; a result that did not converge is an error and
  // neither the train nor the JSON record is written.
  const FormulationSummary* converged = nullptr;
  try {
    converged = &s.converged_primary();
  } catch (const NotConvergedError& e) {
    throw NotConvergedError(std::string(e.what()) + " (raise --max-iterations, now " +
                            std::to_string(a.max_iterations) + ", or add logs)");
  }
  const FormulationSummary& result = *converged;

  data::OutputBatch batch;  // both files or neither
  if (!a.out.empty()) {
    const std::string toml = data::train_to_toml(calibrated_train(base, result));
    batch.add(a.out, [&](std::ostream& out) { out << toml; });
  }
  if (!a.json.empty()) {
    const nlohmann::json j = calibration_to_json(s);
    batch.add(a.json, [&](std::ostream& out) { output::write_json(out, j); });
  }
  batch.commit();
  if (!a.out.empty()) {
    report << "wrote " << a.out << " (" << method_name(result.method) << " estimate)\n";
  }
  if (!a.json.empty()) report << "wrote " << a.json << "\n";
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "calibrate the train model (Davis A, B, C, rotating-mass factor, gradient scale) from "
      "per-second logs");
  cmd->add_option("--log", args->logs,
                  "per-second log (published table or plain CSV); repeat for several logs")
      ->required();
  cmd->add_option("--train", args->train, "base train (default: the reference train)");
  cmd->add_option("--out", args->out, "calibrated train file to write (TOML)");
  cmd->add_option("--json", args->json,
                  "write the fit as JSON (davis_A, davis_A_se, ..., discounted_rows)");
  cmd->add_option("--method", args->method,
                  "equation (equation error), output (output error) or both (default; the "
                  "output-error estimate is written)")
      ->check(CLI::IsMember({"equation", "output", "both"}));
  cmd->add_option("--fix", args->fix,
                  "hold a parameter at its starting value: davis_A, davis_B, davis_C, "
                  "rotating_mass_factor, gradient_scale, mass_t, traction_scale");
  cmd->add_flag("--fit-mass", args->fit_mass, "also estimate the mass");
  cmd->add_flag("--fit-traction-scale", args->fit_traction_scale,
                "also estimate a scale on the logged traction force");
  cmd->add_option("--gradient-scale", args->gradient_scale,
                  "auto (fit when the logs show gradient; default), fit, or fixed at 1")
      ->check(CLI::IsMember({"auto", "fit", "fixed"}));
  cmd->add_option("--loss", args->loss, "robust loss: cauchy (default), huber or none")
      ->check(CLI::IsMember({"cauchy", "huber", "none"}));
  cmd->add_option("--loss-scale", args->loss_scale,
                  "robust loss scale in noise standard deviations (default 2.5)");
  cmd->add_option("--segment-rows", args->segment_rows,
                  "rows per multiple-shooting segment of the output-error fit (default 10)");
  cmd->add_option("--max-iterations", args->max_iterations,
                  "Ceres iterations per pass of each fit; a fit that ends without convergence "
                  "is an error and nothing is written")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "threads for Ceres (default 1)");
  cmd->add_flag("--brief", args->brief, "print the one-line report only");
  cmd->add_flag("--quiet", args->quiet, "no progress line on stderr");
  cmd->add_flag("--no-accel-limits", args->no_accel_limits,
                "do not apply the base train's acceleration limits to the logged forces");
  input_files(cmd, {"--log", "--train"});
  cmd->callback([args] { run_calibrate(*args); });
}

}  // namespace ecorail::cli
