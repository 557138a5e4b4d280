// `ecorail export`: writes the line and the train a run would read (--line, --train: any form
// ecorail reads, the embedded reference by default) as TTOBench JSON, for other solvers. Each
// text is read back before it is written: the track must give the same runs between adjacent
// stations (data/route_equivalence.hpp; its tables may differ: rows merged, km posts shifted,
// curves as curvature) and the train the same train_checksum. An export that would not
// round-trip is an error, never a file. What TTOBench cannot state (e.g. a polynomial traction
// envelope) is refused with one error naming the flag, not approximated
// (output/ttobench_writer.hpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "cli/commands.hpp"
#include "cli/output_options.hpp"
#include "cli/problem_options.hpp"
#include "data/atomic_file.hpp"
#include "data/input_error.hpp"
#include "data/route_equivalence.hpp"
#include "data/train_io.hpp"
#include "data/ttobench_io.hpp"
#include "dp/text_format.hpp"
#include "output/ttobench_writer.hpp"

namespace ecorail::cli {

namespace {

struct ExportArgs {
  ProblemOptions problem;
  std::string track, train, track_id;
};

// The text of one export, or an InputError naming flag with what the writer refused.
template <class Write>
std::string exported(const std::string& flag, const char* what, Write write) {
  try {
    return write();
  } catch (const std::invalid_argument& e) {
    throw data::InputError("command line", 0, flag,
                           std::string(what) + " TTOBench can state; " + e.what());
  }
}

void run_export(const ExportArgs& a) {
  if (a.track.empty() && a.train.empty()) {
    throw data::InputError("command line", 0, "--ttobench-track",
                           "at least one of --ttobench-track FILE and --ttobench-train FILE");
  }
  check_output_targets(
      {{"--ttobench-track", a.track, false}, {"--ttobench-train", a.train, false}});
  ProblemOptions whole = a.problem;
  whole.from.clear();  // the whole line, no route
  const Problem p = load_problem(whole);
  data::OutputBatch batch;
  std::vector<std::string> done;  // printed once everything is written
  if (!a.track.empty()) {
    const std::string id =
        !a.track_id.empty()
            ? a.track_id
            : (a.problem.line_path.empty()
                   ? "ecorail_reference"
                   : std::filesystem::path(a.problem.line_path).filename().stem().string());
    const std::string text = exported("--ttobench-track", "a line",
                                      [&] { return output::line_to_ttobench(p.line, id); });
    const std::string why =
        data::line_runs_difference(p.line, data::line_from_ttobench(text, a.track), p.train);
    if (!why.empty()) {
      throw std::runtime_error(
          "the TTOBench track of this line does not read back to the same "
          "runs (" +
          why + "); nothing was written");
    }
    batch.add(a.track, [text](std::ostream& out) { out << text; });
    double lo = p.line.stations.front().km_post_m, hi = lo;
    for (const data::Station& st : p.line.stations) {
      lo = std::min(lo, st.km_post_m);
      hi = std::max(hi, st.km_post_m);
    }
    done.push_back(dp::format_text("track '%s': %zu stops, %.1f m -> %s", id.c_str(),
                                   p.line.stations.size(), hi - lo, a.track.c_str()));
  }
  if (!a.train.empty()) {
    const std::string text =
        exported("--ttobench-train", "a train", [&] { return output::train_to_ttobench(p.train); });
    if (data::train_checksum(data::train_from_ttobench(text, a.train)) !=
        data::train_checksum(p.train)) {
      throw std::runtime_error(
          "the TTOBench train does not read back to the same train "
          "(checksums differ); nothing was written");
    }
    batch.add(a.train, [text](std::ostream& out) { out << text; });
    done.push_back(dp::format_text("train '%s': %.0f kg -> %s", p.train.name.c_str(),
                                   p.train.mass_kg, a.train.c_str()));
  }
  batch.commit();
  for (const std::string& line : done) std::printf("%s\n", line.c_str());
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand("export",
                                     "write the line and the train as TTOBench JSON (round trip "
                                     "checked before writing)");
  add_problem_options(cmd, args->problem, /*stations_required=*/false);
  cmd->add_option("--ttobench-track", args->track, "write the line as a TTOBench track (JSON)");
  cmd->add_option("--ttobench-train", args->train, "write the train as a TTOBench train (JSON)");
  cmd->add_option("--track-id", args->track_id,
                  "the track's metadata id (default: the line file's name)");
  cmd->callback([args] { run_export(*args); });
}

}  // namespace ecorail::cli
