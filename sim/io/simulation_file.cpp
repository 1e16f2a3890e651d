#include "scatterlab/io/simulation_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <ctime>
#include <limits>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "dimension_scales.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/tally/figure_of_merit.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"

namespace scatterlab {

namespace {

// Counts are stored as int64 so that numpy arithmetic on them stays integral.
std::int64_t as_int64(std::uint64_t value, const char* field) {
  if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw std::invalid_argument(std::string(field) + " does not fit in int64");
  }
  return static_cast<std::int64_t>(value);
}

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t values = 1;
  for (const std::size_t extent : shape) values *= extent;
  return values;
}

// A tally that does not describe its own arrays is a programming error; catch it before any
// file is created.
void check_tallies(const std::vector<TallyResult>& tallies) {
  std::set<std::string> names;
  for (const TallyResult& tally : tallies) {
    const std::string label = "tally '" + tally.name + "': ";
    if (tally.name.empty() || tally.name.find('/') != std::string::npos || tally.name == "." ||
        tally.name == "..") {
      throw std::invalid_argument(label + "name must be non-empty, without '/'");
    }
    if (!names.insert(tally.name).second) throw std::invalid_argument(label + "written twice");
    if (tally.dims.size() != tally.shape.size()) {
      throw std::invalid_argument(label + "dims and shape differ in rank");
    }
    const std::size_t values = product(tally.shape);
    if (tally.mean.size() != values || tally.stderr_of_mean.size() != values) {
      throw std::invalid_argument(label + fmt::format("shape holds {} values, mean has {}, "
                                                      "stderr has {}",
                                                      values, tally.mean.size(),
                                                      tally.stderr_of_mean.size()));
    }
    check_finite_tally(tally.name, tally.mean, tally.stderr_of_mean);
  }
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
  std::string joined;
  for (std::size_t i = 0; i < parts.size(); ++i) joined += (i == 0 ? "" : separator) + parts[i];
  return joined;
}

// `batches`: how many the run asked for; `spec_fingerprint`: its identity.
void write_provenance(hdf5::Group& root, const Provenance& provenance, std::uint64_t batches,
                      const std::string& spec_fingerprint) {
  root.write_string_attribute("format", "scatterlab");
  root.write_int64_attribute("format_version", kSimulationFormatVersion);
  root.write_string_attribute("scatterlab_version", provenance.version);
  root.write_string_attribute("command", provenance.command);
  root.write_string_attribute("created", provenance.created);
  root.write_double_attribute("wall_seconds", provenance.wall_seconds);
  root.write_int64_attribute("photons_run", as_int64(provenance.photons_run, "photons_run"));
  root.write_double_attribute("session_wall_seconds",
                              provenance.session_wall_seconds.value_or(provenance.wall_seconds));
  root.write_int64_attribute(
      "session_photons_run",
      as_int64(provenance.session_photons_run.value_or(provenance.photons_run),
               "session_photons_run"));
  root.write_int64_attribute("scattering_events",
                             as_int64(provenance.scattering_events, "scattering_events"));
  const std::uint64_t batches_done = provenance.batches_done.value_or(batches);
  root.write_int64_attribute("batches_done", as_int64(batches_done, "batches_done"));
  root.write_bool_attribute("partial", batches_done < batches);
  root.write_int64_attribute("ranks", provenance.ranks);
  root.write_string_attribute("spec_fingerprint", spec_fingerprint);
}

void write_medium(hdf5::Group& parameters, const Medium& medium) {
  parameters.write_double_attribute("albedo", medium.albedo);
  parameters.write_double_attribute("g", medium.g);
  parameters.write_double_attribute("sigma_t", medium.sigma_t);
  parameters.write_double_attribute("sigma_a", medium.sigma_a());
  parameters.write_double_attribute("sigma_s", medium.sigma_s());
  parameters.write_string_attribute("length_unit", medium.length_unit);
  // g = 0 samples isotropically (docs/architecture.md, "Leave out what a scene does not need").
  parameters.write_string_attribute("phase", medium.g == 0.0 ? "isotropic" : "henyey-greenstein");
}

// Only for a medium from a measured table (data/materials), so other files are as they were.
void write_material(hdf5::Group& parameters, const std::optional<MaterialOrigin>& material) {
  if (!material) return;
  parameters.write_string_attribute("material", material->name);
  parameters.write_string_attribute("material_table", material->library);
  parameters.write_string_attribute("material_citation", material->citation);
  parameters.write_string_attribute("channel", material->channel);
  if (!material->note.empty()) parameters.write_string_attribute("material_note", material->note);
}

