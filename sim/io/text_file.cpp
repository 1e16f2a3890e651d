#include "scatterlab/io/text_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <system_error>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/output_plan.hpp"

namespace scatterlab {
namespace {

namespace fs = std::filesystem;

const std::string accepted = "a regular TOML file of at most 1 MiB";

}  // namespace

void check_scene_file(const fs::path& path, const std::string& field) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) {
    throw InputError(field, fmt::format("'{}' does not exist", path.string()), accepted);
  }
  if (!fs::is_regular_file(status)) {
    throw InputError(field, fmt::format("'{}' is {}", path.string(), file_type_text(status.type())),
                     accepted);
  }
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) {
    throw InputError(field, fmt::format("cannot read '{}': {}", path.string(), error.message()),
                     accepted);
  }
  if (size > max_scene_bytes) {
    throw InputError(field, fmt::format("'{}' holds {} bytes", path.string(), size), accepted);
  }
}

std::string read_scene_file(const fs::path& path, const std::string& field) {
  check_scene_file(path, field);
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) {
    throw InputError(field, fmt::format("cannot read '{}'", path.string()), accepted);
  }
  std::string text(max_scene_bytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw InputError(field, fmt::format("cannot read '{}'", path.string()), accepted);
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max_scene_bytes) {
    throw InputError(field, fmt::format("'{}' holds more than 1 MiB", path.string()), accepted);
  }
  return text;
}

}  // namespace scatterlab
