// Objects bounded by a triangle mesh (mesh/lit_mesh.hpp, mesh/mesh_boundary.hpp): two boxes
// in line, which light leaves and re-enters, against the closed form of a stack of slabs; a
// sphere of light against the chords its rays cross; a finely tessellated sphere against the
// analytic sphere of the same engine; a block's once-scattered light against the refractive
// single-scatter solution; the energy balance photon by photon on a shape that is not convex;
// and the scenes refused (fixed seeds; k sigma tolerances).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "simulation_fixtures.hpp"

namespace scatterlab {
namespace {

using testing::find_tally;
using testing::scalar;
using testing::scalar_error;

LitObjectSpec lit_mesh(TriangleMesh mesh, double albedo, double g, double eta,
                       std::uint64_t photons) {
  LitObjectSpec spec;
  spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  spec.mesh_source = "test";
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.run.photons = photons;
  spec.run.batches = 32;
  spec.run.threads = 2;
  return spec;
}

// Two boxes of half size 1 x 1 x h/2 in line along z, the first at z in [-1.2, -1.2 + h1], the
// second from z = 0.2: one mesh of two closed parts, 24 triangles; 14 and 15 are the second box's
// top face (+z; make_box's second face).
TriangleMesh two_boxes(double h1, double h2) {
  TriangleMesh mesh;
  const auto add = [&mesh](double z_low, double height) {
    append_mesh(mesh, make_box(Vec3(1.0, 1.0, 0.5 * height)), Vec3(0, 0, z_low + 0.5 * height));
  };
  add(-1.2, h1);
  add(0.2, h2);
  return mesh;
}

// An absorbing slab of optical thickness h behind Fresnel faces, at normal incidence (reflectance
// r0 = ((eta - 1) / (eta + 1))^2 each face), summing the light's passes:
//   T = (1 - r0)^2 a / (1 - r0^2 a^2),  R = r0 + (1 - r0)^2 r0 a^2 / (1 - r0^2 a^2),  a = e^{-h}.
// Two slabs with a gap (incoherent light going back and forth between them):
//   T = T1 T2 / (1 - R1 R2),  R = R1 + T1^2 R2 / (1 - R1 R2).
struct StackTotals {
  double reflected, transmitted;
};
StackTotals slab_pair(double h1, double h2, double eta) {
  const double r0 = std::pow((eta - 1.0) / (eta + 1.0), 2);
  const auto slab = [r0](double h) {
    const double a = std::exp(-h), bounce = 1.0 - r0 * r0 * a * a;
    return StackTotals{r0 + (1.0 - r0) * (1.0 - r0) * r0 * a * a / bounce,
                       (1.0 - r0) * (1.0 - r0) * a / bounce};
  };
  const StackTotals s1 = slab(h1), s2 = slab(h2);
  const double between = 1.0 - s1.reflected * s2.reflected;
  return {s1.reflected + s1.transmitted * s1.transmitted * s2.reflected / between,
          s1.transmitted * s2.transmitted / between};
}

TEST(LitMesh, LightLeavesOneBoxAndEntersTheNext) {
  // Parallel light along +z over the boxes' common footprint, no scattering: every photon
  // crosses both. Index matched, the light left is e^{-(h1 + h2)}, all through the second box's
  // top; without the re-entry it would be e^{-h1}, all through the first box's top.
  const double h1 = 0.5, h2 = 0.8;
  {
    const TransportOutput out = run_lit_mesh(lit_mesh(two_boxes(h1, h2), 0.0, 0.0, 1.0, 200'000));
    const double expected = std::exp(-(h1 + h2));
    EXPECT_NEAR(scalar(out, "exited"), expected, 4.0 * scalar_error(out, "exited"));
    EXPECT_LT(scalar_error(out, "exited"), 2e-3);
    // Exitance per unit area of the top face (area 4), and none anywhere else.
    const TallyResult& exitance = find_tally(out, "exitance");
    double top = 0.0;
    for (std::size_t t = 0; t < 24; ++t) {
      if (t == 14 || t == 15) {
        top += exitance.mean[t] * 2.0;  // each of the two triangles has area 2
      } else {
        EXPECT_EQ(exitance.mean[t], 0.0) << "triangle " << t;
      }
    }
    EXPECT_NEAR(top, scalar(out, "exited"), 1e-12);
  }
  // Behind Fresnel faces at normal incidence the light also goes back and forth between the
  // boxes: the stack's closed form. What the first face reflects is reflected at entry (exactly
  // r0, drawn photon by photon); what comes back out through the bottom later has entered, and
  // counts as exited.
  for (const double eta : {1.5, 0.7}) {
    const TransportOutput out = run_lit_mesh(lit_mesh(two_boxes(h1, h2), 0.0, 0.0, eta, 400'000));
    const StackTotals stack = slab_pair(h1, h2, eta);
    const double r0 = std::pow((eta - 1.0) / (eta + 1.0), 2);
    const TallyResult& exitance = find_tally(out, "exitance");
    const double through_top = 2.0 * (exitance.mean[14] + exitance.mean[15]);
    const double top_error =
        2.0 * std::hypot(exitance.stderr_of_mean[14], exitance.stderr_of_mean[15]);
    const std::string label = "eta " + std::to_string(eta);
    EXPECT_NEAR(through_top, stack.transmitted, 4.0 * top_error) << label;
    EXPECT_NEAR(scalar(out, "reflected_at_entry"), r0,
                4.0 * scalar_error(out, "reflected_at_entry"))
        << label;
    EXPECT_NEAR(scalar(out, "exited"), stack.transmitted + stack.reflected - r0,
                4.0 * scalar_error(out, "exited"))
        << label;
    EXPECT_NEAR(scalar(out, "absorbed"), 1.0 - stack.transmitted - stack.reflected,
                4.0 * scalar_error(out, "absorbed"))
        << label;
  }
}

TEST(LitMesh, ASphereOfLightSeesTheChordsItsRaysCross) {
  // Index matched and without scattering, a ray from the sphere of light leaves the object
  // attenuated by the chords it crosses on its straight line, e^{-(L1 + L2)} through the two
  // boxes (or one of them). Evaluated independently here: rays drawn with another generator
  // from the same emission (uniform over the light's surface, Lambert about its normal), the
  // chords summed from the line's crossings, the rays that miss left out.
  const double h1 = 0.5, h2 = 0.8;
  LitObjectSpec spec = lit_mesh(two_boxes(h1, h2), 0.0, 0.0, 1.0, 200'000);
  spec.light = ObjectLight::sphere;
  spec.light_center = {0.6, 0.3, -3.0};
  spec.light_radius = 0.5;
  const TransportOutput out = run_lit_mesh(spec);

  const TriangleMesh& mesh = *spec.mesh;
  const MeshRayTracer tracer(mesh);
  std::mt19937_64 generator(12345);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Vec3 center(0.6, 0.3, -3.0);
  double sum = 0.0, sum2 = 0.0;
  int hits = 0;
  while (hits < 200'000) {
    const double z = 1.0 - 2.0 * uniform(generator),
                 a = 2.0 * std::numbers::pi * uniform(generator);
    const Vec3 normal(std::sqrt(1.0 - z * z) * std::cos(a), std::sqrt(1.0 - z * z) * std::sin(a),
                      z);
    const double u = uniform(generator), b = 2.0 * std::numbers::pi * uniform(generator);
    const Frame frame(normal);
    const Vec3 way = frame.to_world(std::sqrt(1.0 - u) * std::cos(b),
                                    std::sqrt(1.0 - u) * std::sin(b), std::sqrt(u));
    const Vec3 start = center + 0.5 * normal;
    // Inside from a facet that faces the ray to the next that faces away (a ray along an edge
    // may meet both of its facets at once; the pairing by orientation takes it once).
    double inside = 0.0, entered = -1.0;
    bool met = false;
    MeshHit hit;
    double t = 0.0;
    while (tracer.intersect(start, way, t, 1e30, hit)) {
      met = true;
      const bool entering = way.dot(mesh.geometric_normal(hit.triangle)) < 0.0;
      if (entering && entered < 0.0) entered = hit.distance;
      if (!entering && entered >= 0.0) {
        inside += hit.distance - entered;
        entered = -1.0;
      }
      t = hit.distance + tracer.epsilon();
    }
    if (!met) continue;
    const double left = std::exp(-inside);
    sum += left;
    sum2 += left * left;
    ++hits;
  }
  const double mean = sum / hits, error = std::sqrt((sum2 / hits - mean * mean) / hits);
  EXPECT_NEAR(scalar(out, "exited"), mean, 4.0 * std::hypot(scalar_error(out, "exited"), error));
  EXPECT_EQ(scalar(out, "reflected_at_entry"), 0.0);
}

TEST(LitMesh, FineSphereMeshIsTheAnalyticSphere) {
  // The same medium and light on the analytic sphere (sphere.hpp) and on a 36 864-triangle
  // sphere mesh of flat facets. Their difference in shape (the facets' chords, by (1 - cos(pi /
  // 96)) ~ 5e-4 of R, and normals tilted by up to pi / 96 across a facet) moves the totals by
  // ~1e-3 at most, under these runs' errors; each of the 12 zones of psi (8 rings of the mesh
  // each) must hold the same power within 4 combined sigma plus that allowance.
  const double radius = 2.0, eta = 1.3;
  LitObjectSpec analytic;
  analytic.medium.albedo = 0.9;
  analytic.medium.g = 0.5;
  analytic.eta = eta;
  analytic.radius = radius;
  analytic.psi.bins = 12;
  analytic.run.photons = 1'000'000;
  analytic.run.batches = 32;
  analytic.run.threads = 2;
  const TransportOutput sphere = run_lit_sphere(analytic);
  LitObjectSpec spec =
      lit_mesh(make_sphere(radius, 96, 192, false), 0.9, 0.5, eta, analytic.run.photons);
  spec.run.seed = 7;
  const TransportOutput mesh = run_lit_mesh(spec);

  constexpr double allowance = 1e-3;
  for (const std::string name : {"exited", "absorbed", "reflected_at_entry"}) {
    EXPECT_NEAR(scalar(mesh, name), scalar(sphere, name),
                4.0 * std::hypot(scalar_error(mesh, name), scalar_error(sphere, name)) + allowance)
        << name;
  }
  // Zone k of psi (from the lit pole at -z) holds the rings 96 - 8 (k + 1) .. 96 - 8 k of theta
  // (from +z); a triangle's zone is that of its centroid.
  const TallyResult& by_triangle = find_tally(mesh, "exitance");
  const TallyResult& by_zone = find_tally(sphere, "exitance");
  std::vector<double> power(12, 0.0), variance(12, 0.0);
  for (std::size_t t = 0; t < spec.mesh->triangle_count(); ++t) {
    const Vec3 centroid =
        (spec.mesh->vertex(t, 0) + spec.mesh->vertex(t, 1) + spec.mesh->vertex(t, 2)) / 3.0;
    const double psi = std::acos(-centroid.normalized().z());
    const auto zone = static_cast<std::size_t>(psi / (std::numbers::pi / 12));
    const double area = spec.mesh->area(t);
    power[zone] += by_triangle.mean[t] * area;
    variance[zone] += std::pow(by_triangle.stderr_of_mean[t] * area, 2);
  }
  for (int k = 0; k < 12; ++k) {
    const double area = 2.0 * std::numbers::pi * radius * radius *
                        (std::cos(analytic.psi.edge(k)) - std::cos(analytic.psi.edge(k + 1)));
    const auto z = static_cast<std::size_t>(k);
    const double expected = by_zone.mean[z] * area;
    // Triangles of one zone are correlated only through the batch means; their variances add
    // as an upper bound for a sum of counts that exclude each other photon by photon.
    const double sigma = std::hypot(std::sqrt(variance[z]), by_zone.stderr_of_mean[z] * area);
    EXPECT_NEAR(power[z], expected, 4.0 * sigma + allowance * expected) << "zone " << k;
  }
}

// A block [-L, L]^2 x [0, H] whose face z = 0 is an n x n grid of squares (two triangles each);
// its four sides fan from that face's subdivided edges to the top corners. Closed, counter-
// clockwise seen from outside; the first 2 n^2 triangles are the fine face.
TriangleMesh block_with_fine_face(double half_width, double depth, int n) {
  TriangleMesh mesh;
  const auto grid = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      mesh.positions.emplace_back(-half_width + 2.0 * half_width * i / n,
                                  -half_width + 2.0 * half_width * j / n, 0.0);
    }
  }
  for (int i = 0; i < n; ++i) {  // outward -z: (p1 - p0) x (p2 - p0) along -z
    for (int j = 0; j < n; ++j) {
      mesh.triangles.push_back({grid(i, j), grid(i, j + 1), grid(i + 1, j)});
      mesh.triangles.push_back({grid(i + 1, j), grid(i, j + 1), grid(i + 1, j + 1)});
    }
  }
  const auto top = [&mesh, half_width, depth](double sx, double sy) {
    mesh.positions.emplace_back(sx * half_width, sy * half_width, depth);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
  };
  const std::uint32_t t00 = top(-1, -1), t10 = top(1, -1), t01 = top(-1, 1), t11 = top(1, 1);
  mesh.triangles.push_back({t00, t10, t11});
  mesh.triangles.push_back({t00, t11, t01});
  // A side: its bottom edge's vertices running to the right as seen from outside (z up), the
  // top corners above its first (a) and last (c) vertex.
  const auto side = [&mesh, n](auto&& bottom, std::uint32_t a, std::uint32_t c) {
    for (int k = 0; k < n; ++k) mesh.triangles.push_back({bottom(k), bottom(k + 1), c});
    mesh.triangles.push_back({bottom(0), c, a});
  };
  side([&](int k) { return grid(k, 0); }, t00, t10);      // y = -L
  side([&](int k) { return grid(n, k); }, t10, t11);      // x = +L
  side([&](int k) { return grid(n - k, n); }, t11, t01);  // y = +L
  side([&](int k) { return grid(0, n - k); }, t01, t00);  // x = -L
  return mesh;
}

TEST(LitMesh, OnceScatteredLightOfABlockIsTheRefractiveSingleScatterSolution) {
  // A beam along the normal into the fine face of a block 10 mfp wide and deep: the light that
  // leaves it after one scattering, within 1.5 mfp of the entry, is the half-space's, which the
  // refractive single-scatter solution (refract/half_space_single_scatter.hpp; the path Walter
  // et al. 2009's solver finds for a plane) gives exactly. Each triangle's share is the solution
  // integrated over the triangle (its four quarters' centres); triangles are summed into rings
  // by their centres, from 0.25 mfp out (nearer, the solution's 1 / r peak is finer than the
  // squares of 0.1 mfp), each within 4 sigma plus 0.5 % for the quadrature over a triangle.
  const int n = 100;
  const double half_width = 5.0;
  LitObjectSpec spec =
      lit_mesh(block_with_fine_face(half_width, 10.0, n), 0.9, 0.5, 1.33, 1'000'000);
  spec.light = ObjectLight::beam;
  const Vec3 entry(0.0123, 0.0071, 0.0);  // inside a square, off its edges
  spec.beam_origin = {entry.x(), entry.y(), -3.0};
  spec.beam_direction = {0.0, 0.0, 1.0};
  const TransportOutput out = run_lit_mesh(spec);
  const TallyResult& single = find_tally(out, "exitance_single");

  // Both per unit power that meets the surface: the solution holds the entry's transmittance
  // exactly, the mesh photon by photon.
  const int rings = 5;
  std::vector<double> mc(rings, 0.0), variance(rings, 0.0), exact(rings, 0.0);
  const TriangleMesh& mesh = *spec.mesh;
  for (std::size_t t = 0; t < static_cast<std::size_t>(2 * n * n); ++t) {
    const Vec3 a = mesh.vertex(t, 0), b = mesh.vertex(t, 1), c = mesh.vertex(t, 2);
    const double r = ((a + b + c) / 3.0 - entry).norm();
    const int ring = static_cast<int>(std::floor((r - 0.25) / 0.25));
    if (ring < 0 || ring >= rings) continue;
    const auto k = static_cast<std::size_t>(ring);
    const double area = mesh.area(t);
    mc[k] += single.mean[t] * area;
    variance[k] += std::pow(single.stderr_of_mean[t] * area, 2);
    // The centres of the four quarters of the triangle (midpoint subdivision).
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    double sum = 0.0;
    const std::array<Vec3, 4> quarters{Vec3((a + ab + ca) / 3.0), Vec3((ab + b + bc) / 3.0),
                                       Vec3((ca + bc + c) / 3.0), Vec3((ab + bc + ca) / 3.0)};
    for (const Vec3& p : quarters) {
      sum +=
          half_space_single_scatter_exitance(spec.medium, spec.eta, (p - entry).norm(), 1e-8).value;
    }
    exact[k] += 0.25 * sum * area;
  }
  for (int k = 0; k < rings; ++k) {
    const auto i = static_cast<std::size_t>(k);
    EXPECT_NEAR(mc[i], exact[i], 4.0 * std::sqrt(variance[i]) + 0.005 * exact[i])
        << "ring from " << 0.25 * (k + 1) << " mfp";
  }
  // The check has teeth where most of the once-scattered light is.
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT(std::sqrt(variance[i]), 0.05 * exact[i]);
}

TEST(LitMesh, EnergyBalancesPhotonByPhotonOnAShapeThatIsNotConvex) {
  const TriangleMesh bumpy = make_bumpy_sphere(3.0, 0.25, 5, 31, 40);
  for (const ObjectLight light : {ObjectLight::directional, ObjectLight::beam}) {
    for (const double eta : {1.0, 1.4, 0.7}) {
      LitObjectSpec spec = lit_mesh(bumpy, 0.95, 0.6, eta, 20'000);
      spec.light = light;
      spec.beam_origin = {0.3, 0.2, -6.0};
      spec.beam_direction = {0.1, 0.0, 1.0};
      const TransportOutput out = run_lit_mesh(spec);
      const std::string label = to_string(light) + " eta " + std::to_string(eta);
      testing::expect_lit_object_balance(out, label);
      const TallyResult& exitance = find_tally(out, "exitance");
      double total = 0.0;
      for (std::size_t t = 0; t < bumpy.triangle_count(); ++t) {
        total += exitance.mean[t] * bumpy.area(t);
      }
      EXPECT_NEAR(total, scalar(out, "exited"), 1e-12) << label;
    }
  }
}

TEST(LitMesh, BadScenesNameTheField) {
  const auto field_of = [](const LitObjectSpec& spec) {
    try {
      run_lit_mesh(spec);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of(lit_mesh(make_flat_square(1.0, 1), 0.9, 0.0, 1.3, 100)), "mesh");
  LitObjectSpec spec = lit_mesh(make_sphere(1.0, 12, 24, false), 0.9, 0.0, 1.3, 100);
  spec.light = ObjectLight::pole_beam;
  EXPECT_EQ(field_of(spec), "source.type");
  spec.light = ObjectLight::beam;
  spec.beam_origin = {0.0, 0.1, 0.2};  // inside
  EXPECT_EQ(field_of(spec), "source.origin");
  spec.beam_origin = {0.0, 0.0, -3.0};
  spec.beam_direction = {1.0, 0.0, 0.0};  // along x from below: misses
  EXPECT_EQ(field_of(spec), "source.direction");
  spec.beam_direction = {0.0, 0.0, 1.0};
  EXPECT_EQ(field_of(spec), "(accepted)");
  spec.light = ObjectLight::sphere;
  spec.light_center = {0.0, 0.0, 0.0};  // inside
  EXPECT_EQ(field_of(spec), "source.position");
  spec.light_center = {0.0, 0.0, -1.5};
  spec.light_radius = 0.6;  // reaches the object
  EXPECT_EQ(field_of(spec), "source.radius");
  spec.light_radius = 0.4;
  EXPECT_EQ(field_of(spec), "(accepted)");
}

}  // namespace
}  // namespace scatterlab
