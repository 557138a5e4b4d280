// Version information of this build: the project version (CMakeLists.txt), the git commit the
// build tree was configured from ("unknown" when built from a tarball without .git) and the
// CMake build type. Defined in a source file generated at configure time from
// cmake/version.cpp.in, so JSON provenance and `ecorail --version` report the same thing.
// Header: data/version.hpp (include "data/version.hpp"; link ecorail_core / ecorail::core).
#pragma once

#include <string>

namespace ecorail::data {

// "0.1.0"
const char* version();
// Abbreviated git commit hash at configure time, or "unknown".
const char* commit();
// "Release", "Debug", ... (the CMAKE_BUILD_TYPE of the library).
const char* build_type();
// One line for humans: "ecorail 0.1.0 (commit f4da038c1a2b, Release)".
std::string version_string();

}  // namespace ecorail::data
