#pragma once
// A filter says in which bin an event falls along one or two of its coordinates (OpenMC's
// filters): r about the beam axis, depth z, direction (theta, phi), shell rho, exit angle
// theta_o, the two components of a vector. A tally is a score times a list of filters; its cells
// are the product of the filters' bins, row-major in the order listed.
//
// Each filter also carries the measure of each of its bins (an area, a length, a solid angle, a
// time): the finished tally divides a cell's raw sum by the product of its filters' measures,
// taken left to right, which turns a per-bin sum into a bin-averaged density.
//
// Every filter names its coordinate. A filter of a declared tally (the chain, scorer.hpp) bins
// the event itself along it; the fixed paths find their cells by the Scorer's own strides.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "scatterlab/tally/axis.hpp"

namespace scatterlab {

// Where, when and how an event happens, as a filter bins it: the point (for an exit, on the
// surface, about the entry point), the direction of travel (at an exit, inside, before
// refraction, which keeps its azimuth about a plane's normal), the path the photon has travelled
// since it entered the medium (in the walk's length unit times the index it travelled at:
// random_walk.hpp), the cosine of an exit's angle outside, the photon's scatterings so far, a
// slab's layer, and where an exit is on a sphere (cos psi) or a mesh (its triangle).
struct TallyEvent {
  double x = 0.0, y = 0.0, z = 0.0;
  double path = 0.0;
  double cos_outside = 1.0;
  int order = 0;
  int layer = 0;
  double u_x = 0.0, u_y = 0.0, u_z = 1.0;
  double cos_polar = 1.0;
  std::uint32_t triangle = 0;
};

// The coordinate a filter bins along. The event's own, which EventBinning bins: its position x or
// y (of an exit, on the surface), distance r from the beam axis, depth z, distance rho from the
// source, the exit angle theta_o, time of flight t = path x seconds_per_path, the scattering order
// (its last bin holding that order and more), a slab's layer, the direction's polar angle theta
// from +z and azimuth phi about z from +x, an exit point's angle psi from a sphere's lit pole
// (0, 0, -R) and azimuth about z from +x, and a mesh's triangle. And those only the Scorer's
// fixed paths bin (scorer.hpp), which with a tally's score say which path scores it: the
// direction (theta, phi from e_r), a vector's component, a patch (psi, azimuth) of a sphere's
// surface, and whether an event lies inside or outside the (r, z) grid (one bin, no dimension).
enum class Coordinate {
  none,
  x,
  y,
  r,
  z,
  rho,
  exit_angle,
  t,
  order,
  layer,
  theta,
  phi,
  psi,
  azimuth,
  triangle,
  // The fixed paths' own:
  direction,
  component,
  surface_patch,
  inside_grid,
  outside_grid
};

// An azimuth about z from +x, in [0, 2 pi]; 0 on the axis, where every azimuth meets.
inline double azimuth_of(double x, double y) {
  const double angle = std::atan2(y, x);
  return angle < 0.0 ? angle + 2.0 * std::numbers::pi : angle;
}

// Whether EventBinning bins along `coordinate`: a coordinate of the event itself.
constexpr bool bins_events(Coordinate coordinate) {
  return coordinate != Coordinate::none && coordinate < Coordinate::direction;
}

// How a filter bins an event along its coordinate: the axis, in the walk's units.
struct EventBinning {
  Coordinate coordinate = Coordinate::none;
  AxisLookup cells;
  double seconds_per_path = 0.0;  // t only

  // The bin of `event`, or -1 outside the axis.
  int bin(const TallyEvent& event) const {
    switch (coordinate) {
      case Coordinate::x:
        return cells.index(event.x);
      case Coordinate::y:
        return cells.index(event.y);
      case Coordinate::r:
        return cells.index(std::sqrt(event.x * event.x + event.y * event.y));
      case Coordinate::z:
        return cells.index(event.z);
      case Coordinate::rho:
        return cells.index(std::sqrt(event.x * event.x + event.y * event.y + event.z * event.z));
      case Coordinate::exit_angle:
        return cells.index(std::acos(event.cos_outside));
      case Coordinate::order:
        return cells.index(std::min(static_cast<double>(event.order), cells.end - 1.0));
      case Coordinate::layer:
        return cells.index(event.layer);
      case Coordinate::t:
        return cells.index(event.path * seconds_per_path);
      case Coordinate::theta:
        return polar_bin(std::acos(std::clamp(event.u_z, -1.0, 1.0)));
      case Coordinate::phi:
        return cells.index(azimuth_of(event.u_x, event.u_y));
      case Coordinate::psi:
        return polar_bin(std::acos(std::clamp(event.cos_polar, -1.0, 1.0)));
      case Coordinate::azimuth:
        return cells.index(azimuth_of(event.x, event.y));
      case Coordinate::triangle:
        return cells.index(event.triangle);
      default:  // not a coordinate of the event (the fixed paths bin it)
        break;
    }
    return -1;
  }