void write_run(hdf5::Group& parameters, const RunSettings& run) {
  parameters.write_int64_attribute("photons", as_int64(run.photons, "photons"));
  parameters.write_int64_attribute("batches", run.batches);
  // Any 64-bit seed is valid, so it is the one unsigned attribute.
  parameters.write_uint64_attribute("seed", run.seed);
}

void write_parameters(hdf5::Group& root, const InfiniteMediumSpec& spec) {
  hdf5::Group parameters = root.create_group("parameters");
  parameters.write_string_attribute("source", to_string(spec.source));
  write_medium(parameters, spec.medium);
  write_material(parameters, spec.material);
  write_run(parameters, spec.run);
  parameters.write_string_attribute("estimator", to_string(spec.tallies.estimator));
  if (std::isfinite(spec.run.escape_radius)) {
    parameters.write_double_attribute("escape_radius", spec.run.escape_radius);
  }
  parameters.write_bool_attribute("split_by_order", spec.tallies.split_by_order);
  parameters.write_int64_attribute("threads", spec.run.threads);
}

// The half-space run: geometry, interface and beam first.
void write_searchlight_parameters(hdf5::Group& root, const HalfSpaceSpec& spec) {
  hdf5::Group parameters = root.create_group("parameters");
  parameters.write_string_attribute("geometry", "half_space");
  parameters.write_string_attribute("source", "beam");
  parameters.write_double_attribute("eta", spec.eta);
  parameters.write_double_attribute("incidence_deg", spec.incidence_deg);
  write_medium(parameters, spec.medium);
  write_material(parameters, spec.material);
  write_run(parameters, spec.run);
  parameters.write_string_attribute("estimator", "collision");
  if (std::isfinite(spec.run.escape_radius)) {
    parameters.write_double_attribute("escape_radius", spec.run.escape_radius);
  }
  parameters.write_bool_attribute("split_by_order", true);
  parameters.write_int64_attribute("threads", spec.run.threads);
}

// A mesh's vertices (in the length unit), its triangles (vertex indices, counter-clockwise seen
// from outside) and their areas: what the exitance per triangle is drawn on.
void write_mesh(hdf5::Group& parameters, const LitObjectSpec& spec) {
  const TriangleMesh& mesh = *spec.mesh;
  hdf5::Group group = parameters.create_group("mesh");
  group.write_string_attribute("source", spec.mesh_source);
  std::vector<double> positions;
  for (const Vec3& p : mesh.positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
  group.write_dataset("positions", positions, {mesh.positions.size(), 3})
      .write_string_attribute("units", spec.medium.length_unit);
  std::vector<std::int32_t> corners;
  std::vector<double> areas;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) corners.push_back(static_cast<std::int32_t>(v));
    areas.push_back(mesh.area(t));
  }
  group.write_dataset("triangles", corners, {mesh.triangle_count(), 3});
  group.write_dataset("area", areas)
      .write_string_attribute("units", spec.medium.length_unit + "^2");
}

void write_lit_sphere_parameters(hdf5::Group& root, const LitObjectSpec& spec) {
  hdf5::Group parameters = root.create_group("parameters");
  parameters.write_string_attribute("geometry", spec.mesh ? "mesh" : "sphere");
  parameters.write_string_attribute("source", to_string(spec.light));
  if (spec.mesh) {
    write_mesh(parameters, spec);
  } else {
    parameters.write_double_attribute("radius", spec.radius);
  }
  if (spec.light == ObjectLight::sphere) {
    parameters.write_string_attribute(
        "light_sphere",
        fmt::format("radius {} about ({}, {}, {})", spec.light_radius, spec.light_center[0],
                    spec.light_center[1], spec.light_center[2]));
  }
  if (spec.light == ObjectLight::beam) {
    parameters.write_string_attribute(
        "beam", fmt::format("from ({}, {}, {}) along ({}, {}, {})", spec.beam_origin[0],
                            spec.beam_origin[1], spec.beam_origin[2], spec.beam_direction[0],
                            spec.beam_direction[1], spec.beam_direction[2]));
  }
  parameters.write_double_attribute("eta", spec.eta);
  write_medium(parameters, spec.medium);
  write_material(parameters, spec.material);
  write_run(parameters, spec.run);
  parameters.write_string_attribute("estimator", "collision");
  parameters.write_bool_attribute("split_by_order", spec.split_by_order);
  parameters.write_int64_attribute("threads", spec.run.threads);
}

