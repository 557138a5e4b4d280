// OpenMP's waiting threads yield the core (OMP_WAIT_POLICY=passive) unless the user chose
// otherwise. With libgomp's default, a thread that waits at a barrier or for a chunk spins on
// the core for a while; on a busy 2-core machine that spinning takes the time slice its
// descheduled partner needs, and two threads made a section solve twice as slow as one
// (bench_section under a load of 3.4: 134 ms against 64 ms; passive: 66 ms against 66 ms,
// docs/performance.md).
//
// libgomp reads its environment in its own initialiser, which runs before any initialiser of the
// program and before main, so neither can set the variable in time (a value set from the
// executable's .preinit_array is lost too: the C library's own initialiser resets the
// environment after it). The program instead defines getenv (cli/wait_policy.cpp): it answers
// every name from the environment exactly as the C library's does, and answers
// OMP_WAIT_POLICY with PASSIVE when the environment does not set it. The dynamic linker binds
// libgomp's getenv to the executable's, so the default holds from libgomp's first read, with
// no re-execution: the program runs as it is under valgrind, gdb and perf. A user's own
// OMP_WAIT_POLICY stands. A libgomp that scans the environment without getenv would not see the
// default; tests/cli/wait_policy.sh checks with OMP_DISPLAY_ENV that the one linked does.
#pragma once

namespace ecorail::cli {

// The wait policy libgomp gets when the environment sets none.
inline constexpr const char* kDefaultOpenMPWaitPolicy = "PASSIVE";

}  // namespace ecorail::cli
