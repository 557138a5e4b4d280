// Placeholder until the fitting room lands: `ecorail calibrate`.
#include "cli/commands.hpp"

namespace ecorail::cli {
void add_calibrate_command(CLI::App&) {}
}  // namespace ecorail::cli
