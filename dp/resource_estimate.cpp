#include "dp/resource_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include "dp/text_format.hpp"
#include "physics/control.hpp"
#include "physics/units.hpp"

namespace ecorail::dp {

EngineFootprint estimate_engine(const physics::Train& train, const physics::Route& route,
                                const GridSpec& grid, double envelope_resolution_m) {
  double top_ms = 0.0;
  for (const physics::RouteSegment& seg : route.segments()) {
    top_ms = std::max(top_ms, std::min(seg.speed_limit_ms, train.max_speed_ms));
  }
  EngineFootprint f;
  f.stages = std::ceil(route.length_m() / grid.ds_m) + 1.0;
  f.nodes = f.stages * (std::ceil(top_ms / units::kmh_to_ms(grid.dv_kmh)) + 1.0);
  const double envelope_samples = std::ceil(route.length_m() / envelope_resolution_m) + 1.0;
  f.bytes = f.nodes * kEngineBytesPerNode + envelope_samples * 16.0;
  f.build_s = f.nodes * physics::kControlCount / kTransitionsPerSecond;
  return f;
}

namespace {

// The first line of a cgroup limit file as bytes; infinity for "max", a missing file or a
// number of 2^62 or more (v1's "no limit").
double limit_in_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string word;
  if (!(in >> word) || word == "max") return std::numeric_limits<double>::infinity();
  char* end = nullptr;
  const double bytes = std::strtod(word.c_str(), &end);
  if (end == word.c_str() || !(bytes > 0.0) || bytes >= 4.6e18)
    return std::numeric_limits<double>::infinity();
  return bytes;
}

}  // namespace

double cgroup_memory_limit_bytes(const std::string& root) {
  const std::filesystem::path base(root);
  double limit = std::numeric_limits<double>::infinity();
  // /proc/self/cgroup lines: "0::/path" (v2) or "4:memory:/path" (v1).
  std::ifstream groups(base / "proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    const std::size_t a = line.find(':');
    const std::size_t b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    std::string path = line.substr(b + 1);
    while (!path.empty() && path.front() == '/') path.erase(0, 1);
    std::filesystem::path dir, file;
    if (controllers.empty()) {
      dir = base / "sys/fs/cgroup", file = "memory.max";
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      dir = base / "sys/fs/cgroup/memory", file = "memory.limit_in_bytes";
    } else {
      continue;
    }
    limit = std::min({limit, limit_in_file(dir / path / file), limit_in_file(dir / file)});
  }
  return limit;
}

double memory_limit_bytes() {
  double limit =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  if (!(limit > 0.0)) limit = std::numeric_limits<double>::infinity();
  limit = std::min(limit, cgroup_memory_limit_bytes());
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit r{};
    if (getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
      limit = std::min(limit, static_cast<double>(r.rlim_cur));
    }
  }
  return limit;
}

EngineFootprint check_engine_fits(const physics::Train& train, const physics::Route& route,
                                  const GridSpec& grid, double envelope_resolution_m) {
  const EngineFootprint f = estimate_engine(train, route, grid, envelope_resolution_m);
  const double limit = memory_limit_bytes();
  // Node indices are 32-bit; beyond that no amount of memory helps.
  const double max_nodes =
      static_cast<double>(std::numeric_limits<std::int32_t>::max()) / physics::kControlCount;
  if (f.bytes > limit || f.nodes > max_nodes) {
    throw ResourceLimitError(format_text(
        "a grid that fits in the %.1f GB this process can have; got ds %g m and dv %g km/h over "
        "%s -> %s (%.0f m): about %.0f nodes, %.1f GB and %.0f s of one core to build",
        limit / 1e9, grid.ds_m, grid.dv_kmh, route.from_name().c_str(), route.to_name().c_str(),
        route.length_m(), f.nodes, f.bytes / 1e9, f.build_s));
  }
  return f;
}

}  // namespace ecorail::dp
