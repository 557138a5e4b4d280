// OpenMP's waiting threads yield the core (OMP_WAIT_POLICY=passive) unless the user chose
// otherwise. With libgomp's default, a thread that waits at a barrier or for a chunk spins on
// the core for a while; on a busy 2-core machine that spinning takes the time slice its
// descheduled partner needs, and two threads made a section solve twice as slow as one
// (bench_section under a load of 3.4: 134 ms against 64 ms; passive: 66 ms against 66 ms,
// docs/performance.md). libgomp reads the policy from the environment when it is loaded,
// before main, so the program sets it and runs itself again once.
#pragma once

namespace ecorail::cli {

// Call first in main. When OMP_WAIT_POLICY is unset, sets it to PASSIVE and re-executes the
// program (/proc/self/exe) with the same arguments; returns only if nothing was to be done or
// the re-execution failed (then the program runs on with libgomp's default).
void prefer_passive_openmp_waits(char** argv);

}  // namespace ecorail::cli
