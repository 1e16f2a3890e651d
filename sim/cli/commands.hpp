#pragma once
// The subcommands of the `scatterlab` program. Each registers its options on the app and
// returns the action to run once the command line has been parsed.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>

#include "scatterlab/parallel/world.hpp"

namespace scatterlab::cli {

using Action = std::function<int()>;

// `command_line` is the whole command as typed, recorded in output files. Commands that run
// photons spread them over the ranks of `world`; only its root writes files and prints.
Action add_simulate_command(CLI::App& app, const std::string& command_line, World& world);
Action add_searchlight_command(CLI::App& app, const std::string& command_line, World& world);
// scatterlab scene: the scene's keys (io/scene_schema.hpp), as a JSON Schema or a reference.
Action add_scene_command(CLI::App& app);
// scatterlab materials [NAME]: the measured media of data/materials, compiled in.
Action add_materials_command(CLI::App& app);
Action add_info_command(CLI::App& app);
Action add_fit_command(CLI::App& app);
Action add_validate_command(CLI::App& app);
Action add_merge_command(CLI::App& app, const std::string& command_line);
Action add_report_command(CLI::App& app, const std::string& command_line);
Action add_render_command(CLI::App& app);
Action add_invert_command(CLI::App& app);
Action add_mcml_command(CLI::App& app, const std::string& command_line, World& world);
Action add_explore_command(CLI::App& app);

// What --help says of the commands of components that are programs of their own
// (component_program.hpp), both in the core program's list and in their own.
inline constexpr const char* kFitDescription =
    "Fit lobe models to every spatial bin of a simulation file (Vavassori 2013, §4.2)";
inline constexpr const char* kReportDescription =
    "Run the accuracy suite: every method against its exact reference, error against run time, "
    "stiff and extreme cases; write a Markdown report with CSVs. Exits 1 if any check fails";
inline constexpr const char* kExploreDescription =
    "The explorer in a browser (Bitterli §3.6): R_d(r) of every model for a material you change, "
    "in linear, log, sqrt and r R_d plots; presets, (R_dr, l_d) inversion, models from text "
    "files, searchlight files and the lit sphere. Serves this machine only unless --host says "
    "otherwise; runs until interrupted (Ctrl-C).";

// Stands in for a command whose optional component was not built: it takes any arguments and,
// run, stops with bad-input status 2 and one line saying what the build needs, e.g. "Ceres
// (Debian: libceres-dev)".
Action add_unavailable_command(CLI::App& app, const std::string& name,
                               const std::string& description, const std::string& needs);

// --photons as a double, so that 1e8 reads as it does in scene files; throws InputError
// ("run.photons") unless it is a whole number that fits.
std::uint64_t photon_count(double photons);

}  // namespace scatterlab::cli