void write_axis(hdf5::Group& grid, const char* name, const UniformAxis& axis,
                const std::string& units) {
  const std::vector<double> edges = axis.edges();
  grid.write_dataset(name, edges).write_string_attribute("units", units);
}

// The slab's stack as datasets of /parameters/layers, one value per layer, top down, in the
// spec's length unit.
void write_layered_slab_parameters(hdf5::Group& root, const LayeredSlabSpec& spec) {
  hdf5::Group parameters = root.create_group("parameters");
  parameters.write_string_attribute("geometry", "slab");
  parameters.write_string_attribute("source", "pencil beam at normal incidence");
  parameters.write_string_attribute("length_unit", spec.length_unit);
  parameters.write_double_attribute("n_above", spec.n_above);
  parameters.write_double_attribute("n_below", spec.n_below);
  hdf5::Group layers = parameters.create_group("layers");
  const std::string inverse = spec.length_unit + "^-1";
  const auto column = [&](const char* name, double SlabLayerSpec::*field,
                          const std::string& units) {
    std::vector<double> values;
    for (const SlabLayerSpec& l : spec.layers) values.push_back(l.*field);
    layers.write_dataset(name, values).write_string_attribute("units", units);
  };
  column("mu_a", &SlabLayerSpec::mu_a, inverse);
  column("mu_s", &SlabLayerSpec::mu_s, inverse);
  column("g", &SlabLayerSpec::g, "1");
  column("n", &SlabLayerSpec::n, "1");
  column("thickness", &SlabLayerSpec::thickness, spec.length_unit);
  write_run(parameters, spec.run);
  parameters.write_string_attribute("weighting", to_string(spec.weighting));
  parameters.write_bool_attribute("split_by_order", spec.split_by_order);
  parameters.write_int64_attribute("threads", spec.run.threads);
}

// Grid lengths are in the medium's length unit, mean free paths by default (docs/architecture.md,
// "Units"): the spec holds them in that unit, and the tallies come back from transport in it.
void write_grid(hdf5::Group& root, const InfiniteMediumSpec& spec) {
  hdf5::Group grid = root.create_group("grid");
  const std::string& length = spec.medium.length_unit;
  grid.write_bool_attribute("phi_folded", spec.grid.fold_phi);
  write_axis(grid, "r", spec.grid.r, length);
  write_axis(grid, "z", spec.grid.z, length);
  write_axis(grid, "theta", spec.grid.theta, "rad");
  write_axis(grid, "phi", spec.grid.phi, "rad");
  if (spec.tallies.fluence_spherical) write_axis(grid, "rho", spec.grid.rho, length);
}

// r from the entry point and z depth in the medium's length unit; theta_o from the outward
// normal, outside.
void write_searchlight_grid(hdf5::Group& root, const HalfSpaceSpec& spec) {
  hdf5::Group grid = root.create_group("grid");
  const std::string& length = spec.medium.length_unit;
  write_axis(grid, "r", spec.grid.r, length);
  if (spec.tallies.fluence) write_axis(grid, "z", spec.grid.z, length);
  write_axis(grid, "theta_o", spec.grid.theta_o, "rad");
  if (spec.tallies.exitance_map) {
    write_axis(grid, "x", spec.grid.x, length);
    write_axis(grid, "y", spec.grid.y, length);
  }
}

// Each geometry's /parameters and /grid (simulation_file.hpp).
void describe(hdf5::Group& root, const InfiniteMediumSpec& spec) {
  write_parameters(root, spec);
  write_grid(root, spec);
}

void describe(hdf5::Group& root, const HalfSpaceSpec& spec) {
  write_searchlight_parameters(root, spec);
  write_searchlight_grid(root, spec);
}

void describe(hdf5::Group& root, const LitObjectSpec& spec) {
  write_lit_sphere_parameters(root, spec);
  hdf5::Group grid = root.create_group("grid");
  if (spec.mesh) return;  // the exitance is per triangle of /parameters/mesh
  write_axis(grid, "psi", spec.psi, "rad");
  write_axis(grid, "azimuth", spec.azimuth, "rad");
}

