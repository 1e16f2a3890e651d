#include "scatterlab/fit/field_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab::fit {

std::vector<std::filesystem::path> sweep_files(const std::filesystem::path& directory) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.is_regular_file() && entry.path().extension() == ".h5") files.push_back(entry.path());
  }
  if (files.empty()) {
    throw InputError("FILE", directory.string() + ": no .h5 files",
                     "a file, or a directory of files written by scatterlab simulate --out-dir");
  }
  std::sort(files.begin(), files.end());
  return files;
}

FieldFit fit_field(const std::filesystem::path& directory, const std::filesystem::path& table,
                   const std::vector<LobeModel>& models, const FitOptions& options,
                   int quadrature_order, int threads, const WorkProgress& progress) {
  FieldFit field;
  for (const std::filesystem::path& path : sweep_files(directory)) {
    RadianceLobes lobes = read_radiance_lobes(path);
    if (!std::isfinite(lobes.albedo) || !std::isfinite(lobes.g)) {
      throw InputError("FILE", path.string() + ": no albedo or g in /parameters",
                       "files written by scatterlab simulate");
    }
    field.files.push_back(std::move(lobes));
  }
  std::uint64_t bins = 0, bins_before = 0;
  for (const RadianceLobes& lobes : field.files) bins += lobes.r_bins() * lobes.z_bins();
  for (const RadianceLobes& lobes : field.files) {
    const LobeGrid grid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded, quadrature_order);
    WorkProgress file_progress;
    if (progress) {
      file_progress = [&](std::uint64_t done, std::uint64_t) {
        progress(bins_before + done, bins);
      };
    }
    field.runs.push_back(fit_lobes(lobes, grid, models, options, threads, file_progress));
    bins_before += lobes.r_bins() * lobes.z_bins();
    write_fits(lobes, grid, field.runs.back(), options);
  }
  write_text_file(table, [&field](std::ostream& csv) {
    std::vector<std::string> header = {"file", "albedo", "g"};
    const std::vector<std::string> columns = fits_csv_header(field.runs.front());
    header.insert(header.end(), columns.begin(), columns.end());
    csv << join_csv(header) << '\n';
    for (std::size_t f = 0; f < field.files.size(); ++f) {
      const RadianceLobes& lobes = field.files[f];
      for (std::vector<std::string> row : fits_csv_rows(lobes, field.runs[f])) {
        row.insert(row.begin(),
                   {lobes.path.filename().string(), fmt::format("{:.6g}", lobes.albedo),
                    fmt::format("{:.6g}", lobes.g)});
        csv << join_csv(row) << '\n';
      }
    }
  });
  return field;
}

}  // namespace scatterlab::fit
