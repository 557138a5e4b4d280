#include "cli/wait_policy.hpp"

#include <unistd.h>  // environ

#include <cstdlib>
#include <cstring>

// The C library's getenv, with one default (see cli/wait_policy.hpp). It reads environ as the
// C library does and allocates nothing, so it is safe as early as libgomp's initialiser calls
// it.
extern "C" char* getenv(const char* name) noexcept {
  const std::size_t length = std::strlen(name);
  if (length == 0 || std::strchr(name, '=') != nullptr) return nullptr;
  if (environ != nullptr) {
    for (char** entry = environ; *entry != nullptr; ++entry) {
      if (std::strncmp(*entry, name, length) == 0 && (*entry)[length] == '=') {
        return *entry + length + 1;
      }
    }
  }
  if (std::strcmp(name, "OMP_WAIT_POLICY") == 0) {
    return const_cast<char*>(ecorail::cli::kDefaultOpenMPWaitPolicy);
  }
  return nullptr;
}
