#pragma once
// The commands of an optional component built as a program of its own (program.hpp):
// `scatterlab fit ...` runs `scatterlab-fit fit ...` from beside the core program, with the same
// arguments, in its place (exec), so that its help, errors, exit status and signals are the
// component's own.

#include <CLI/CLI.hpp>
#include <string>

namespace scatterlab::cli {

// When argv[1] is a component's command, replaces this process by the component's program; it
// returns only when argv[1] is none, and throws std::runtime_error when the program is missing
// or cannot be run.
void run_component_program(char** argv);

// Lists the component's command under --help, and nothing more: main gives the command to the
// component's program before parsing.
void list_component_command(CLI::App& app, const std::string& name, const std::string& description);

}  // namespace scatterlab::cli