void describe(hdf5::Group& root, const LayeredSlabSpec& spec) {
  write_layered_slab_parameters(root, spec);
  hdf5::Group grid = root.create_group("grid");
  write_axis(grid, "r", spec.r, spec.length_unit);
  write_axis(grid, "z", spec.z, spec.length_unit);
  write_axis(grid, "theta_o", spec.theta_o, "rad");
  // The layer axis's edges are the interfaces' depths (the last infinite when semi-infinite).
  std::vector<double> interfaces{0.0};
  for (const SlabLayerSpec& l : spec.layers) {
    interfaces.push_back(interfaces.back() + l.thickness);
  }
  grid.write_dataset("layer", interfaces).write_string_attribute("units", spec.length_unit);
}

void write_tallies(hdf5::Group& root, const std::vector<TallyResult>& tallies) {
  hdf5::Group group = root.create_group("tallies");
  for (const TallyResult& tally : tallies) {
    hdf5::Group node = group.create_group(tally.name);
    node.write_string_attribute("units", tally.units);
    node.write_string_attribute("description", tally.description);
    node.write_string_attribute("dims", join(tally.dims, ","));
    node.write_dataset("mean", tally.mean, tally.shape)
        .write_string_attribute("units", tally.units);
    node.write_dataset("stderr", tally.stderr_of_mean, tally.shape)
        .write_string_attribute("units", tally.units);
    if (tally.axes.empty()) continue;
    // A declared tally's own axes, which stand in for /grid's (tally_result.hpp).
    hdf5::Group axes = node.create_group("axes");
    for (const TallyAxis& axis : tally.axes) {
      axes.write_dataset(axis.dim, axis.edges).write_string_attribute("units", axis.units);
    }
  }
}

// /figures_of_merit/<tally>: 1 / (R^2 T) (tally/figure_of_merit.hpp) with T the whole run's
// wall time, for every tally whose figure is defined (a tally that scored nothing has none).
void write_figures_of_merit(hdf5::Group& root, const std::vector<TallyResult>& tallies,
                            double wall_seconds) {
  hdf5::Group group = root.create_group("figures_of_merit");
  group.write_string_attribute(
      "description",
      "figure of merit 1 / (R^2 T) of each tally (MCNP5 manual, LA-UR-03-1987, ch. 2 §VI.D): R "
      "its relative standard error, stderr / |mean| (for a binned tally the median over the bins "
      "with mean != 0), T the run's wall_seconds; larger reaches a given error sooner");
  for (const TallyResult& tally : tallies) {
    const double relative = relative_standard_error(tally.mean, tally.stderr_of_mean);
    const double merit = figure_of_merit(relative, wall_seconds);
    if (!std::isfinite(merit)) continue;
    hdf5::Dataset dataset = group.write_dataset(tally.name, std::span<const double>(&merit, 1), {});
    dataset.write_string_attribute("units", "1/s");
    dataset.write_string_attribute(
        "description",
        fmt::format("1 / (R^2 T) of /tallies/{}, R = {} = {:.6g}, T = {:.6g} s", tally.name,
                    tally.shape.empty() ? "stderr / |mean|" : "median over bins of stderr / |mean|",
                    relative, wall_seconds));
  }
}

