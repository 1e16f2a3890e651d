// The frame every scatterlab program shares (program.hpp).
#include "program.hpp"

#include <fmt/format.h>
#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/spelling.hpp"
#include "value_checks.hpp"

namespace scatterlab::cli {
namespace {

// A reader that stopped reading (`scatterlab info run.h5 | head`) is not an error: the run ends as
// a write to a closed pipe ends it by default, by SIGPIPE, silently. This is reached only where
// SIGPIPE was ignored (by the parent), so that the write failed with EPIPE instead.
[[noreturn]] void end_as_by_sigpipe() {
  std::signal(SIGPIPE, SIG_DFL);
  std::raise(SIGPIPE);
  std::_Exit(128 + SIGPIPE);
}

// Errors go to stderr through stdio, which does not throw: fmt::print throws when stderr itself
// cannot be written (a full disk behind it), and from one of main's handlers that would abort.
template <typename... Args>
void print_error(fmt::format_string<Args...> format, Args&&... args) {
  std::fputs(fmt::format(format, std::forward<Args>(args)...).c_str(), stderr);
}

// The errno of a write to standard output that failed during the command (fmt::print throws).
int standard_output_error = 0;

bool reader_gone(int error) {
  if (error == EPIPE) return true;
  pollfd out{STDOUT_FILENO, POLLOUT, 0};  // a pipe whose reader closed polls as POLLERR
  return ::poll(&out, 1, 0) == 1 && (out.revents & POLLERR) != 0;
}

// Output that was lost is an error, as a file that could not be written is: a full disk or
// /dev/full behind standard output ends with one line on stderr and status 1, not status 0 and
// nothing written. fmt::print reports a failed write by throwing (main's handlers end up here
// too); CLI11's help and std::cout only mark the stream, so the end of main flushes and checks.
int finish_standard_output(int status) {
  // A write that failed earlier (CLI11's help, through std::cout) left its errno: nothing that
  // runs between it and here sets errno; the final flush, if it fails, tells for itself.
  const int earlier = errno;
  errno = 0;
  const bool flush_failed = std::fflush(stdout) != 0;  // std::cout writes through stdout
  const int error = flush_failed                 ? errno
                    : standard_output_error != 0 ? standard_output_error
                                                 : earlier;
  if (!flush_failed && !std::ferror(stdout) && !std::cout.bad()) return status;
  if (reader_gone(error)) end_as_by_sigpipe();
  print_error("scatterlab: error: cannot write standard output: {}\n",
              error != 0 ? std::strerror(error) : "part of it was lost");
  return status == 0 ? 1 : status;
}

// The command that was being read when parsing stopped: the deepest subcommand given.
const CLI::App& innermost_command(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return innermost_command(*sub);
  return app;
}

// The nearest accepted spelling of `typed`: a flag of `command` when it starts with '-', else
// one of its subcommands.
std::optional<std::string> nearest_spelling(const CLI::App& command, const std::string& typed) {
  std::vector<std::string> accepted;
  if (typed.rfind("-", 0) == 0) {
    for (const CLI::Option* option : command.get_options()) {
      for (const std::string& name : option->get_lnames()) accepted.push_back("--" + name);
      for (const std::string& name : option->get_snames()) accepted.push_back("-" + name);
    }
  } else {
    for (const CLI::App* sub : command.get_subcommands([](const CLI::App*) { return true; })) {
      accepted.push_back(sub->get_name());
    }
  }
  return nearest_name(typed, accepted);
}

// What a command line that did not parse gets, with its likely meaning as the scene's keys get
// one: an unexpected `--albdo` or `--albdo=0.3` is named first, whatever else CLI11 found (the
// value after a mistyped flag lands on a positional argument and may fail there), with the flag
// it was near; a mistyped command, with the command.
std::string parse_error_text(const CLI::App& app, const CLI::ParseError& error) {
  std::string message = error.what();
  std::replace(message.begin(), message.end(), '\n', ' ');
  const CLI::App& command = innermost_command(app);
  for (const std::string& argument : command.remaining()) {
    const bool flag = argument.rfind("-", 0) == 0;
    const std::string typed = flag ? argument.substr(0, argument.find('=')) : argument;
    const auto nearest = nearest_spelling(command, typed);
    if (flag) {
      return fmt::format("{}: not a flag of {}{}", typed, command.get_display_name(),
                         nearest ? fmt::format(" (did you mean {}?)", *nearest) : "");
    }
    // CLI11 does not name a mistyped command ("A subcommand is required").
    if (nearest) return fmt::format("{} (\"{}\": did you mean {}?)", message, typed, *nearest);
  }
  return message;
}

// A list that starts empty (--section, --Rd) has no default to show: not "=[]".
void hide_empty_list_defaults(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_default_str() == "[]") option->default_str("");
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    hide_empty_list_defaults(*sub);
  }
}

