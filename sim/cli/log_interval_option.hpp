#pragma once
// --log-interval SECONDS, on every command that reports progress (progress_reporter.hpp): how
// often a plain progress line is written to standard error when it is not a terminal.

#include <CLI/CLI.hpp>
#include <memory>

namespace scatterlab::cli {

// The seconds between lines, 60 unless given; 0 writes none.
std::shared_ptr<double> add_log_interval_option(CLI::App& command);

}  // namespace scatterlab::cli
