// Objects bounded by a triangle mesh (mesh/lit_mesh.hpp) against exact values of their own
// polyhedron, and the tessellated sphere against the analytic one.
//
// Under the directional light along +z, photons start on a convex mesh's lit facets in proportion
// to each facet's shadow s_t = A_t max(0, -n_t . z), uniformly over it (mesh/mesh_light.hpp). So,
// per unit power meeting the object:
//   reflected at entry      sum_t s_t F(-n_t . z, eta) / sum_t s_t                (exact),
// and with the index matched (eta = 1) the light goes straight through until it first collides:
//   leaves unscattered      sum_t s_t <e^{-c}>_t / sum_t s_t,
// with c the chord (in mfp) from a point of facet t along +z to the far side, <.>_t the mean over
// the facet. The chord is piecewise linear over a facet (it changes plane where the line crosses
// an edge of the far side), so the mean is taken by a degree-5 rule on an m x m subdivision of
// the facet, and the quadrature's error by doubling m. A sphere mesh of n rings (2n segments)
// is inscribed in its sphere: its chords are shorter, by O(n^-2), and so is the bias of its
// unscattered light against the sphere's closed form 1 - (1 - (1 + 2R) e^{-2R}) / (2 R^2)
// (sphere_accuracy.cpp), whose order this section measures.

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/report/suites.hpp"
#include "simulation_checks.hpp"

