// Placeholder until the fitting room lands: `ecorail fit-envelope`.
#include "cli/commands.hpp"

namespace ecorail::cli {
void add_fit_envelope_command(CLI::App&) {}
}  // namespace ecorail::cli
