#include "scatterlab/transport/simulate.hpp"

#include <cmath>

#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

// The infinite medium's tallies, each declared once: score, filters, units, meaning.
std::vector<TallyDeclaration> declare_tallies(const InfiniteMediumSpec& spec) {
  const Grid& grid = spec.grid;
  const TallyRequest& want = spec.tallies;
  const std::string estimator =
      want.estimator == Estimator::collision ? "collision estimator" : "track-length estimator";
  const Filter r = radius_filter(grid.r), z = depth_filter(grid.z);
  std::vector<TallyDeclaration> tallies;
  if (want.radiance) {
    tallies.push_back({"radiance",
                       Score::radiance,
                       {r, z, direction_filter(grid.theta, grid.phi, grid.fold_phi)},
                       Units{1, -2, -1},
                       "radiance L(r, z, theta, phi), bin average, " + estimator,
                       true});
  }
  if (want.fluence) {
    tallies.push_back({"fluence",
                       Score::fluence,
                       {r, z},
                       Units{1, -2},
                       "fluence phi(r, z), bin average, " + estimator,
                       true});
  }
  if (want.flux) {
    tallies.push_back(
        {"flux",
         Score::flux,
         {r, z, component_filter(2)},
         Units{1, -2},
         "vector irradiance E = integral of L omega d omega: components (E_r, E_z), " + estimator,
         true});
  }
  if (want.fluence_spherical) {
    tallies.push_back(
        {"fluence_spherical",
         Score::fluence,
         {shell_filter(grid.rho)},
         Units{1, -2},
         "fluence phi(rho) on spherical shells about the source, shell average, " + estimator,
         true});
  }
  tallies.push_back({"absorbed",
                     Score::absorbed,
                     {grid_region_filter(true)},
                     Units{},
                     "power absorbed inside the (r, z) grid"});
  tallies.push_back({"absorbed_outside_grid",
                     Score::absorbed,
                     {grid_region_filter(false)},
                     Units{},
                     "power absorbed outside the (r, z) grid"});
  if (std::isfinite(spec.run.escape_radius)) {
    tallies.push_back({"escaped",
                       Score::escaped,
                       {},
                       Units{},
                       "power carried past the escape radius (see /parameters escape_radius)"});
  }
  tallies.push_back({"absorbed_mean_depth",
                     Score::absorbed_depth,
                     {},
                     Units{0, 1},
                     "first moment in depth z (along the beam axis) of the absorbed power, "
                     "integral of z dP_absorbed per W incident; the mean absorption depth when "
                     "every photon is absorbed"});
  return tallies;
}

// The fields a memory error names: the bins of the tallies asked for, and what multiplies them.
std::string size_fields(const InfiniteMediumSpec& spec) {
  const TallyRequest& want = spec.tallies;
  std::string fields;
  auto add = [&fields](const std::string& more) { fields += (fields.empty() ? "" : ", ") + more; };
  if (want.radiance) add("grid.r.bins x grid.z.bins x grid.theta.bins x grid.phi.bins");
  if (!want.radiance && (want.fluence || want.flux)) add("grid.r.bins x grid.z.bins");
  if (want.fluence_spherical) add("grid.rho.bins");
  add("tallies");
  if (want.split_by_order) add("tallies.split_by_order");
  add("run.threads");
  return fields;
}

}  // namespace

TransportProblem transport_problem(const InfiniteMediumSpec& given) {
  // Lengths into mfp (length_units.hpp): the grid's r, z and rho and the escape radius. In "mfp"
  // the spec is used as it is.
  InfiniteMediumSpec spec = given;
  const double mfp_per_unit = mfp_per_length_unit(given.medium);
  if (given.medium.length_unit != "mfp") {
    spec.grid.r = length_axis_in_mfp(given.grid.r, mfp_per_unit);
    spec.grid.z = length_axis_in_mfp(given.grid.z, mfp_per_unit);
    spec.grid.rho = length_axis_in_mfp(given.grid.rho, mfp_per_unit);
    spec.run.escape_radius = given.run.escape_radius * mfp_per_unit;
  }
  TransportProblem problem;
  problem.albedo = spec.medium.albedo;
  problem.g = spec.medium.g;
  problem.geometry = GeometryKind::infinite;
  problem.source.kind = spec.source == SourceKind::point ? Source::Kind::point : Source::Kind::beam;
  const Grid& grid = spec.grid;
  problem.axes.r = grid.r;
  problem.axes.z = grid.z;
  problem.axes.theta = grid.theta;
  problem.axes.phi = grid.phi;
  problem.axes.fold_phi = grid.fold_phi;
  problem.axes.rho = grid.rho;
  problem.tallies = declare_tallies(spec);
  for (TallyDeclaration& d : declare_chained_tallies(
           spec.declared_tallies, homogeneous_frame("infinite", spec.medium, std::nullopt),
           problem.tallies)) {
    problem.tallies.push_back(std::move(d));
  }
  problem.split_by_order = spec.tallies.split_by_order;
  problem.estimator = spec.tallies.estimator;
  problem.run = spec.run;
  problem.length = reported_length(spec.medium);  // back from mfp
  problem.size_fields = size_fields(spec);
  return problem;
}

TransportOutput run_infinite_medium(const InfiniteMediumSpec& spec,
                                    const ProgressCallback& progress, const RunControl& control) {
  spec.validate();
  return transport(transport_problem(spec), progress, control);
}

}  // namespace scatterlab
