#pragma once
// Procedural test meshes: the shapes Walter et al. 2009 (§5, Fig. 5) and Holzschuch 2013 (Fig. 1)
// use, built here so that tests, benchmarks and renders need no data files.

#include <cstddef>

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// Latitude-longitude sphere of `rings` latitude bands and `segments` longitudes (poles closed
// with fans): 2 * segments * (rings - 1) triangles. With smooth_normals the vertex normals are the
// exact sphere normals; without, the facets are flat.
TriangleMesh make_sphere(double radius, int rings, int segments, bool smooth_normals);

// The sphere with its radius modulated by
//   r(theta, phi) = radius * (1 + amplitude * sin(frequency * theta) * cos(frequency * phi)),
// and area-weighted vertex normals. rings = 71, segments = 72 gives 10 080 triangles.
TriangleMesh make_bumpy_sphere(double radius, double amplitude, int frequency, int rings,
                               int segments);

// An axis-aligned box of the given half sizes centred at the origin, flat facets (12 triangles).
TriangleMesh make_box(const Vec3& half_size);

// A rounded tile: the superellipsoid |x/a|^(2/e) + |y/b|^(2/e) + |z/c|^(2/e) = 1 (e < 1 gives a
// box with rounded edges), with area-weighted interpolated normals, like Walter's glass tile.
TriangleMesh make_rounded_tile(double half_x, double half_y, double half_z, double exponent,
                               int rings, int segments);

// A flat square of side 2 * half_width in the plane z = 0, outward normal `up` (+1: +z,
// -1: -z), two triangles, no shading normals.
TriangleMesh make_flat_square(double half_width, int up);

}  // namespace scatterlab
