// Shared pieces of the libFuzzer harnesses: each harness feeds bytes to one loader exactly as
// the program would (text or bytes already read, no file system) and lets only the errors the
// program reports as bad input (exit 2) pass. Any other exception escapes and libFuzzer reports
// it as a crash, as it does for sanitizer reports, hangs (-timeout) and memory blow-ups
// (-rss_limit_mb). Built only with -DECORAIL_BUILD_FUZZERS=ON and clang (fuzz/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "data/input_error.hpp"

namespace ecorail::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Runs f; a data::InputError (bad input, exit 2) is the expected way to refuse.
template <class F>
void refuse_cleanly(F&& f) {
  try {
    f();
  } catch (const data::InputError&) {
  }
}

}  // namespace ecorail::fuzz