// The command line parsed and its command run, to an exit status.
int run_commands(int argc, char** argv, const AddCommands& add_commands) {
  std::string command_line = argv[0];
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];

  // Under mpirun every rank runs this program; only the root writes files and prints.
  std::unique_ptr<World> world;
  try {
    world = std::make_unique<World>(argc, argv);
  } catch (const InputError& e) {
    print_error("scatterlab: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    print_error("scatterlab: failed: {}\n", e.what());
    return 1;
  }

  CLI::App app{"scatterlab " SCATTERLAB_VERSION
               ": Monte Carlo light transport in participating media and the analytic models "
               "that approximate it"};
  app.set_version_flag("--version", SCATTERLAB_VERSION);
  // Every option's help shows its built-in default the one way CLI11 does (--albedo FLOAT=0.5),
  // taken from the value the option starts with; an option whose default follows from other
  // input (a scene's value, the output's name) says so in its default string.
  app.option_defaults()->always_capture_default();
  app.footer(
      "Exit status: 0 done; 2 bad input, found before any work (a flag, a scene file, an output "
      "whose directory takes no new files, a launcher's rank count such as OMPI_COMM_WORLD_SIZE "
      "set without a launcher); 1 a failure while running (a write that failed, standard output "
      "included: a full disk, /dev/full) or a report section that failed; 130 interrupted. A "
      "reader that stops reading (| head) ends scatterlab quietly, by SIGPIPE.");
  app.require_subcommand(1);
  const std::vector<Command> commands = add_commands(app, command_line, *world);
  check_numeric_values(app);
  hide_empty_list_defaults(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version: CLI11 prints them, with status 0.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return world->is_root() ? app.exit(e) : 0;
    }
    // Anything else is bad input, reported as every other: one line naming the flag, status 2.
    if (world->is_root()) {
      print_error("scatterlab: error: {} (see --help)\n", parse_error_text(app, e));
    }
    return 2;
  }
  try {
    for (const Command& command : commands) {
      if (app.got_subcommand(command.name)) return command.action();
    }
  } catch (const InputError& e) {
    // Bad input is found alike on every rank, before any of them waits on another.
    if (world->is_root()) print_error("scatterlab: error: {}\n", e.what());
    return 2;
  } catch (const std::system_error& e) {
    // fmt::print's failed write to standard output: reported by finish_standard_output.
    if (std::ferror(stdout)) {
      standard_output_error = e.code().value();
    } else {
      print_error("scatterlab: failed: {}\n", e.what());
    }
  } catch (const std::bad_alloc&) {
    // Past every estimate (core/memory_budget.hpp): still one line and status 1, not an abort.
    print_error(
        "scatterlab: failed: out of memory (an allocation was refused; --memory-limit "
        "makes the estimates refuse such a run before it starts)\n");
    if (world->size() > 1) world->abort(1);
    return 1;
  } catch (const std::exception& e) {
    print_error("scatterlab: failed: {}\n", e.what());
    if (world->size() > 1) world->abort(1);  // the other ranks may be waiting on this one
    return 1;
  }
  return 1;
}

}  // namespace

int run_program(int argc, char** argv, const AddCommands& add_commands) {
  return finish_standard_output(run_commands(argc, argv, add_commands));
}

}  // namespace scatterlab::cli
