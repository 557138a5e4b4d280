#include "policy/policy_table.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "data/atomic_file.hpp"
#include "data/line.hpp"
#include "dp/backward_sweep.hpp"
#include "dp/text_format.hpp"
#include "physics/units.hpp"

namespace ecorail::policy {

namespace {

constexpr std::size_t kMaxString = 4096;
constexpr double kMaxRouteLength_m = 1e6;
constexpr std::uintmax_t kMaxPolicyFileBytes = std::uintmax_t{1} << 34;  // 16 GiB
constexpr std::size_t kChecksumBytes = 8;
constexpr std::size_t kPreambleBytes = 8 + 4 + 8;  // magic, version, file size

// ---- little-endian encoding ---------------------------------------------------------------

class Writer {
 public:
  void bytes(const void* p, std::size_t n) { out_.append(static_cast<const char*>(p), n); }
  void u8(std::uint8_t x) { out_.push_back(static_cast<char>(x)); }
  void u32(std::uint32_t x) {
    for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>(x >> (8 * k)));
  }
  void u64(std::uint64_t x) {
    for (int k = 0; k < 8; ++k) u8(static_cast<std::uint8_t>(x >> (8 * k)));
  }
  void f64(double x) { u64(std::bit_cast<std::uint64_t>(x)); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  void f64s(const std::vector<double>& v) {
    for (double x : v) f64(x);
  }
  std::string& buffer() { return out_; }

 private:
  std::string out_;
};

// Bounds-checked reader: every read names its field, so a short or inconsistent file gives a
// message instead of reading past the end.
class Reader {
 public:
  Reader(std::string_view bytes, std::string label) : b_(bytes), label_(std::move(label)) {}

