#pragma once
// Where a file the project ships is, wherever the program runs: installed beside the program
// (<prefix>/share/scatterlab/<installed>, as `cmake --install` lays it out), else in the source
// tree the program was built from.

#include <filesystem>

namespace scatterlab::cli {

// `installed` relative to <prefix>/share/scatterlab; `source` absolute.
std::filesystem::path shipped_path(const std::filesystem::path& installed,
                                   const std::filesystem::path& source);

}  // namespace scatterlab::cli
