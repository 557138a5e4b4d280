// QuietStderr: silences the process's standard error (file descriptor 2) for a scope. Some
// libraries print their own diagnostics (libxlsxwriter's "[ERROR] workbook_close(): ..." on a
// full disk) before returning an error code; the program reports the failure itself in one
// line (cli/errors.cpp), so their text is kept out. Use only around a single library call on
// the thread that writes the outputs.
#pragma once

#include <fcntl.h>
#include <unistd.h>

namespace ecorail::output {

class QuietStderr {
 public:
  QuietStderr() : saved_(::dup(STDERR_FILENO)) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null >= 0) ::dup2(null, STDERR_FILENO);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    if (saved_ >= 0) {
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

}  // namespace ecorail::output