namespace scatterlab::report {
namespace {

// Dunavant 1985, "High degree efficient symmetrical Gaussian quadrature rules for the
// triangle", Int. J. Numer. Methods Eng. 21, Table (degree 5, 7 points): barycentric points
// (a, a, 1 - 2a) in each of their three orders, and the centroid; the weights sum to 1.
struct TrianglePoint {
  double a, b, weight;  // point = (1 - a - b) p0 + a p1 + b p2
};
constexpr double d5_a1 = 0.470142064105115, d5_a2 = 0.101286507323456;
constexpr double d5_w1 = 0.132394152788506, d5_w2 = 0.125939180544827;
constexpr std::array<TrianglePoint, 7> degree5{{
    {1.0 / 3.0, 1.0 / 3.0, 0.225},
    {d5_a1, d5_a1, d5_w1},
    {d5_a1, 1.0 - 2.0 * d5_a1, d5_w1},
    {1.0 - 2.0 * d5_a1, d5_a1, d5_w1},
    {d5_a2, d5_a2, d5_w2},
    {d5_a2, 1.0 - 2.0 * d5_a2, d5_w2},
    {1.0 - 2.0 * d5_a2, d5_a2, d5_w2},
}};

// The mean of f over the triangle (p0, p1, p2), on its m x m subdivision into m^2 triangles of
// equal area (m (m + 1) / 2 upright, m (m - 1) / 2 upside down), each by the degree-5 rule.
template <class F>
double triangle_mean(const Vec3& p0, const Vec3& p1, const Vec3& p2, int m, const F& f) {
  const auto at = [&](double i, double j) {
    return p0 + (i / m) * (p1 - p0) + (j / m) * (p2 - p0);
  };
  const auto on = [&](const Vec3& q0, const Vec3& q1, const Vec3& q2) {
    double sum = 0.0;
    for (const TrianglePoint& w : degree5) {
      sum += w.weight * f((1.0 - w.a - w.b) * q0 + w.a * q1 + w.b * q2);
    }
    return sum;
  };
  double sum = 0.0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; i + j < m; ++j) {
      sum += on(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 2 <= m) sum += on(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return sum / (static_cast<double>(m) * m);
}

// The exact fate, per unit power meeting a convex mesh under the directional light along +z, of
// its light before any collision: reflected at entry (for `eta`) and, for eta = 1, leaving
// unscattered (its quadrature at m and 2m subdivisions per facet; the finer is the value).
struct PolyhedronLight {
  double reflected = 0.0;
  double leaves = 0.0, leaves_coarse = 0.0;

  double quadrature_error() const { return std::abs(leaves - leaves_coarse); }
};

PolyhedronLight polyhedron_light(const TriangleMesh& mesh, double eta, int m, int threads) {
  const MeshRayTracer tracer(mesh);
  const Vec3 along(0.0, 0.0, 1.0);
  const auto leaves = [&](const Vec3& p) {
    MeshHit hit;
    const bool far_side =
        tracer.intersect(p, along, tracer.epsilon(), std::numeric_limits<double>::infinity(), hit);
    return std::exp(-(far_side ? hit.distance : 0.0));
  };
  const auto count = static_cast<std::ptrdiff_t>(mesh.triangle_count());
  // Per facet, then summed in order: the same bits on any number of threads.
  std::vector<std::array<double, 4>> facet(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(dynamic, 8) num_threads(threads)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto t = static_cast<std::size_t>(i);
    const double cos_incident = -mesh.geometric_normal(t).dot(along);
    if (!(cos_incident > 0.0)) {
      facet[t] = {0.0, 0.0, 0.0, 0.0};
      continue;
    }
    const double shadow = mesh.area(t) * cos_incident;
    const Vec3 &a = mesh.vertex(t, 0), &b = mesh.vertex(t, 1), &c = mesh.vertex(t, 2);
    facet[t] = {shadow, shadow * fresnel_dielectric_terms(cos_incident, eta).reflectance(),
                shadow * triangle_mean(a, b, c, 2 * m, leaves),
                shadow * triangle_mean(a, b, c, m, leaves)};
  }
  std::array<double, 4> total{};
  for (const auto& f : facet) {
    for (std::size_t k = 0; k < 4; ++k) total[k] += f[k];
  }
  return {total[1] / total[0], total[2] / total[0], total[3] / total[0]};
}

int report_threads(const Profile& profile) {
  return profile.threads > 0 ? profile.threads : omp_get_max_threads();
}

// The sphere mesh of `rings` latitude bands and 2 rings segments, flat facets.
std::shared_ptr<const TriangleMesh> sphere_mesh(double radius, int rings) {
  return std::make_shared<const TriangleMesh>(make_sphere(radius, rings, 2 * rings, false));
}

// Subdivisions per facet for a sphere mesh of `rings`: the finer quadrature takes about the same
// 2 10^5 points whatever the mesh.
int subdivisions(int rings) {
  return std::max(2, 64 / rings);
}

LitObjectSpec mesh_spec(std::shared_ptr<const TriangleMesh> mesh, const std::string& source,
                        double albedo, double g, double eta, const RunSettings& run) {
  LitObjectSpec spec;
  spec.mesh = std::move(mesh);
  spec.mesh_source = source;
  spec.medium = Medium{albedo, 1.0, g, "mfp"};
  spec.eta = eta;
  spec.light = ObjectLight::directional;
  spec.run = run;
  return spec;
}

// The analytic sphere's unscattered light under the directional light, eta = 1.
double sphere_leaves(double radius) {
  return (1.0 - (1.0 + 2.0 * radius) * std::exp(-2.0 * radius)) / (2.0 * radius * radius);
}

}  // namespace

Section mesh_convergence(const Profile& profile) {
  Section section;
  section.id = "mesh_convergence";
  section.title = "Mesh: error against run time";
  constexpr double albedo = 0.9, g = 0.5, radius = 1.0;
  constexpr int rings = 16;
  const auto mesh = sphere_mesh(radius, rings);
  const PolyhedronLight exact =
      polyhedron_light(*mesh, 1.0, subdivisions(rings), report_threads(profile));
  section.reference = fmt::format(
      "The light that leaves a sphere mesh of {} rings and {} segments ({} flat facets, radius {} "
      "mfp, index matched, albedo {}, g {}) under the directional light without colliding: the "
      "mean of e^-chord over the lit facets, weighted by their shadows, = {:.9f} (degree-5 "
      "quadrature on each facet, error {:.1g} by doubling its subdivision).",
      rings, 2 * rings, mesh->triangle_count(), radius, albedo, g, exact.leaves,
      exact.quadrature_error());
  section.tolerance =
      "Each budget within 5 standard errors of the exact value (plus the quadrature's error); "
      "the standard error falls as N^-1/2 (slope in [-0.6, -0.4]).";
  add_error_against_run_time(
      section, profile,
      {{"exited_unscattered", "the unscattered exitance", exact.leaves, exact.quadrature_error()}},
      fmt::format("Sphere mesh, {} rings, R = {:g} mfp, directional light", rings, radius),
      [&](std::uint64_t photons, std::uint64_t seed) {
        return run_lit_mesh(
            mesh_spec(mesh, "sphere mesh", albedo, g, 1.0, report_run(photons, seed, profile)));
      });
  return section;
}

Section mesh_tessellation(const Profile& profile) {
  Section section;
  section.id = "mesh_tessellation";
  section.title = "Mesh: tessellation against the analytic sphere";
  constexpr double albedo = 0.9, g = 0.5, radius = 1.0;
  const double sphere = sphere_leaves(radius);
  section.reference = fmt::format(
      "Sphere meshes of n rings and 2n segments (radius {} mfp, index matched, albedo {}, g {}) "
      "under the directional light: their unscattered exitance from the Monte Carlo against the "
      "exact value of each polyhedron (quadrature), and the polyhedron's against the analytic "
      "sphere's closed form 1 - (1 - (1 + 2R) e^-2R) / (2 R^2) = {:.9f}.",
      radius, albedo, g, sphere);
  section.tolerance =
      "Each Monte Carlo within 5 standard errors of its own polyhedron (plus the quadrature's "
      "error), and the quadrature's error below a hundredth of the bias; the bias falls as "
      "n^-2 (least-squares slope of log |bias| against log n in [-2.2, -1.8]).";
  section.table.columns = {
      "rings",  "triangles",  "photons",          "seconds",      "exited_unscattered",
      "stderr", "polyhedron", "quadrature_error", "z_polyhedron", "sphere",
      "bias"};
  const auto photons = static_cast<std::uint64_t>(profile.quick ? 2e5 : 2e6);
  PlotSeries bias_series{"|polyhedron − sphere| / sphere (quadrature)", {}, {}, {}, true, "exact"};
  PlotSeries mc_series{"|Monte Carlo − sphere| / sphere", {}, {}, {}, true, "monte_carlo"};
  PlotSeries reference_line{"$\\propto n^{-2}$", {}, {}, {}, false, "straight"};
  std::vector<double> ring_counts, biases;
  for (const int rings : {4, 8, 16, 32, 64}) {
    const auto mesh = sphere_mesh(radius, rings);
    const PolyhedronLight exact =
        polyhedron_light(*mesh, 1.0, subdivisions(rings), report_threads(profile));
    const std::uint64_t seed = profile.seed + section.table.rows.size();
    const TransportOutput out = run_lit_mesh(
        mesh_spec(mesh, "sphere mesh", albedo, g, 1.0, report_run(photons, seed, profile)));
    section.non_finite_values += count_non_finite(out.tallies);
    const Estimate mc = estimate(out, "exited_unscattered");
    const double bias = exact.leaves - sphere;
    section.checks.push_back(
        {fmt::format("{} rings: Monte Carlo {:.6f} against its polyhedron {:.6f}, z {:.2f}", rings,
                     mc.mean, exact.leaves, z_score(mc, exact.leaves)),
         std::abs(mc.mean - exact.leaves) <= 5.0 * mc.stderr_of_mean + exact.quadrature_error()});
    section.checks.push_back(
        {fmt::format("{} rings: quadrature error {:.2g} below 1 % of the bias {:.3g}", rings,
                     exact.quadrature_error(), bias),
         exact.quadrature_error() <= 0.01 * std::abs(bias)});
    section.table.rows.push_back(
        {fmt::format("{}", rings), fmt::format("{}", mesh->triangle_count()),
         fmt::format("{}", photons), fmt::format("{:.3g}", out.wall_seconds),
         fmt::format("{:.7f}", mc.mean), fmt::format("{:.2g}", mc.stderr_of_mean),
         fmt::format("{:.9f}", exact.leaves), fmt::format("{:.1g}", exact.quadrature_error()),
         fmt::format("{:.2f}", z_score(mc, exact.leaves)), fmt::format("{:.9f}", sphere),
         fmt::format("{:.3g}", bias)});
    ring_counts.push_back(rings);
    biases.push_back(std::abs(bias));
    bias_series.x.push_back(rings);
    bias_series.y.push_back(std::abs(bias) / sphere);
    mc_series.x.push_back(rings);
    mc_series.y.push_back(std::abs(mc.mean - sphere) / sphere);
    mc_series.y_error.push_back(mc.stderr_of_mean / sphere);
  }
  const double order = log_log_slope(ring_counts, biases);
  section.checks.push_back(
      {fmt::format("order of the tessellation's bias {:.3f} in [-2.2, -1.8]", order),
       order >= -2.2 && order <= -1.8});
  for (const double rings : ring_counts) {
    reference_line.x.push_back(rings);
    reference_line.y.push_back(bias_series.y.front() * std::pow(rings / ring_counts.front(), -2.0));
  }
  section.findings = fmt::format(
      "The inscribed polyhedron lets through more unscattered light than the sphere, by a bias "
      "that falls as n^{:.3f}; at {} rings it is {:.2g} of the sphere's value. Each Monte Carlo "
      "run agrees with its own polyhedron.\n",
      order, ring_counts.back(), biases.back() / sphere);
  section.figures.push_back(
      {section.id,
       LinePlot{"Sphere mesh of n rings, R = 1 mfp, index matched:\nbias of the unscattered "
                "exitance against the analytic sphere",
                "rings n",
                "relative bias",
                AxisScale::log,
                true,
                {bias_series, mc_series, reference_line}}});
  return section;
}

Section mesh_extremes(const Profile& profile) {
  Section section;
  section.id = "mesh_extremes";
  section.title = "Mesh: stiff and extreme cases";
  section.reference =
      "Energy (reflected at entry + exited + absorbed = 1, and each by scattering order); the "
      "exact light reflected at entry (the lit facets' Fresnel reflectances weighted by their "
      "shadows, or the beam's at its incidence); with the index matched, the exact unscattered "
      "light that leaves and that the first collision absorbs ((1 - albedo) times the light "
      "that collides) of the polyhedron itself.";
  section.tolerance =
      "Energy to 1e-12; each exact part within 5 standard errors, or, where no photon was "
      "scored, an exact value below 3 / photons. No NaN or Inf.";
  section.table.columns = {"light",
                           "albedo",
                           "g",
                           "eta",
                           "photons",
                           "seconds",
                           "energy_residual",
                           "reflected",
                           "reflected_exact",
                           "reflected_z",
                           "exited_z",
                           "absorbed_unscattered_z"};
  constexpr int rings = 16;
  const auto sphere = sphere_mesh(1.0, rings);
  struct Cell {
    double albedo, g, eta;
  };
  std::vector<Cell> cells;
  for (const double albedo : {1e-6, 0.5, 1.0 - 1e-6}) {
    for (const double g : {-0.999, 0.0, 0.999}) cells.push_back({albedo, g, 1.0});
  }
  for (const double eta : {1.0001, 1.33, 2.5}) cells.push_back({0.9, 0.5, eta});
  const double scale = profile.quick ? 1.0 : 10.0;
  const auto photons = static_cast<std::uint64_t>(scale * 2e4);
  const double n = static_cast<double>(photons);
  const PolyhedronLight matched =
      polyhedron_light(*sphere, 1.0, subdivisions(rings), report_threads(profile));

  const auto add_row = [&](const std::string& light, const Cell& c, const TransportOutput& out,
                           double reflected_exact, bool beam) {
    section.non_finite_values += count_non_finite(out.tallies);
    const std::string cell =
        fmt::format("{}, albedo {}, g {}, eta {}", light, c.albedo, c.g, c.eta);
    const auto [energy, orders] =
        energy_residuals(out, estimate(out, "reflected_at_entry").mean, {"exited", "absorbed"});
    section.checks.push_back({fmt::format("{}: energy residual {:.2g}, by order {:.2g}, within "
                                          "1e-12",
                                          cell, energy, orders),
                              std::abs(energy) <= 1e-12 && std::abs(orders) <= 1e-12});
    const Estimate reflected = estimate(out, "reflected_at_entry");
    section.checks.push_back({fmt::format("{}: reflected at entry {:.6g} against exact {:.6g}",
                                          cell, reflected.mean, reflected_exact),
                              agrees(reflected, reflected_exact, n)});
    std::string exited_z = "", absorbed_z = "";
    if (c.eta == 1.0 && !beam) {
      const Estimate exited = estimate(out, "exited_unscattered");
      const Estimate absorbed = estimate(out, "absorbed_unscattered");
      const double absorbed_exact = (1.0 - c.albedo) * (1.0 - matched.leaves);
      section.checks.push_back(
          {fmt::format("{}: exited unscattered {:.6g} against its polyhedron {:.6g}", cell,
                       exited.mean, matched.leaves),
           agrees(exited, matched.leaves, n)});
      section.checks.push_back(
          {fmt::format("{}: absorbed at the first collision {:.6g} against exact {:.6g}", cell,
                       absorbed.mean, absorbed_exact),
           agrees(absorbed, absorbed_exact, n)});
      exited_z = fmt::format("{:.2f}", z_score(exited, matched.leaves));
      absorbed_z = fmt::format("{:.2f}", z_score(absorbed, absorbed_exact));
    }
    section.table.rows.push_back(
        {light, fmt::format("{}", c.albedo), fmt::format("{}", c.g), fmt::format("{}", c.eta),
         fmt::format("{}", photons), fmt::format("{:.3g}", out.wall_seconds),
         fmt::format("{:.2g}", energy), fmt::format("{:.6g}", reflected.mean),
         fmt::format("{:.6g}", reflected_exact),
         fmt::format("{:.2f}", z_score(reflected, reflected_exact)), exited_z, absorbed_z});
  };

  for (const Cell& c : cells) {
    const std::uint64_t seed = profile.seed + section.table.rows.size();
    const TransportOutput out = run_lit_mesh(
        mesh_spec(sphere, "sphere mesh", c.albedo, c.g, c.eta, report_run(photons, seed, profile)));
    const double reflected = c.eta == 1.0 ? 0.0 : polyhedron_light(*sphere, c.eta, 1, 1).reflected;
    add_row("directional, sphere mesh", c, out, reflected, false);
  }
  // A beam at 89.9 degrees from the normal of a box's lit face, entering 1 mfp from its edge.
  const auto box = std::make_shared<const TriangleMesh>(make_box(Vec3(2.0, 2.0, 1.0)));
  const double grazing = 89.9 * std::numbers::pi / 180.0;
  const Vec3 way(std::sin(grazing), 0.0, std::cos(grazing));
  const Vec3 entry(-1.0, 0.3, -1.0);
  for (const double eta : {1.0001, 1.33, 2.5}) {
    const Cell c{0.9, 0.5, eta};
    LitObjectSpec spec =
        mesh_spec(box, "box", c.albedo, c.g, eta,
                  report_run(photons, profile.seed + section.table.rows.size(), profile));
    spec.light = ObjectLight::beam;
    const Vec3 origin = entry - 3.0 * way;
    spec.beam_origin = {origin.x(), origin.y(), origin.z()};
    spec.beam_direction = {way.x(), way.y(), way.z()};
    add_row("beam at 89.9 deg, box", c, run_lit_mesh(spec),
            fresnel_dielectric_terms(std::cos(grazing), eta).reflectance(), true);
  }
  section.findings = checks_over_cells(section);
  return section;
}

}  // namespace scatterlab::report
