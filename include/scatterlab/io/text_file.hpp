#pragma once
// Scene files are small regular files: a directory, a device (/dev/urandom never ends), a FIFO
// (blocks until someone writes) or a socket is refused before it is opened, and so is a file over
// max_scene_bytes. Every scene reader (simulate, searchlight, render) and the --scene flags check
// with these.

#include <cstdint>
#include <filesystem>
#include <string>

namespace scatterlab {

// 1 MiB: the largest scene shipped is a few kB; a sweep of thousands of values still fits.
inline constexpr std::uintmax_t max_scene_bytes = std::uintmax_t{1} << 20;

// Throws InputError naming `field` unless `path` is, after symbolic links, a regular file of at
// most max_scene_bytes.
void check_scene_file(const std::filesystem::path& path, const std::string& field);

// The text of the scene file at `path`, after check_scene_file; a file that grows past the limit
// while it is read is refused as well. Throws InputError naming `field`.
std::string read_scene_file(const std::filesystem::path& path, const std::string& field);

}  // namespace scatterlab
