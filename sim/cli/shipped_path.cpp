#include "shipped_path.hpp"

#include <system_error>

namespace scatterlab::cli {

std::filesystem::path shipped_path(const std::filesystem::path& installed,
                                   const std::filesystem::path& source) {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path beside =
        program.parent_path().parent_path() / "share/scatterlab" / installed;
    if (std::filesystem::exists(beside, error)) return beside;
  }
  return source;
}

}  // namespace scatterlab::cli
