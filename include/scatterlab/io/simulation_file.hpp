#pragma once
// The simulation file: one self-describing HDF5 file per run.
//
//   /                  attrs format="scatterlab", format_version=1, scatterlab_version, command,
//                            created (ISO 8601 UTC), wall_seconds, photons_run, scattering_events,
//                            batches_done, partial (1 when stopped before every batch ran),
//                            ranks, spec_fingerprint (simulation.hpp); merged files have
//                            merged_from (the input paths, one per line) instead of a fingerprint.
//                            wall_seconds and photons_run count the whole run, over every
//                            process that ran it (--resume); session_wall_seconds and
//                            session_photons_run the last process's share
//   /parameters        attrs source, albedo, g, sigma_t, sigma_a, sigma_s, length_unit, phase,
//                            photons, batches, seed, estimator, escape_radius (when finite),
//                            split_by_order, threads
//   /grid/{r,z,theta,phi[,rho]}   bin edges, attr units (the length unit, "mfp" by default, or
//                            "rad"); attr phi_folded on /grid (the half-space's and the
//                            sphere's grids are below)
//   /parameters        with a measured material (io/material_presets.hpp) also: material,
//                            material_table, material_citation, channel, material_note
//   /tallies/<name>    attrs units, description, dims ("r,z,theta,phi"; "" for a scalar)
//   /tallies/<name>/{mean,stderr}  the tally's shape; a scalar is a rank-0 dataset; attr units
//   /tallies/<name>/axes/<dim>     a declared tally's own bin edges (attr units), which stand in
//                                  for /grid/<dim> ([[tally]], transport/declared_tally.hpp)
//   /figures_of_merit/<name>  rank-0: 1 / (R^2 wall_seconds) of the tally
//                            (tally/figure_of_merit.hpp); attrs units "1/s", description
//   /models/<model>/<name>  a model's curve beside the tally <name> it compares with (attrs
//                            units, description, dims), <name>_error its numerical error when
//                            known; a model left out has only the attribute note (why)

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scatterlab/io/scene.hpp"
#include "scatterlab/tally/tally_result.hpp"
#include "scatterlab/transport/engine.hpp"