void write_models(hdf5::Group& root, const std::vector<ModelResult>& models) {
  if (models.empty()) return;
  hdf5::Group group = root.create_group("models");
  for (const ModelResult& m : models) {
    hdf5::Group node =
        group.has_member(m.model) ? group.open_group(m.model) : group.create_group(m.model);
    if (m.values.empty()) {  // not evaluated for this run: say why
      node.write_string_attribute("note", m.description);
      continue;
    }
    auto write = [&](const std::string& name, const std::vector<double>& values,
                     const std::string& description) {
      hdf5::Dataset dataset = node.write_dataset(name, values, m.shape);
      dataset.write_string_attribute("units", m.units);
      dataset.write_string_attribute("description", description);
      dataset.write_string_attribute("dims", join(m.dims, ","));
    };
    write(m.name, m.values, m.description);
    // The error is not the curve: say so, rather than repeat the curve's description.
    if (!m.error.empty()) {
      write(m.name + "_error", m.error,
            "absolute numerical error estimate of " + m.name + ": " + m.description);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Reading back

std::string attribute_text(const hdf5::Object& object, const std::string& name) {
  switch (object.attribute_type(name)) {
    case hdf5::AttributeType::string:
      return object.read_string_attribute(name);
    case hdf5::AttributeType::floating:
      return fmt::format("{}", object.read_double_attribute(name));
    case hdf5::AttributeType::signed_integer:
      return fmt::format("{}", object.read_int64_attribute(name));
    case hdf5::AttributeType::unsigned_integer:
      return fmt::format("{}", object.read_uint64_attribute(name));
    case hdf5::AttributeType::other:
      break;
  }
  return "(unsupported type)";
}

std::string string_or_empty(const hdf5::Object& object, const char* name) {
  return object.has_attribute(name) ? object.read_string_attribute(name) : std::string();
}

AxisSummary summarize_axis(const hdf5::Group& grid, const std::string& name);

TallySummary summarize_tally(const hdf5::Group& tallies, const std::string& name) {
  const hdf5::Group node = tallies.open_group(name);
  const hdf5::Dataset mean_dataset = node.open_dataset("mean");
  const hdf5::Array mean = mean_dataset.read();  // checks the size it declares first
  // Held at once: the mean, the stderr and their ratios, whose median is taken (each dataset's
  // read checks only itself).
  MemoryEstimate need;
  need.add_doubles(
      fmt::format("mean, stderr and their ratios ({} values each)", mean.values.size()),
      mean.values.size(), 3);
  check_memory(need, mean_dataset.location(), "a file of smaller tallies");
  const hdf5::Array stderr_of_mean = node.read_dataset("stderr");
  if (stderr_of_mean.shape != mean.shape) {
    throw std::runtime_error("tally '" + name + "': mean and stderr differ in shape");
  }
  TallySummary summary;
  summary.name = name;
  summary.shape = mean.shape;
  summary.dims = string_or_empty(node, "dims");
  summary.units = string_or_empty(node, "units");
  summary.description = string_or_empty(node, "description");
  summary.mean_max = mean.values.empty() ? 0.0 : -std::numeric_limits<double>::infinity();
  for (const double value : mean.values) {
    summary.mean_sum += value;
    summary.mean_max = std::max(summary.mean_max, value);
    if (value != 0.0) ++summary.nonzero_bins;
  }
  summary.median_relative_stderr = relative_standard_error(mean.values, stderr_of_mean.values);
  if (node.has_member("axes")) {
    const hdf5::Group axes = node.open_group("axes");
    for (const std::string& axis : axes.member_names()) {
      summary.axes.push_back(summarize_axis(axes, axis));
    }
  }
  if (summary.is_scalar() && !stderr_of_mean.values.empty()) {
    summary.scalar_stderr = stderr_of_mean.values.front();
  }
  return summary;
}

// A grid axis's edges increase strictly and are finite; only the last may be +inf (a slab's
// semi-infinite layer). A file that says otherwise was damaged or edited, and every bin width,
// centre and density read from it would be wrong.
void check_edges(const std::string& name, const std::vector<double>& edges) {
  if (edges.size() < 2) {
    throw std::runtime_error(
        fmt::format("is damaged: /grid/{} holds {} edges, not 2 or more", name, edges.size()));
  }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const bool last = i + 1 == edges.size();
    if (!(std::isfinite(edges[i]) ||
          (last && edges[i] == std::numeric_limits<double>::infinity()))) {
      throw std::runtime_error(
          fmt::format("is damaged: /grid/{}[{}] is {}, not a finite edge", name, i, edges[i]));
    }
    if (i > 0 && !(edges[i] > edges[i - 1])) {
      throw std::runtime_error(
          fmt::format("is damaged: /grid/{}[{}] is {}, not above the edge "
                      "before it ({})",
                      name, i, edges[i], edges[i - 1]));
    }
  }
}

// Each tally's mean and stderr have one extent per name in its dims, and the extent along a grid
// axis is that axis's bins (from the datasets' shapes: nothing is read whole).
void check_tally_shapes(const hdf5::Group& root, const hdf5::Group& grid) {
  if (!root.has_member("tallies")) return;
  const hdf5::Group tallies = root.open_group("tallies");
  for (const std::string& name : tallies.member_names()) {
    const hdf5::Group node = tallies.open_group(name);
    const std::vector<std::string> dims = split_dims(string_or_empty(node, "dims"));
    for (const char* part : {"mean", "stderr"}) {
      const hdf5::Dataset dataset = node.open_dataset(part);
      const std::vector<std::size_t> shape = dataset.shape();
      if (shape.size() != dims.size()) {
        throw std::runtime_error(
            fmt::format("is damaged: /tallies/{}/{} has {} dimensions but "
                        "its dims name {}",
                        name, part, shape.size(), dims.size()));
      }
      for (std::size_t d = 0; d < dims.size(); ++d) {
        // A tally's own axis (/tallies/<name>/axes/<dim>) stands in for /grid's.
        const std::string own = "axes/" + dims[d];
        const bool owned = node.has_member("axes") && node.open_group("axes").has_member(dims[d]);
        if (!owned && !grid.has_member(dims[d])) continue;
        const std::vector<std::size_t> axis =
            (owned ? node.open_dataset(own) : grid.open_dataset(dims[d])).shape();
        const std::size_t edges = axis.size() == 1 ? axis[0] : 0;
        if (shape[d] + 1 != edges) {
          throw std::runtime_error(fmt::format(
              "is damaged: /tallies/{}/{} has {} bins along {} but {} has {} edges", name, part,
              shape[d], dims[d],
              owned ? fmt::format("/tallies/{}/{}", name, own) : "/grid/" + dims[d], edges));
        }
      }
    }
  }
}

AxisSummary summarize_axis(const hdf5::Group& grid, const std::string& name) {
  const hdf5::Dataset edges = grid.open_dataset(name);
  const hdf5::Array values = edges.read();
  check_edges(name, values.values);
  AxisSummary axis;
  axis.name = name;
  axis.bins = values.values.empty() ? 0 : values.values.size() - 1;
  if (!values.values.empty()) {
    axis.min = values.values.front();
    axis.max = values.values.back();
  }
  axis.units = string_or_empty(edges, "units");
  return axis;
}

// Everything but the tallies' values when `read_tallies` is false: the attributes, parameters,
// grid and the names of the models and fits.
FileSummary summarize(const hdf5::File& file, bool read_tallies) {
  const hdf5::Group& root = file.root();
  FileSummary summary;
  summary.path = file.path();
  summary.format_version = root.read_int64_attribute("format_version");
  summary.scatterlab_version = root.read_string_attribute("scatterlab_version");
  summary.command = root.read_string_attribute("command");
  summary.created = root.read_string_attribute("created");
  summary.wall_seconds = root.read_double_attribute("wall_seconds");
  summary.session_wall_seconds = root.has_attribute("session_wall_seconds")
                                     ? root.read_double_attribute("session_wall_seconds")
                                     : summary.wall_seconds;
  summary.photons_run =
      root.has_attribute("photons_run") ? root.read_int64_attribute("photons_run") : 0;
  summary.scattering_events = root.read_int64_attribute("scattering_events");
  // Files from before checkpoints and merging lack these; they were complete, single-process runs.
  summary.batches_done =
      root.has_attribute("batches_done") ? root.read_int64_attribute("batches_done") : 0;
  summary.partial = root.has_attribute("partial") && root.read_int64_attribute("partial") != 0;
  summary.ranks = root.has_attribute("ranks") ? root.read_int64_attribute("ranks") : 1;
  summary.spec_fingerprint = string_or_empty(root, "spec_fingerprint");
  summary.merged_from = string_or_empty(root, "merged_from");

  const hdf5::Group parameters = root.open_group("parameters");
  for (const std::string& name : parameters.attribute_names()) {
    summary.parameters.emplace_back(name, attribute_text(parameters, name));
  }
  if (summary.format_version != kSimulationFormatVersion) {
    throw std::runtime_error(fmt::format("has format_version {}; this scatterlab reads {}",
                                         summary.format_version, kSimulationFormatVersion));
  }
  const hdf5::Group grid = root.open_group("grid");
  summary.phi_folded = grid.has_attribute("phi_folded") && grid.read_int64_attribute("phi_folded");
  for (const std::string& name : grid.member_names()) {
    summary.grid.push_back(summarize_axis(grid, name));
  }
  check_tally_shapes(root, grid);
  if (read_tallies) {
    const hdf5::Group tallies = root.open_group("tallies");
    for (const std::string& name : tallies.member_names()) {
      summary.tallies.push_back(summarize_tally(tallies, name));
    }
  }
  if (root.has_member("models")) {
    const hdf5::Group models = root.open_group("models");
    for (const std::string& name : models.member_names()) {
      const hdf5::Group model = models.open_group(name);
      // A model left out of the run has no curves, only its "note" saying why.
      std::vector<std::string> curves = curve_names(model);
      if (curves.empty() && model.has_attribute("note")) {
        curves.push_back(model.read_string_attribute("note"));
      }
      summary.models.emplace_back(name, curves);
    }
  }
  if (root.has_member("fits")) summary.fits = root.open_group("fits").member_names();
  return summary;
}

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::vector<std::string> extents;
  for (const std::size_t extent : shape) extents.push_back(std::to_string(extent));
  return fmt::format("[{}]", join(extents, " x "));
}

std::string tally_text(const TallySummary& tally) {
  std::string text = "  " + tally.name + "  ";
  text += tally.is_scalar() ? "scalar" : shape_text(tally.shape) + " (" + tally.dims + ")";
  if (!tally.units.empty()) text += ", " + tally.units;
  text += "\n";
  if (!tally.description.empty()) text += "      " + tally.description + "\n";
  for (const AxisSummary& axis : tally.axes) {
    text += fmt::format("      {} {} bins in [{:.6g}, {:.6g}] {}\n", axis.name, axis.bins, axis.min,
                        axis.max, axis.units);
  }
  if (tally.is_scalar()) {
    text += "      " + estimate_text({tally.mean_sum, tally.scalar_stderr}) + "\n";
  } else if (tally.nonzero_bins == 0) {
    text += "      all bins zero\n";
  } else {
    text += fmt::format(
        "      sum {:.6g}, max {:.6g}; median relative stderr {:.3g} over {} nonzero bins\n",
        tally.mean_sum, tally.mean_max, tally.median_relative_stderr, tally.nonzero_bins);
  }
  return text;
}

[[noreturn]] void not_a_simulation_file(const std::filesystem::path& path,
                                        const std::string& reason,
                                        const std::string& field = "FILE") {
  throw InputError(field, path.string() + " is not a scatterlab HDF5 file (" + reason + ")",
                   "a file written by scatterlab simulate or searchlight");
}

// A scatterlab file that this build cannot read as it stands: damaged, edited or of another
// format version.
[[noreturn]] void unreadable_simulation_file(const std::filesystem::path& path,
                                             const std::string& reason, const std::string& field) {
  throw InputError(field, path.string() + " " + reason,
                   "a file written by scatterlab (format_version " +
                       std::to_string(kSimulationFormatVersion) + "), as written");
}

}  // namespace

