#pragma once
// What every fuzz target shares: which exceptions are a clean refusal of bad input, and a private
// working folder for targets whose reader takes a path.
//
// A clean refusal is what the command line's handler (sim/cli/program.cpp) reports as one line:
// any std::exception. With SCATTERLAB_FUZZ_STRICT=1 in the environment only InputError,
// std::invalid_argument and std::runtime_error count (the exceptions whose message says what is
// wrong); another std::exception (std::out_of_range, std::length_error, a JSON library's error)
// reaches the user as "failed: <library text>" with exit status 1, and is then a finding too.
// Anything else that leaves the reader (a crash, a sanitizer report, an exception the handler
// does not catch) is always one.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"

namespace scatterlab::fuzz {

inline bool strict() {
  static const bool on = [] {
    const char* value = std::getenv("SCATTERLAB_FUZZ_STRICT");
    return value != nullptr && std::string_view(value) == "1";
  }();
  return on;
}

// Stops the run as a finding, with what was thrown (libFuzzer saves the input).
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "scatterlab fuzz finding: %s\n", what.c_str());
  std::abort();
}

// Runs `read` on one input: a clean refusal returns, everything else is a finding.
template <typename Read>
void expect_clean(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    if (strict()) finding(std::string("unclean refusal ") + typeid(e).name() + ": " + e.what());
  }
}

// Every target runs as under --memory-limit 2G, libFuzzer's -rss_limit_mb: the estimates refuse
// what would not fit there, so an input they admit that then runs out of memory is a finding.
// (The machine's own limit would also be read from the cgroup's files at every check.)
inline void limit_memory() {
  set_memory_limit(std::uint64_t{2} << 30, "2G");
}

inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A fresh, empty folder of this process under $TMPDIR for the files a target writes, and the base
// of the relative paths an input may name (the working directory stays libFuzzer's: its corpus
// and artifact paths may be relative). Removed at exit.
inline const std::filesystem::path& work_folder() {
  static const std::filesystem::path folder = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "scatterlab-fuzz-XXXXXX");
    if (::mkdtemp(pattern.data()) == nullptr) finding("cannot make a temporary folder");
    const std::filesystem::path made = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(work_folder(), ignored);
    });
    return made;
  }();
  return folder;
}

// Writes `bytes` to `name` in the working folder and returns its path.
inline std::filesystem::path write_input(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = work_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) finding("cannot write " + path.string());
  return path;
}

}  // namespace scatterlab::fuzz