  void need(std::size_t n, const char* field) const {
    if (n > b_.size() - pos_) {
      throw PolicyFormatError(label_ + ": truncated or inconsistent: field '" + field + "' needs " +
                              std::to_string(n) + " bytes at offset " + std::to_string(pos_) +
                              ", only " + std::to_string(b_.size() - pos_) + " remain");
    }
  }
  std::uint8_t u8(const char* field) {
    need(1, field);
    return static_cast<std::uint8_t>(b_[pos_++]);
  }
  std::uint32_t u32(const char* field) {
    need(4, field);
    std::uint32_t x = 0;
    for (int k = 0; k < 4; ++k)
      x |= std::uint32_t{static_cast<std::uint8_t>(b_[pos_++])} << (8 * k);
    return x;
  }
  std::uint64_t u64(const char* field) {
    need(8, field);
    std::uint64_t x = 0;
    for (int k = 0; k < 8; ++k)
      x |= std::uint64_t{static_cast<std::uint8_t>(b_[pos_++])} << (8 * k);
    return x;
  }
  double f64(const char* field) { return std::bit_cast<double>(u64(field)); }
  std::string str(const char* field) {
    const std::uint32_t n = u32(field);
    if (n > kMaxString) {
      throw PolicyFormatError(label_ + ": field '" + field + "' claims " + std::to_string(n) +
                              " characters (at most " + std::to_string(kMaxString) + ")");
    }
    need(n, field);
    std::string s(b_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  std::vector<double> f64s(std::size_t n, const char* field) {
    need(n * 8, field);  // n is bounded by the caller, so n * 8 does not overflow
    std::vector<double> v(n);
    for (auto& x : v) x = f64(field);
    return v;
  }
  std::vector<std::uint8_t> u8s(std::size_t n, const char* field) {
    need(n, field);
    std::vector<std::uint8_t> v(n);
    for (auto& x : v) x = u8(field);
    return v;
  }
  std::size_t remaining() const { return b_.size() - pos_; }
  std::size_t position() const { return pos_; }

 private:
  std::string_view b_;
  std::size_t pos_ = 0;
  std::string label_;
};

std::uint64_t payload_checksum(std::string_view bytes_before_trailer) {
  return data::fnv1a64(bytes_before_trailer);
}

std::string hex64(std::uint64_t x) {
  return dp::format_text("0x%016llx", static_cast<unsigned long long>(x));
}

// Time to go along the optimal policy: the same backward recursion as the cost-to-go, over the
// time of each node's optimal transition.
std::vector<double> time_to_go(const dp::SectionEngine& engine, const dp::ValueFunction& value) {
  const dp::StageGrid& grid = engine.grid();
  const int last = grid.stage_count() - 1;
  std::vector<double> T(grid.total_nodes(), dp::kInfeasible);
  T[grid.offset(last)] = 0.0;
  for (int i = last - 1; i >= 0; --i) {
    for (int node = grid.offset(i); node < grid.offset(i) + grid.node_count(i); ++node) {
      if (!dp::is_feasible(value.cost_to_go[node])) continue;
      const dp::Transition t =
          engine.transitions().at(node, static_cast<physics::Control>(value.best[node]));
      if (t.lower < 0) continue;
      double next = T[t.lower];
      if (t.weight > 0.0) next += t.weight * (T[t.lower + 1] - next);
      T[node] = t.time_s + next;
    }
  }
  return T;
}

}  // namespace

// ---- lookups --------------------------------------------------------------------------------

int PolicyTable::nominal_layer() const {
  for (std::size_t k = 0; k < layers.size(); ++k) {
    if (layers[k].time_offset_s == 0.0) return static_cast<int>(k);
  }
  return 0;
}

int PolicyTable::next_stage_after(double s_m) const {
  auto it = std::upper_bound(position_m.begin(), position_m.end(), s_m + 1e-9);
  return it == position_m.end() ? stage_count() - 1 : static_cast<int>(it - position_m.begin());
}

void PolicyTable::locate(int i, double v, int* lower, double* weight) const {
  const int first = static_cast<int>(stage_offset[i]);
  const int top = static_cast<int>(stage_offset[i + 1]) - 1;
  if (top == first || v >= speed_ms[top]) {
    *lower = top;
    *weight = 0.0;
    return;
  }
  if (!(v > speed_ms[first])) {  // also catches NaN
    *lower = first;
    *weight = 0.0;
    return;
  }
  auto begin = speed_ms.begin() + first;
  auto end = speed_ms.begin() + top + 1;
  const int k = static_cast<int>(std::upper_bound(begin, end, v) - speed_ms.begin()) - 1;
  *lower = k;
  *weight = (v - speed_ms[k]) / (speed_ms[k + 1] - speed_ms[k]);
}

double PolicyTable::interpolate(const std::vector<double>& values, int i, double v) const {
  int lower;
  double w;
  locate(i, v, &lower, &w);
  const double lo = values[lower];
  return w > 0.0 ? lo + w * (values[lower + 1] - lo) : lo;
}

double PolicyTable::cost_to_go_J(int layer, double s_m, double v_ms) const {
  const auto& J = layers.at(layer).cost_to_go_J;
  if (s_m >= position_m.back()) return 0.0;
  const double s = std::max(0.0, s_m);
  const int next = std::max(1, next_stage_after(s));
  const int prev = next - 1;
  const double a = interpolate(J, prev, v_ms);
  const double b = interpolate(J, next, v_ms);
  if (!dp::is_feasible(a) || !dp::is_feasible(b)) return dp::kInfeasible;
  const double x = (s - position_m[prev]) / (position_m[next] - position_m[prev]);
  return a + std::clamp(x, 0.0, 1.0) * (b - a);
}

void PolicyTable::validate() const {
  auto fail = [](const std::string& what) { throw PolicyFormatError("invalid table: " + what); };
  const int N = stage_count();
  const int M = node_count();
  if (N < 2) fail("fewer than two stages");
  if (layers.empty()) fail("no layer");
  if (!(std::isfinite(route_length_m) && route_length_m > 0.0)) fail("route length");
  if (!(grid_spec.ds_m > 0.0 && grid_spec.dv_kmh > 0.0 && grid_spec.substep_m > 0.0 &&
        envelope_resolution_m > 0.0 && std::isfinite(grid_spec.ds_m) &&
        std::isfinite(grid_spec.dv_kmh) && std::isfinite(grid_spec.substep_m) &&
        std::isfinite(envelope_resolution_m))) {
    fail("grid settings must be positive and finite");
  }
  // Ranges, not only signs: a file is untrusted input, and a 1e-12 m substep or a subnormal
  // envelope resolution would make inspecting or advising run for ever or allocate without end.
  if (!(route_length_m <= kMaxRouteLength_m)) fail("route length above 1000 km");
  if (!(grid_spec.ds_m >= 0.01 && grid_spec.ds_m <= 100.0)) fail("ds_m outside [0.01, 100] m");
  if (!(grid_spec.dv_kmh >= 0.001 && grid_spec.dv_kmh <= 10.0))
    fail("dv_kmh outside [0.001, 10] km/h");
  if (!(grid_spec.substep_m >= grid_spec.ds_m / 1000.0 && grid_spec.substep_m <= grid_spec.ds_m))
    fail("substep_m outside [ds_m / 1000, ds_m]");
  if (!(envelope_resolution_m >= 0.01 && envelope_resolution_m <= 10.0))
    fail("envelope_resolution_m outside [0.01, 10] m");
  if (objective != dp::Objective::Traction && objective != dp::Objective::Net)
    fail("objective code");
  if (position_m.front() != 0.0) fail("first stage is not at 0 m");
  for (int i = 1; i < N; ++i) {
    if (!(position_m[i] > position_m[i - 1]) || !std::isfinite(position_m[i])) {
      fail(dp::format_text("stage positions not increasing at stage %d", i));
    }
  }
  if (std::abs(position_m.back() - route_length_m) > 1e-6) fail("last stage is not the stop");
  if (stage_offset.size() != position_m.size() + 1 || stage_offset.front() != 0 ||
      stage_offset.back() != static_cast<std::uint32_t>(M)) {
    fail("stage offsets do not cover the nodes");
  }
  // Every offset checked before any is used to index the node arrays.
  for (int i = 0; i < N; ++i) {
    if (!(stage_offset[i + 1] > stage_offset[i])) fail(dp::format_text("stage %d has no node", i));
  }
  if (speed_ms.size() != static_cast<std::size_t>(M)) fail("node speeds do not match the nodes");
  for (int i = 0; i < N; ++i) {
    for (std::uint32_t n = stage_offset[i]; n < stage_offset[i + 1]; ++n) {
      if (!(std::isfinite(speed_ms[n]) && speed_ms[n] >= 0.0))
        fail(dp::format_text("speed of node %u", n));
      if (n > stage_offset[i] && !(speed_ms[n] > speed_ms[n - 1])) {
        fail(dp::format_text("node speeds not increasing at stage %d", i));
      }
    }
  }
  if (stage_offset[N] - stage_offset[N - 1] != 1 || speed_ms.back() != 0.0) {
    fail("the last stage must be the single node v = 0 (the stop)");
  }
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const PolicyLayer& L = layers[k];
    const std::string which = dp::format_text("layer %zu: ", k);
    if (!(std::isfinite(L.lambda_J_per_s) && L.lambda_J_per_s >= 0.0)) fail(which + "lambda");
    if (L.control.size() != speed_ms.size() || L.regime.size() != speed_ms.size() ||
        L.force_N.size() != speed_ms.size() || L.cost_to_go_J.size() != speed_ms.size() ||
        L.time_to_go_s.size() != speed_ms.size()) {
      fail(which + "per-node arrays do not match the node count");
    }
    for (int n = 0; n < M; ++n) {
      if (L.control[n] >= physics::kControlCount)
        fail(which + dp::format_text("control code at node %d", n));
      if (L.regime[n] > static_cast<std::uint8_t>(physics::Regime::FullBrake)) {
        fail(which + dp::format_text("regime code at node %d", n));
      }
      if (!std::isfinite(L.force_N[n]) || !std::isfinite(L.cost_to_go_J[n]) ||
          !std::isfinite(L.time_to_go_s[n]) || L.time_to_go_s[n] < 0.0) {
        fail(which + dp::format_text("non-finite or negative value at node %d", n));
      }
    }
    if (L.cost_to_go_J[M - 1] != 0.0 || L.time_to_go_s[M - 1] != 0.0) {
      fail(which + "cost and time to go at the stop must be 0");
    }
  }
}

// ---- building from an engine --------------------------------------------------------------

physics::Substep control_probe(const physics::Motion& motion, double s_m, double v_ms,
                               physics::Control c, double until_m) {
  const double seg_end = motion.route().at(s_m).end_m;
  const double h = std::min({1.0, until_m - s_m, seg_end - s_m});
  if (!(h > 0.0)) {
    physics::Substep none;
    none.e_end = 0.5 * v_ms * v_ms;
    none.mean_force_N = 0.0;
    return none;
  }
  return motion.substep(s_m, 0.5 * v_ms * v_ms, h, c, 4);
}

PolicyTable make_policy_table(const dp::SectionEngine& engine, const std::string& line_name,
                              std::uint64_t line_checksum, std::uint64_t train_checksum) {
  PolicyTable t;
  t.line_name = line_name;
  t.line_checksum = line_checksum;
  t.train_name = engine.train().name;
  t.train_checksum = train_checksum;
  t.from = engine.route().from_name();
  t.to = engine.route().to_name();
  t.route_length_m = engine.route().length_m();
  t.objective = engine.options().objective;
  t.grid_spec = engine.options().grid;
  t.envelope_resolution_m = engine.options().envelope_resolution_m;
  const dp::StageGrid& grid = engine.grid();
  t.position_m = grid.positions();
  for (int i = 0; i <= grid.stage_count(); ++i) {
    t.stage_offset.push_back(
        static_cast<std::uint32_t>(i < grid.stage_count() ? grid.offset(i) : grid.total_nodes()));
  }
  t.speed_ms.reserve(grid.total_nodes());
  for (int i = 0; i < grid.stage_count(); ++i) {
    for (int j = 0; j < grid.node_count(i); ++j) t.speed_ms.push_back(grid.speed(i, j));
  }
  return t;
}

PolicyLayer build_policy_layer(const dp::SectionEngine& engine, double lambda) {
  const dp::ValueFunction value = engine.sweep(lambda);
  const dp::StageGrid& grid = engine.grid();
  PolicyLayer L;
  L.lambda_J_per_s = lambda;
  L.control.assign(value.best.begin(), value.best.end());
  L.cost_to_go_J.assign(value.cost_to_go.begin(), value.cost_to_go.end());
  L.time_to_go_s = time_to_go(engine, value);
  const int M = grid.total_nodes();
  L.regime.assign(M, static_cast<std::uint8_t>(physics::Regime::Coast));
  L.force_N.assign(M, 0.0);
  const int last = grid.stage_count() - 1;
  for (int i = 0; i < last; ++i) {
#pragma omp parallel for schedule(static)
    for (int j = 0; j < grid.node_count(i); ++j) {
      const int node = grid.offset(i) + j;
      if (!dp::is_feasible(value.cost_to_go[node])) continue;
      const physics::Substep probe =
          control_probe(engine.motion(), grid.position(i), grid.speed(i, j),
                        static_cast<physics::Control>(value.best[node]), grid.position(i + 1));
      L.regime[node] = static_cast<std::uint8_t>(probe.regime);
      L.force_N[node] = probe.mean_force_N;
    }
  }
  const dp::LambdaRun run = engine.run(lambda);
  L.planned_time_s = run.sim.running_time_s;
  L.planned_energy_J = run.cost_J;
  L.target_time_s = run.sim.running_time_s;
  return L;
}

// ---- binary format --------------------------------------------------------------------------

std::string encode_policy(const PolicyTable& t) {
  t.validate();
  Writer w;
  w.bytes(kPolicyMagic, sizeof kPolicyMagic);
  w.u32(kPolicyFormatVersion);
  w.u64(0);  // file size, patched below
  w.str(std::string(kPolicyUnits));
  w.str(t.line_name);
  w.u64(t.line_checksum);
  w.str(t.train_name);
  w.u64(t.train_checksum);
  w.str(t.from);
  w.str(t.to);
  w.f64(t.route_length_m);
  w.u8(t.objective == dp::Objective::Net ? 1 : 0);
  w.f64(t.grid_spec.ds_m);
  w.f64(t.grid_spec.dv_kmh);
  w.f64(t.grid_spec.substep_m);
  w.f64(t.envelope_resolution_m);
  w.u32(static_cast<std::uint32_t>(t.stage_count()));
  w.u32(static_cast<std::uint32_t>(t.node_count()));
  w.u32(static_cast<std::uint32_t>(t.layers.size()));
  w.f64s(t.position_m);
  for (std::uint32_t o : t.stage_offset) w.u32(o);
  w.f64s(t.speed_ms);
  for (const PolicyLayer& L : t.layers) {
    w.f64(L.lambda_J_per_s);
    w.f64(L.time_offset_s);
    w.f64(L.target_time_s);
    w.f64(L.planned_time_s);
    w.f64(L.planned_energy_J);
  }
  for (const PolicyLayer& L : t.layers) {
    w.bytes(L.control.data(), L.control.size());
    w.bytes(L.regime.data(), L.regime.size());
    w.f64s(L.force_N);
    w.f64s(L.cost_to_go_J);
    w.f64s(L.time_to_go_s);
  }
  std::string& out = w.buffer();
  const std::uint64_t size = out.size() + kChecksumBytes;
  for (int k = 0; k < 8; ++k) out[12 + k] = static_cast<char>(size >> (8 * k));
  w.u64(payload_checksum(out));
  return out;
}

void write_policy(std::ostream& out, const PolicyTable& table) {
  const std::string bytes = encode_policy(table);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("writing the policy table failed");
}

void save_policy(const PolicyTable& table, const std::filesystem::path& path) {
  const std::string bytes = encode_policy(table);
  data::write_atomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

PolicyTable decode_policy(std::string_view b, const std::string& label) {
  const std::size_t size = b.size();
  if (size < sizeof kPolicyMagic || std::memcmp(b.data(), kPolicyMagic, sizeof kPolicyMagic) != 0) {
    throw PolicyFormatError(label + ": not an ecorail policy table (wrong magic; " +
                            std::to_string(size) + " bytes)");
  }
  Reader r(b, label);
  r.u64("magic");
  if (size < kPreambleBytes) {
    throw PolicyFormatError(label + ": truncated: " + std::to_string(size) +
                            " bytes, shorter than the " + std::to_string(kPreambleBytes) +
                            "-byte preamble");
  }
  const std::uint32_t version = r.u32("version");
  if (version != kPolicyFormatVersion) {
    throw PolicyFormatError(label + ": format version " + std::to_string(version) +
                            ", this program reads version " + std::to_string(kPolicyFormatVersion));
  }
  const std::uint64_t declared = r.u64("file_bytes");
  if (declared != size) {
    throw PolicyFormatError(
        label +
        (size < declared ? ": truncated: " : ": size mismatch (corrupted or trailing data): ") +
        std::to_string(size) + " bytes, the header says " + std::to_string(declared));
  }
  if (size < kPreambleBytes + kChecksumBytes) {
    throw PolicyFormatError(label + ": truncated: no room for the checksum");
  }
  const std::string_view body = b.substr(0, size - kChecksumBytes);
  std::uint64_t stored = 0;
  for (int k = 0; k < 8; ++k) {
    stored |= std::uint64_t{static_cast<std::uint8_t>(b[size - kChecksumBytes + k])} << (8 * k);
  }
  const std::uint64_t actual = payload_checksum(body);
  if (stored != actual) {
    throw PolicyFormatError(label + ": corrupted: checksum " + hex64(actual) +
                            " does not match the stored " + hex64(stored));
  }

  Reader p(body, label);
  p.u64("magic");
  p.u32("version");
  p.u64("file_bytes");
  const std::string units = p.str("units");
  if (units != kPolicyUnits) {
    throw PolicyFormatError(label + ": unexpected units '" + units + "' (expected '" +
                            std::string(kPolicyUnits) + "')");
  }
  PolicyTable t;
  t.line_name = p.str("line_name");
  t.line_checksum = p.u64("line_checksum");
  t.train_name = p.str("train_name");
  t.train_checksum = p.u64("train_checksum");
  t.from = p.str("from");
  t.to = p.str("to");
  t.route_length_m = p.f64("route_length_m");
  const std::uint8_t objective = p.u8("objective");
  if (objective > 1)
    throw PolicyFormatError(label + ": unknown objective code " + std::to_string(objective));
  t.objective = objective == 1 ? dp::Objective::Net : dp::Objective::Traction;
  t.grid_spec.ds_m = p.f64("ds_m");
  t.grid_spec.dv_kmh = p.f64("dv_kmh");
  t.grid_spec.substep_m = p.f64("substep_m");
  t.envelope_resolution_m = p.f64("envelope_resolution_m");
  const std::size_t N = p.u32("stage_count");
  const std::size_t M = p.u32("node_count");
  const std::size_t K = p.u32("layer_count");
  // Every count must fit in what is left before allocating anything for it.
  const std::size_t per_layer = 5 * 8 + M * (2 + 3 * 8);
  if (N < 2 || M < N || K < 1 || N * 12 + 4 + M * 8 > p.remaining() ||
      K > p.remaining() / per_layer) {
    throw PolicyFormatError(label + ": inconsistent counts: " + std::to_string(N) + " stages, " +
                            std::to_string(M) + " nodes, " + std::to_string(K) +
                            " layers do not fit in " + std::to_string(p.remaining()) + " bytes");
  }
  t.position_m = p.f64s(N, "position_m");
  t.stage_offset.resize(N + 1);
  for (auto& o : t.stage_offset) o = p.u32("stage_offset");
  t.speed_ms = p.f64s(M, "speed_ms");
  t.layers.resize(K);
  for (PolicyLayer& L : t.layers) {
    L.lambda_J_per_s = p.f64("lambda_J_per_s");
    L.time_offset_s = p.f64("time_offset_s");
    L.target_time_s = p.f64("target_time_s");
    L.planned_time_s = p.f64("planned_time_s");
    L.planned_energy_J = p.f64("planned_energy_J");
  }
  for (PolicyLayer& L : t.layers) {
    L.control = p.u8s(M, "control");
    L.regime = p.u8s(M, "regime");
    L.force_N = p.f64s(M, "force_N");
    L.cost_to_go_J = p.f64s(M, "cost_to_go_J");
    L.time_to_go_s = p.f64s(M, "time_to_go_s");
  }
  if (p.remaining() != 0) {
    throw PolicyFormatError(label + ": " + std::to_string(p.remaining()) +
                            " unexpected bytes before the checksum");
  }
  try {
    t.validate();
  } catch (const PolicyFormatError& e) {
    throw PolicyFormatError(label + ": " + e.what());
  }
  return t;
}

PolicyTable load_policy(const std::filesystem::path& path) {
  // Only a regular file of bounded size: /dev/zero never ends, a directory cannot be read.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw PolicyFormatError(path.string() + ": is a directory, not a policy table");
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw PolicyFormatError(path.string() + ": not a regular file, not a policy table");
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxPolicyFileBytes) {
    throw PolicyFormatError(path.string() + ": " + std::to_string(size) +
                            " bytes, larger than any policy table this program writes (at most " +
                            std::to_string(kMaxPolicyFileBytes) + ")");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PolicyFormatError(path.string() + ": cannot open the policy table");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw PolicyFormatError(path.string() + ": read error");
  return decode_policy(bytes, path.string());
}

// ---- CSV --------------------------------------------------------------------------------

void write_policy_csv(std::ostream& out, const PolicyTable& t) {
  out << "layer,lambda_kJ_per_s,stage,s_m,node,v_kmh,control,regime,force_kN,cost_to_go_kJ,"
         "time_to_go_s,energy_to_go_kJ\n";
  char line[400];
  for (std::size_t k = 0; k < t.layers.size(); ++k) {
    const PolicyLayer& L = t.layers[k];
    for (int i = 0; i < t.stage_count(); ++i) {
      for (std::uint32_t n = t.stage_offset[i]; n < t.stage_offset[i + 1]; ++n) {
        const bool feasible = dp::is_feasible(L.cost_to_go_J[n]);
        const std::string control(
            physics::control_name(static_cast<physics::Control>(L.control[n])));
        const std::string regime(physics::regime_name(static_cast<physics::Regime>(L.regime[n])));
        if (feasible) {
          std::snprintf(line, sizeof line, "%zu,%.6f,%d,%.6f,%u,%.6f,%s,%s,%.6f,%.6f,%.6f,%.6f\n",
                        k, units::J_to_kJ(L.lambda_J_per_s), i, t.position_m[i],
                        n - t.stage_offset[i], units::ms_to_kmh(t.speed_ms[n]), control.c_str(),
                        regime.c_str(), units::N_to_kN(L.force_N[n]),
                        units::J_to_kJ(L.cost_to_go_J[n]), L.time_to_go_s[n],
                        units::J_to_kJ(L.cost_to_go_J[n] - L.lambda_J_per_s * L.time_to_go_s[n]));
        } else {
          std::snprintf(line, sizeof line, "%zu,%.6f,%d,%.6f,%u,%.6f,infeasible,,,,,\n", k,
                        units::J_to_kJ(L.lambda_J_per_s), i, t.position_m[i], n - t.stage_offset[i],
                        units::ms_to_kmh(t.speed_ms[n]));
        }
        out << line;
      }
    }
  }
}

}  // namespace ecorail::policy