void check_finite_tally(const std::string& name, const std::vector<double>& mean,
                        const std::vector<double>& stderr_of_mean) {
  for (const auto& [values, what] :
       {std::pair{&mean, "mean"}, std::pair{&stderr_of_mean, "stderr"}}) {
    for (std::size_t i = 0; i < values->size(); ++i) {
      if (!std::isfinite((*values)[i])) {
        throw std::runtime_error(fmt::format(
            "tally '{}': {} of cell {} is {}; no file written (a grid or medium the validation "
            "let through: please report it with the command line)",
            name, what, i, (*values)[i]));
      }
    }
  }
}

Provenance run_provenance(const TransportOutput& out, std::string command) {
  Provenance provenance;
  provenance.version = SCATTERLAB_VERSION;
  provenance.command = std::move(command);
  provenance.created = iso8601_now();
  provenance.wall_seconds = out.run_wall_seconds();
  provenance.photons_run = out.photons;
  provenance.scattering_events = out.scattering_events;
  provenance.batches_done = out.batches_done;
  provenance.ranks = out.ranks;
  provenance.session_wall_seconds = out.wall_seconds;
  provenance.session_photons_run = out.session_photons();
  return provenance;
}

std::string iso8601_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// Every run's file, one way: written whole to a temporary beside `path` and renamed into place
// (atomic_output.hpp), with the provenance, then the geometry's parameters and grid (`describe`),
// then the tallies, their figures of merit and any model curves.
void write_simulation_file(const std::filesystem::path& path, const SceneSpec& spec,
                           const std::vector<TallyResult>& tallies, const Provenance& provenance,
                           const std::vector<ModelResult>& models) {
  AtomicOutput output(path);
  check_tallies(tallies);
  {
    hdf5::File file = hdf5::File::create(output.temporary_path());
    write_provenance(file.root(), provenance, run_settings(spec).batches, fingerprint(spec));
    std::visit([&file](const auto& s) { describe(file.root(), s); }, spec);
    write_tallies(file.root(), tallies);
    write_figures_of_merit(file.root(), tallies, provenance.wall_seconds);
    write_models(file.root(), models);
    write_dimension_scales(file.root());
    file.close();
  }
  output.commit();
}

