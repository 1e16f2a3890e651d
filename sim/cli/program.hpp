#pragma once
// The frame every scatterlab program shares: the world of ranks, the command line (its
// description, version and exit statuses), errors as one line each, and the command given run
// to an exit status. The core program, `scatterlab`, holds the commands that run photons (and
// so every library a scene may need: simulate's meshes need the renderer); fit and report
// (Ceres) and explore (an HTTP server) are programs of their own beside it
// (component_program.hpp), so that a run of photons does not load their libraries.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "scatterlab/parallel/world.hpp"

namespace scatterlab::cli {

// A command of the program: its name on the command line and what it does once parsed.
struct Command {
  std::string name;
  Action action;
};

// Adds the program's commands to `app`; `command_line` is the whole command as typed.
using AddCommands = std::function<std::vector<Command>(
    CLI::App& app, const std::string& command_line, World& world)>;

// The program's main: returns its exit status, standard output flushed and checked.
int run_program(int argc, char** argv, const AddCommands& add_commands);

}  // namespace scatterlab::cli