namespace scatterlab {

inline constexpr std::int64_t kSimulationFormatVersion = 1;

// Where a file came from: enough to reproduce and to judge the run.
struct Provenance {
  std::string version;  // scatterlab version that wrote the file
  std::string command;  // the command line, as typed
  std::string created;  // ISO 8601 UTC, e.g. "2024-05-01T12:34:56Z"
  double wall_seconds = 0.0;
  std::uint64_t photons_run = 0;
  std::uint64_t scattering_events = 0;
  // Fewer than parameters.batches marks the file partial; unset means all of them ran.
  std::optional<std::uint64_t> batches_done;
  int ranks = 1;
  // This process's share when it continued an earlier process's checkpoint (--resume); unset: the
  // whole run (wall_seconds, photons_run) ran in this process.
  std::optional<double> session_wall_seconds = std::nullopt;
  std::optional<std::uint64_t> session_photons_run = std::nullopt;
};

// The provenance of a transport run: the whole run's figures, and this process's share.
Provenance run_provenance(const TransportOutput& out, std::string command);

// The last guard before a tally reaches a file: throws std::runtime_error (exit status 1), naming
// the tally, when a mean or standard error is NaN or infinite. Every writer of tallies calls it
// before its file is created (write_simulation_file, merge).
void check_finite_tally(const std::string& name, const std::vector<double>& mean,
                        const std::vector<double>& stderr_of_mean);

// The current time as ISO 8601 UTC with second resolution: "YYYY-MM-DDTHH:MM:SSZ".
std::string iso8601_now();

// A model's curve on the run's grid, written as /models/<model>/<name> (attrs units, description,
// dims) and, when the model carries a numerical error estimate, /models/<model>/<name>_error.
struct ModelResult {
  std::string model;               // e.g. "dipole", "single_scatter"
  std::string name;                // the tally it compares with, e.g. "reflectance"
  std::vector<std::string> dims;   // empty for a scalar
  std::vector<std::size_t> shape;  // empty for a scalar
  std::string units;
  std::string description;
  std::vector<double> values;
  std::vector<double> error;  // empty, or one absolute error estimate per value
};
// A ModelResult without values is a model left out of this run: its group gets the attribute
// "note" with the description (why), and no dataset.

// Writes the whole file to a temporary name beside `path` and renames it into place, so that a
// failure leaves no file behind. Throws InputError("out", ...) when the directory does not
// exist, std::invalid_argument for an inconsistent tally, std::runtime_error for HDF5 failures.
// Tallies are written in the order given. Does not validate `spec` (the caller did). Model
// curves, if any (validate/point_source_models.hpp, searchlight_models.hpp), go under /models.
//
// Each geometry writes its own /parameters and /grid:
// - the infinite medium (transport/simulation.hpp): as in the layout above;
// - the half-space (transport/searchlight.hpp): /parameters adds geometry = "half_space", eta and
//   incidence_deg; /grid holds r, z (with the fluence) and theta_o, the exit angle outside the
//   medium, and x and y with the exitance map;
// - a lit object (transport/lit_object.hpp): /parameters adds geometry = "sphere", source
//   (directional, pole_beam, beam, sphere), radius and eta; /grid holds psi, the angle of a point
//   of the surface from the lit pole, and azimuth. For a mesh, geometry = "mesh" and
//   /parameters/mesh holds positions (n x 3, in the length unit), triangles (m x 3 vertex
//   indices, int32), area (m) and the attribute source; /grid is empty (the exitance is per
//   triangle); a sphere of light's radius and centre are the attribute light_sphere;
// - the layered slab (transport/layered_slab.hpp): /parameters adds geometry = "slab", the
//   indices above and below and the stack in /parameters/layers (mu_a, mu_s, g, n, thickness, top
//   down); /grid holds r, z, theta_o and layer (the interfaces' depths).
// The tallies are those each geometry declares (sim/transport/<geometry>.cpp).
void write_simulation_file(const std::filesystem::path& path, const SceneSpec& spec,
                           const std::vector<TallyResult>& tallies, const Provenance& provenance,
                           const std::vector<ModelResult>& models = {});

// What `scatterlab info FILE` reports, read back from a file.
struct AxisSummary {
  std::string name;
  std::size_t bins = 0;
  double min = 0.0;
  double max = 0.0;
  std::string units;
};

struct TallySummary {
  std::string name;
  std::vector<std::size_t> shape;  // empty for a scalar
  std::string dims;
  std::string units;
  std::string description;
  double mean_sum = 0.0;       // for a scalar, its value
  double mean_max = 0.0;       // for a scalar, its value
  double scalar_stderr = 0.0;  // scalars only: the standard error
  // Median of stderr / |mean| over bins with mean != 0; NaN when there are none.
  double median_relative_stderr = 0.0;
  std::size_t nonzero_bins = 0;
  std::vector<AxisSummary> axes;  // its own (a declared tally's), in place of /grid's

  bool is_scalar() const { return shape.empty(); }
};

struct FileSummary {
  std::filesystem::path path;
  std::int64_t format_version = 0;
  std::string scatterlab_version;
  std::string command;
  std::string created;
  double wall_seconds = 0.0;
  double session_wall_seconds = 0.0;  // of the last process; wall_seconds in older files
  std::int64_t photons_run = 0;
  std::int64_t scattering_events = 0;
  std::int64_t batches_done = 0;
  bool partial = false;
  std::int64_t ranks = 1;
  std::string spec_fingerprint;  // empty for merged files
  std::string merged_from;       // input paths, one per line; empty unless merged
  std::vector<std::pair<std::string, std::string>> parameters;  // name, value as text
  std::vector<AxisSummary> grid;
  bool phi_folded = false;
  std::vector<TallySummary> tallies;
  // /models/<model> and the curves it holds; /fits/<model> names (scatterlab fit).
  // Each model with its curves, or with the note that says why it has none.
  std::vector<std::pair<std::string, std::vector<std::string>>> models;
  std::vector<std::string> fits;
};

// Throws InputError(field, ...) for a file that is missing, not HDF5, not a scatterlab file, of
// another format_version, or one that contradicts itself: grid edges that are not finite or do
// not increase, or tallies whose shape is not the grid's.
FileSummary read_file_summary(const std::filesystem::path& path, const std::string& field = "FILE");
// The same without the tallies' values (`tallies` left empty): what a run, a resume, a merge or a
// fit needs to know of a file (partial, fingerprint, counts, parameters, grid) without reading
// every tally whole.
FileSummary read_file_header(const std::filesystem::path& path, const std::string& field = "FILE");
std::string describe(const FileSummary& summary);
// read_file_summary + describe: the text of `scatterlab info FILE`.
std::string describe_simulation_file(const std::filesystem::path& path);

}  // namespace scatterlab
