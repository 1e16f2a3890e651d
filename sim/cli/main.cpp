// scatterlab: Monte Carlo transport of light in participating media, from the command line.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <string>

#include "commands.hpp"
#include "scatterlab/core/error.hpp"

int main(int argc, char** argv) {
  std::string command_line = argv[0];
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];

  CLI::App app{"scatterlab " SCATTERLAB_VERSION
               ": Monte Carlo light transport in participating media and the analytic models "
               "that approximate it"};
  app.set_version_flag("--version", SCATTERLAB_VERSION);
  app.require_subcommand(1);
  const auto simulate = scatterlab::cli::add_simulate_command(app, command_line);
  const auto searchlight = scatterlab::cli::add_searchlight_command(app, command_line);
  const auto info = scatterlab::cli::add_info_command(app);
  const auto fit = scatterlab::cli::add_fit_command(app);
  const auto validate = scatterlab::cli::add_validate_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("simulate")) return simulate();
    if (app.got_subcommand("searchlight")) return searchlight();
    if (app.got_subcommand("info")) return info();
    if (app.got_subcommand("fit")) return fit();
    if (app.got_subcommand("validate")) return validate();
  } catch (const scatterlab::InputError& e) {
    fmt::print(stderr, "scatterlab: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "scatterlab: failed: {}\n", e.what());
    return 1;
  }
  return 1;
}
