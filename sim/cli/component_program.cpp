#include "component_program.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace scatterlab::cli {
namespace {

struct ComponentCommand {
  std::string_view command;
  std::string_view program;
};

constexpr auto kComponentCommands = std::to_array<ComponentCommand>({
#ifdef SCATTERLAB_WITH_FIT
    {"fit", "scatterlab-fit"},
    {"report", "scatterlab-fit"},
#endif
#ifdef SCATTERLAB_WITH_EXPLORE
    {"explore", "scatterlab-explore"},
#endif
    {"", ""},  // none: keeps the array non-empty in a build with neither component
});

}  // namespace

void run_component_program(char** argv) {
  const std::string_view given = argv[1];
  for (const ComponentCommand& entry : kComponentCommands) {
    if (entry.command.empty() || entry.command != given) continue;
    // Beside this program, in the build tree as where it is installed.
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    const std::filesystem::path program = self.parent_path() / entry.program;
    if (error || !std::filesystem::exists(program, error)) {
      throw std::runtime_error(
          fmt::format("{}: its program {} is not beside {}", given, entry.program, self.string()));
    }
    std::fflush(stdout);
    ::execv(program.c_str(), argv);
    throw std::runtime_error(
        fmt::format("{}: cannot run {}: {}", given, program.string(), std::strerror(errno)));
  }
}

Action add_component_command(CLI::App& app, const std::string& name,
                             const std::string& description) {
  app.add_subcommand(name, description)->allow_extras();
  return [name]() -> int { throw std::logic_error(name + ": not given to its own program"); };
}

}  // namespace scatterlab::cli
