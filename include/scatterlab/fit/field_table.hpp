#pragma once
// The whole field (Vavassori §4.5, "the spatial behavior of the parameters ... and their
// interaction with the anisotropy factor g and albedo"): the lobe fits of every file of a sweep
// directory (scatterlab simulate --out-dir) in one table of parameters against
// (r, z, albedo, g).
//
// Every *.h5 file of the directory is read and checked before any is fitted, so that a bad
// file stops the run with its name and leaves every file as it was. Each file then gets its
// /fits/<model> (lobe_fits_file.hpp), and the table, albedo, g and the columns of
// write_fits_csv, one row per file and spatial bin, files in name order, is written to a
// temporary name and renamed into place.

#include <filesystem>
#include <vector>

#include "scatterlab/fit/lobe_fits_file.hpp"

namespace scatterlab::fit {

struct FieldFit {
  std::vector<RadianceLobes> files;
  std::vector<LobeFitRun> runs;  // one per file
};

// The *.h5 files of `directory`, in name order. Throws InputError("FILE", ...) when it holds
// none.
std::vector<std::filesystem::path> sweep_files(const std::filesystem::path& directory);

// Fits every file of `directory` (see the top of this file) and writes the table to `table`.
// Throws InputError("FILE", ...) for a file without the radiance tally or without albedo and g
// in /parameters, before any file is written. progress counts the spatial bins of every file.
FieldFit fit_field(const std::filesystem::path& directory, const std::filesystem::path& table,
                   const std::vector<LobeModel>& models, const FitOptions& options,
                   int quadrature_order, int threads, const WorkProgress& progress = {});

}  // namespace scatterlab::fit
