// scatterlab: Monte Carlo transport of light in participating media, from the command line.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "commands.hpp"
#include "value_checks.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/parallel/world.hpp"

int main(int argc, char** argv) {
  std::string command_line = argv[0];
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];

  // Under mpirun every rank runs this program; only the root writes files and prints.
  std::unique_ptr<scatterlab::World> world;
  try {
    world = std::make_unique<scatterlab::World>(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "scatterlab: failed: {}\n", e.what());
    return 1;
  }

  CLI::App app{"scatterlab " SCATTERLAB_VERSION
               ": Monte Carlo light transport in participating media and the analytic models "
               "that approximate it"};
  app.set_version_flag("--version", SCATTERLAB_VERSION);
  app.require_subcommand(1);
  const auto simulate = scatterlab::cli::add_simulate_command(app, command_line, *world);
  const auto searchlight = scatterlab::cli::add_searchlight_command(app, command_line, *world);
  const auto info = scatterlab::cli::add_info_command(app);
  const auto fit = scatterlab::cli::add_fit_command(app);
  const auto validate = scatterlab::cli::add_validate_command(app);
  const auto merge = scatterlab::cli::add_merge_command(app, command_line);
  const auto report = scatterlab::cli::add_report_command(app, command_line);
  const auto render = scatterlab::cli::add_render_command(app);
  const auto invert = scatterlab::cli::add_invert_command(app);
  scatterlab::cli::check_numeric_values(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version: CLI11 prints them, with status 0.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return world->is_root() ? app.exit(e) : 0;
    }
    // Anything else is bad input, reported as every other: one line naming the flag, status 2.
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    if (world->is_root()) fmt::print(stderr, "scatterlab: error: {} (see --help)\n", message);
    return 2;
  }
  try {
    if (app.got_subcommand("simulate")) return simulate();
    if (app.got_subcommand("searchlight")) return searchlight();
    if (app.got_subcommand("info")) return info();
    if (app.got_subcommand("fit")) return fit();
    if (app.got_subcommand("validate")) return validate();
    if (app.got_subcommand("merge")) return merge();
    if (app.got_subcommand("report")) return report();
    if (app.got_subcommand("render")) return render();
    if (app.got_subcommand("invert")) return invert();
  } catch (const scatterlab::InputError& e) {
    // Bad input is found alike on every rank, before any of them waits on another.
    if (world->is_root()) fmt::print(stderr, "scatterlab: error: {}\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    // Past every estimate (core/memory_budget.hpp): still one line and status 1, not an abort.
    fmt::print(stderr,
               "scatterlab: failed: out of memory (an allocation was refused; --memory-limit "
               "makes the estimates refuse such a run before it starts)\n");
    if (world->size() > 1) world->abort(1);
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "scatterlab: failed: {}\n", e.what());
    if (world->size() > 1) world->abort(1);  // the other ranks may be waiting on this one
    return 1;
  }
  return 1;
}