namespace {

FileSummary read_summary(const std::filesystem::path& path, bool read_tallies,
                         const std::string& field) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    not_a_simulation_file(
        path, std::filesystem::exists(path, error) ? "not a regular file" : "no such file", field);
  }
  if (!hdf5::is_hdf5_file(path)) {
    not_a_simulation_file(path, "not an HDF5 file, or unreadable", field);
  }
  try {
    const hdf5::File file = hdf5::File::open_read_only(path);
    const hdf5::Group& root = file.root();
    if (!root.has_attribute("format")) not_a_simulation_file(path, "no 'format' attribute", field);
    const std::string format = root.read_string_attribute("format");
    if (format != "scatterlab") not_a_simulation_file(path, "format is '" + format + "'", field);
    try {
      return summarize(file, read_tallies);
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& failure) {
      unreadable_simulation_file(path, failure.what(), field);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& failure) {
    not_a_simulation_file(path, failure.what(), field);
  }
}

}  // namespace

FileSummary read_file_summary(const std::filesystem::path& path, const std::string& field) {
  return read_summary(path, true, field);
}

FileSummary read_file_header(const std::filesystem::path& path, const std::string& field) {
  return read_summary(path, false, field);
}

std::string describe(const FileSummary& summary) {
  std::string text;
  text += fmt::format("file        {}\n", summary.path.string());
  text += fmt::format("format      scatterlab, version {}\n", summary.format_version);
  text += fmt::format("written by  scatterlab {}\n", summary.scatterlab_version);
  text += fmt::format("command     {}\n", summary.command);
  text += fmt::format("created     {}\n", summary.created);
  text += fmt::format("wall time   {:.3g} s", summary.wall_seconds);
  if (summary.session_wall_seconds < summary.wall_seconds) {
    text += fmt::format(" over the whole run, {:.3g} s in its last session (--resume)",
                        summary.session_wall_seconds);
  }
  text += "\n";
  text += fmt::format("photons run {} ({} scattering events)\n", summary.photons_run,
                      summary.scattering_events);
  if (summary.partial) {
    text += fmt::format(
        "status      PARTIAL: stopped after {} batches; tallies are the mean of "
        "those batches\n",
        summary.batches_done);
  }
  if (summary.ranks > 1) text += fmt::format("ranks       {} (MPI processes)\n", summary.ranks);
  if (!summary.merged_from.empty()) {
    std::string inputs = summary.merged_from;
    for (std::size_t at = inputs.find('\n'); at != std::string::npos; at = inputs.find('\n', at)) {
      inputs.replace(at, 1, "\n            ");
      at += 13;
    }
    text += fmt::format("merged from {}\n", inputs);
  }

  text += "\nparameters\n";
  std::size_t width = 0;
  for (const auto& parameter : summary.parameters) width = std::max(width, parameter.first.size());
  for (const auto& [name, value] : summary.parameters) {
    text += fmt::format("  {:<{}}  {}\n", name, width, value);
  }

  text += summary.phi_folded ? "\ngrid (phi folded onto [0, pi])\n" : "\ngrid\n";
  for (const AxisSummary& axis : summary.grid) {
    text += fmt::format("  {:<7} {:>4} bins in [{:.6g}, {:.6g}] {}\n", axis.name, axis.bins,
                        axis.min, axis.max, axis.units);
  }

  text += "\ntallies\n";
  if (summary.tallies.empty()) text += "  (none)\n";
  for (const TallySummary& tally : summary.tallies) text += tally_text(tally);
  if (!summary.models.empty()) text += "\nmodels (analytic and exact curves on the same grid)\n";
  for (const auto& [model, curves] : summary.models) {
    text += fmt::format("  {:<24} {}\n", model, join(curves, ", "));
  }
  if (!summary.fits.empty()) text += fmt::format("\nfits\n  {}\n", join(summary.fits, ", "));
  return text;
}

std::string describe_simulation_file(const std::filesystem::path& path) {
  return describe(read_file_summary(path));
}

}  // namespace scatterlab
