// printf-style formatting into a std::string, for solver reports and error messages.
#pragma once

#include <cstdio>
#include <string>

namespace ecorail::dp {

template <typename... Args>
std::string format_text(const char* fmt, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace ecorail::dp
