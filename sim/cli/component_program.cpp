#include "component_program.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace scatterlab::cli {
namespace {

// The program of a component's command; empty for a command of the core program.
std::string_view program_of(std::string_view command) {
#ifdef SCATTERLAB_WITH_FIT
  if (command == "fit" || command == "report") return "scatterlab-fit";
#endif
#ifdef SCATTERLAB_WITH_EXPLORE
  if (command == "explore") return "scatterlab-explore";
#endif
  (void)command;
  return {};
}

}  // namespace

void run_component_program(char** argv) {
  const std::string_view given = argv[1];
  const std::string_view name = program_of(given);
  if (name.empty()) return;
  // Beside this program, in the build tree as where it is installed.
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path program = self.parent_path() / name;
  if (error || !std::filesystem::exists(program, error)) {
    throw std::runtime_error(
        fmt::format("{}: its program {} is not beside {}", given, name, self.string()));
  }
  std::fflush(stdout);
  ::execv(program.c_str(), argv);
  throw std::runtime_error(
      fmt::format("{}: cannot run {}: {}", given, program.string(), std::strerror(errno)));
}

void list_component_command(CLI::App& app, const std::string& name,
                            const std::string& description) {
  app.add_subcommand(name, description)->allow_extras();
}

}  // namespace scatterlab::cli
