// ecorail::format_text: printf-style formatting into a std::string, for reports and error
// messages in every room (dp/ re-exports it as dp::format_text). At most 511 characters: the
// text is cut there, never overrun.
#pragma once

#include <cstdio>
#include <string>

namespace ecorail {

template <typename... Args>
std::string format_text(const char* fmt, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace ecorail