  // An angle in [0, pi] on an axis that ends at pi keeps pi in its last bin: the antipode of a
  // sphere's lit pole, where unscattered light leaves, and a direction straight along -z.
  int polar_bin(double angle) const {
    const int bin = cells.index(angle);
    if (bin >= 0 || angle < std::numbers::pi) return bin;
    return (angle - cells.min) * cells.inverse_width <= cells.end + 1e-9
               ? static_cast<int>(cells.end) - 1
               : -1;
  }
};

struct Filter {
  std::vector<std::string> dims;   // the file's dimension names, e.g. {"theta", "phi"}
  std::vector<std::size_t> shape;  // extent per dimension
  std::vector<double> measures;    // one per bin of this filter, row-major over its dims
  EventBinning binning = {};       // its coordinate, and how it bins an event along it

  std::size_t bins() const { return measures.size(); }
  Coordinate coordinate() const { return binning.coordinate; }
};

// r about the beam axis, by the area of each ring: pi (r1^2 - r0^2), in mfp^2.
Filter radius_filter(const UniformAxis& r);
// A Cartesian coordinate x, y or z of the event (x and y of an exit on the surface), binned by the
// filter itself, by its bin width, in mfp.
Filter position_filter(Coordinate coordinate, const UniformAxis& axis);
// Depth z: position_filter(Coordinate::z, z).
Filter depth_filter(const UniformAxis& z);
// Time of flight t in seconds, by its bin width in s: the path (TallyEvent) times
// `seconds_per_path`, the seconds light takes per unit of path (the index is in the path).
Filter time_filter(const UniformAxis& t, double seconds_per_path);
// The scattering order 0, 1, ..., bins - 1, the last bin holding that order and more: measure 1.
Filter order_filter(int bins);
// Direction (theta from +z, phi from e_r), by each bin's solid angle in sr: a folded phi bin
// stands for phi and -phi together, so it counts twice.
Filter direction_filter(const UniformAxis& theta, const UniformAxis& phi, bool fold_phi);
// rho from the source (the origin), by the volume of each spherical shell, in mfp^3.
Filter shell_filter(const UniformAxis& rho);
// Exit angle theta_o from the outward normal, by projected solid angle over all azimuths:
// integral of cos theta dw = pi (sin^2 theta1 - sin^2 theta0), in sr.
Filter exit_angle_filter(const UniformAxis& theta_o);
// Exit angle theta_o by solid angle: 2 pi (cos theta0 - cos theta1), in sr: MCML's R_d(alpha) and
// T_t(alpha) are per steradian, not per projected steradian (the MCML manual, Wang & Jacques
// 1992, "Scored physical quantities").
// Beside an azimuth filter (phi), by (cos theta0 - cos theta1) alone: the pair's product is then
// each cell's solid angle.
Filter exit_solid_angle_filter(const UniformAxis& theta_o, bool with_azimuth = false);
// The direction's polar angle theta from +z, by each band's solid angle 2 pi (cos theta0 -
// cos theta1), in sr; beside phi, by (cos theta0 - cos theta1) alone, as theta_o.
Filter polar_angle_filter(const UniformAxis& theta, bool with_azimuth);
// The direction's azimuth phi about z from +x, over [0, 2 pi], by its width in rad.
Filter azimuth_angle_filter(const UniformAxis& phi);
// An exit point on a sphere of radius R: its angle psi from the lit pole, by each band's area
// 2 pi R^2 (cos psi0 - cos psi1); beside the azimuth filter, by R^2 (cos psi0 - cos psi1).
Filter sphere_polar_filter(const UniformAxis& psi, double radius, bool with_azimuth);
// An exit point on a sphere of radius R: its azimuth about z from +x, by each lune's area
// 2 R^2 (azimuth1 - azimuth0); beside psi, by the width alone.
Filter sphere_azimuth_filter(const UniformAxis& azimuth, double radius, bool with_psi);
// A slab's layers, counted from the lit side: measure 1.
Filter layer_filter(std::size_t layers);
// On a sphere of radius R, a point's polar angle psi from the lit pole and its azimuth about the
// z axis, by the area of each patch: R^2 (cos psi0 - cos psi1) (azimuth1 - azimuth0), in mfp^2.
Filter sphere_patch_filter(const UniformAxis& psi, const UniformAxis& azimuth, double radius);
// The triangles of a mesh, by each triangle's area (in mfp^2).
Filter triangle_filter(const std::vector<double>& areas);
// The components of a vector (E_r, E_z): measure 1.
Filter component_filter(std::size_t components);
// One bin, no dimension: events inside the (r, z) grid (inside = true) or outside it.
Filter grid_region_filter(bool inside);

}  // namespace scatterlab
