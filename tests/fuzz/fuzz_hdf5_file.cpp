// HDF5 files as the commands read them: `info` (read_file_summary and its text), a run's output
// before --resume and a sweep's skip (read_file_header), `--resume`'s checkpoint
// (read_checkpoint), `fit` (read_radiance_lobes and the lobe grid), `merge` (beside a sound file
// of another seed) and the explorer's /api/file. The bytes are written to a file in the working
// folder, which is all the readers are given.

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "scatterlab/explore/api.hpp"
#include "scatterlab/fit/lobe_fits_file.hpp"
#include "scatterlab/fit/lobe_grid.hpp"
#include "scatterlab/io/checkpoint_file.hpp"
#include "scatterlab/io/merge.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace {

using namespace scatterlab;

// The fingerprint of the run that wrote corpus/hdf5_file/interrupted.checkpoint (README.md): with
// it the reader goes on past the fingerprint to the counts and values.
const std::string kCheckpointFingerprint = "423459b2a8ef6f2b";

std::unique_ptr<const ExploreApi> explorer;

}  // namespace

// HDF5 1.10 loses what it had read of a damaged file's metadata when a read fails partway (its own
// allocators, never called by our code, which holds identifiers only): those leaks are HDF5's.
// A leak of ours is an identifier left open, checked after every input below.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:H5FL__malloc\nleak:H5MM_malloc\nleak:H5MM_calloc\nleak:H5MM_realloc\n"
         "leak:H5MM_xstrdup\nleak:H5MM_strdup\nleak:H5MM_strndup\n";
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  // HDF5 keeps the blocks it frees for the next file: each open allocates a metadata cache of
  // about a megabyte, which the sanitizer would otherwise map, fault in and unmap every time.
  H5set_free_list_limits(-1, -1, -1, -1, -1, -1);
  ExploreOptions options;
  options.page = std::filesystem::path(SCATTERLAB_SOURCE_DIR) / "web";
  options.open_folders = {fuzz::work_folder()};
  explorer = std::make_unique<const ExploreApi>(options);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = fuzz::write_input("input.h5", fuzz::text_of(data, size));

  fuzz::expect_clean([&] { (void)describe_simulation_file(path); });
  fuzz::expect_clean([&] { (void)read_file_header(path); });
  fuzz::expect_clean([&] { (void)is_checkpoint_of(path, kCheckpointFingerprint); });
  fuzz::expect_clean([&] { (void)read_checkpoint(path, kCheckpointFingerprint); });
  fuzz::expect_clean([&] {
    const fit::RadianceLobes lobes = fit::read_radiance_lobes(path);
    (void)fit::LobeGrid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded, /*quadrature=*/3);
  });
  fuzz::expect_clean([&] {
    const std::filesystem::path partner =
        std::filesystem::path(SCATTERLAB_FUZZ_DIR) / "hdf5_merge_partner.h5";
    (void)merge_simulation_files({partner, path}, fuzz::work_folder() / "merged.h5", "fuzz");
  });
  // The explorer answers every failure itself (a status and a JSON error); only a crash is a
  // finding here.
  (void)explorer->handle("GET", "/api/file", {{"path", "0/input.h5"}}, "");

  // Every identifier the readers opened is closed again: one left open would keep the file open
  // (HDF5 would hand the next input's reader the stale file).
  const ssize_t open = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
  if (open != 0) fuzz::finding(std::to_string(open) + " HDF5 identifiers left open");
  return 0;
}
