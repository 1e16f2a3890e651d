#pragma once
// What CLI11 would read silently is refused here, for every command at once: an empty value
// (`--albedo ''` read as 0), a number with trailing text, NaN, a double that overflows to inf,
// a negative value for an unsigned option (`--seed -1` read as 2^64 - 1) and integers in octal
// or hexadecimal (`--seed 010` read as 8). Each is one error naming the flag.

#include <CLI/CLI.hpp>
#include <string>

namespace scatterlab::cli {

// Adds the check to every numeric option (CLI11's type names FLOAT, INT, UINT) of `app` and of
// its subcommands, recursively. Call once, after every command has registered its options.
void check_numeric_values(CLI::App& app);

// The problem with `text` as a value of CLI11 type `type` ("FLOAT", "INT" or "UINT"), with what
// is accepted; empty when it is a well-formed number.
std::string numeric_value_problem(const std::string& text, const std::string& type);

}  // namespace scatterlab::cli
