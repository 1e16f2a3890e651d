#pragma once
// --memory-limit SIZE, on every command that runs work or reads files: the memory the run may
// use in place of the machine's (core/memory_budget.hpp). Each command checks what it will hold
// against it before it allocates.

#include <CLI/CLI.hpp>

namespace scatterlab::cli {

void add_memory_limit_option(CLI::App& command);

}  // namespace scatterlab::cli
