#pragma once
// Writes a report directory: report.md with every section, one CSV per section table. Each file
// is written to a temporary name and renamed into place.

#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/report/section.hpp"

namespace scatterlab::report {

// Creates `directory` if it is missing (its parent must exist: InputError "out" otherwise).
// Returns every file written, report.md last.
std::vector<std::filesystem::path> write_report(const std::filesystem::path& directory,
                                                const std::string& command_line,
                                                const std::vector<Section>& sections);

// The table as RFC 4180 CSV and as a Markdown table.
std::string to_csv(const Table& table);
std::string to_markdown(const Table& table);

}  // namespace scatterlab::report
