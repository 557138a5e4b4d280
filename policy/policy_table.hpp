// PolicyTable: the optimal feedback policy of one section on the DP grid, for on-board use. For
// each time price lambda (a "layer"; a lambda ladder is several layers on one grid) it holds, at
// every grid node (position s_i, speed v_ij), the optimal control u*, the regime and mean force
// that control applies over the next metre, the cost-to-go J = energy + lambda * time to the stop
// and the time-to-go. The header identifies what the table was made for: line and train (names
// and content checksums), section, objective, grid and envelope settings. Tables are built from
// a SectionEngine (build_policy_layer) and written in the little-endian binary format of
// docs/policy_format.md, ending in an FNV-1a checksum of everything before it, or as CSV. Reading
// validates sizes, checksum and content and throws PolicyFormatError, never reading out of
// bounds. Everything is SI (m, m/s, N, J, s, J/s); the CSV carries unit names in its columns.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.hpp"
#include "dp/objective.hpp"
#include "dp/section_engine.hpp"
#include "physics/control.hpp"
#include "physics/motion.hpp"

namespace ecorail::policy {

// A policy file that cannot be read: wrong magic or version, truncated, corrupted, inconsistent.
class PolicyFormatError : public std::runtime_error, public Error {
 public:
  explicit PolicyFormatError(const std::string& what)
      : std::runtime_error(what), Error(ErrorKind::kPolicyFormat) {}
};

inline constexpr char kPolicyMagic[8] = {'E', 'C', 'R', 'L', 'P', 'O', 'L', '\n'};
inline constexpr std::uint32_t kPolicyFormatVersion = 1;
// The units of the binary file, stored in its header and checked on reading.
inline constexpr std::string_view kPolicyUnits =
    "s=m v=m/s force=N cost=J time=s lambda=J/s energy=J";

// One time price: the policy and values at every node of the grid.
struct PolicyLayer {
  double lambda_J_per_s = 0.0;
  double time_offset_s = 0.0;         // offset of target from the nominal running time (0: nominal)
  double target_time_s = 0.0;         // running time lambda was searched for
  double planned_time_s = 0.0;        // re-simulated running time of the lambda-optimal run
  double planned_energy_J = 0.0;      // its energy cost (by the table's objective)
  std::vector<std::uint8_t> control;  // physics::Control per node
  std::vector<std::uint8_t> regime;   // physics::Regime per node
  std::vector<double> force_N;        // mean applied force over the next metre (signed)
  std::vector<double> cost_to_go_J;   // energy + lambda * time to the stop; >= 1e25: infeasible
  std::vector<double> time_to_go_s;   // running time to the stop following the policy
};

struct PolicyTable {
  std::string line_name;
  std::uint64_t line_checksum = 0;
  std::string train_name;
  std::uint64_t train_checksum = 0;
  std::string from, to;
  double route_length_m = 0.0;
  dp::Objective objective = dp::Objective::Traction;
  dp::GridSpec grid_spec;
  double envelope_resolution_m = 0.1;
  std::vector<double> position_m;           // stage positions s_i, increasing, last = length
  std::vector<std::uint32_t> stage_offset;  // first node of each stage; size stages + 1
  std::vector<double> speed_ms;             // node speeds, increasing within each stage
  std::vector<PolicyLayer> layers;

  int stage_count() const { return static_cast<int>(position_m.size()); }
  int node_count() const { return static_cast<int>(speed_ms.size()); }
  // The layer with time offset 0 if there is one, else the first.
  int nominal_layer() const;
  // First stage strictly after s (the next decision position); the last stage at the end.
  int next_stage_after(double s_m) const;
  // Lower node (global index) and weight of speed v at stage i, for linear interpolation;
  // speeds below the first node or above the top node are clamped to them.
  void locate(int i, double v_ms, int* lower, double* weight) const;
  // A per-node value of a layer interpolated linearly in speed at stage i.
  double interpolate(const std::vector<double>& values, int i, double v_ms) const;
  // Cost-to-go from the table alone, bilinear in (s, v) between the stages around s.
  double cost_to_go_J(int layer, double s_m, double v_ms) const;

  // Checks the internal consistency of the table (sizes, ordering, finite values, codes);
  // throws PolicyFormatError naming the first problem.
  void validate() const;
};

// The first substep of applying control c at (s, v): at most one metre, and never past until_m
// or the end of the track segment holding s; the envelope clamp is included, so its regime and
// mean force are what the train does (e.g. braking on a braking curve whatever the control).
physics::Substep control_probe(const physics::Motion& motion, double s_m, double v_ms,
                               physics::Control c, double until_m);

// Identity of the table (everything but the layers) from an engine and the line's and train's
// checksums and names.
PolicyTable make_policy_table(const dp::SectionEngine& engine, const std::string& line_name,
                              std::uint64_t line_checksum, std::uint64_t train_checksum);

// One layer for a time price lambda: a backward sweep, the time-to-go along the optimal policy,
// the force and regime of each node's control, and the planned (re-simulated) run.
PolicyLayer build_policy_layer(const dp::SectionEngine& engine, double lambda_J_per_s);

// The binary format (docs/policy_format.md). Writing throws std::runtime_error on I/O failure.
std::string encode_policy(const PolicyTable& table);
void write_policy(std::ostream& out, const PolicyTable& table);
void save_policy(const PolicyTable& table, const std::filesystem::path& path);  // atomic
// Reading throws PolicyFormatError (prefixed with the label, usually the file name).
PolicyTable decode_policy(std::string_view bytes, const std::string& label = "policy table");
PolicyTable load_policy(const std::filesystem::path& path);

// CSV export, one row per (layer, node); columns in docs/policy_format.md.
void write_policy_csv(std::ostream& out, const PolicyTable& table);

}  // namespace ecorail::policy
