// Resource estimate of a section engine, made before anything is allocated. A grid is
// stages x speed nodes; each node holds kControlCount transitions and its share of the value
// functions a lambda search keeps, so memory grows like (length / ds) x (top speed / dv). A
// 1 cm step would run for minutes and then die of std::bad_alloc or the kernel's OOM killer;
// SectionEngine refuses such a grid at once with ResourceLimitError, which states the
// estimate, the memory this process can have (physical memory, bounded by the address-space
// limit `ulimit -v`) and an estimate of the build time.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "dp/stage_grid.hpp"
#include "physics/route.hpp"
#include "physics/train.hpp"

namespace ecorail::dp {

// Bytes per grid node: kControlCount transitions of 32 bytes, two value functions of 9 bytes
// and the extraction's bookkeeping, rounded up (measured peak RSS is below this,
// docs/reliability.md).
inline constexpr double kEngineBytesPerNode = 176.0;
// Transitions integrated per second on one core (measured, release build): for the time estimate.
inline constexpr double kTransitionsPerSecond = 4e6;

struct EngineFootprint {
  double stages = 0.0;
  double nodes = 0.0;    // upper bound: every stage up to the route's top speed
  double bytes = 0.0;    // nodes x kEngineBytesPerNode + the speed envelope
  double build_s = 0.0;  // one core; divide by the threads for a rough wall time
};

EngineFootprint estimate_engine(const physics::Train& train, const physics::Route& route,
                                const GridSpec& grid, double envelope_resolution_m);

// Memory this process can have: physical memory, bounded by RLIMIT_AS and RLIMIT_DATA and by
// the memory limit of its control group (a container's limit), cgroup_memory_limit_bytes.
double memory_limit_bytes();
// The memory limit of this process's control group, read under root ("/" normally; a test
// passes a fake tree): cgroup v2 memory.max and v1 memory.limit_in_bytes, in the process's own
// group (/proc/self/cgroup) and at the hierarchy's root, the smallest found; infinity when
// there is none or it is "max" (v1 writes no limit as a number near 2^63).
double cgroup_memory_limit_bytes(const std::string& root = "/");

// Thrown when a grid's estimate exceeds memory_limit_bytes() or the node count exceeds what a
// 32-bit node index holds. what() names the grid steps (ds_m, dv_kmh), the estimate and the limit.
class ResourceLimitError : public std::runtime_error, public Error {
 public:
  explicit ResourceLimitError(const std::string& what)
      : std::runtime_error(what), Error(ErrorKind::kResourceLimit) {}
};

// Throws ResourceLimitError if the engine would not fit; otherwise returns the estimate.
EngineFootprint check_engine_fits(const physics::Train& train, const physics::Route& route,
                                  const GridSpec& grid, double envelope_resolution_m);

}  // namespace ecorail::dp
