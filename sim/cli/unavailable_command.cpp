// A command of an optional component that this build left out (CMakeLists.txt, "Optional
// components"): it is still listed, so that a user learns what to install rather than that the
// command does not exist.
#include <fmt/format.h>

#include "commands.hpp"
#include "scatterlab/core/error.hpp"

namespace scatterlab::cli {

Action add_unavailable_command(CLI::App& app, const std::string& name,
                               const std::string& description, const std::string& needs) {
  auto* command = app.add_subcommand(
      name, fmt::format("{} (not in this build: it needs {})", description, needs));
  command->allow_extras();
  return [name, needs]() -> int { throw not_in_this_build(name, needs); };
}

}  // namespace scatterlab::cli
