#include "cli/wait_policy.hpp"

#include <unistd.h>

#include <cstdlib>

namespace ecorail::cli {

void prefer_passive_openmp_waits(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;  // the user's choice stands
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the re-execution failed; run on as we are (the policy only affects speed).
}

}  // namespace ecorail::cli
