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
// A filter of a declared tally (the chain, scorer.hpp) bins the event itself, along its
// coordinate; the fixed scores' cells are found by the Scorer's own strides (Coordinate::none).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "scatterlab/tally/axis.hpp"

namespace scatterlab {

// Where, when and how an event happens, as a filter bins it: the point (for an exit, on the
// surface, about the entry point), the path the photon has travelled since it entered the
// medium (in the walk's length unit times the index it travelled at: random_walk.hpp), the
// cosine of an exit's angle outside, the photon's scatterings so far and a slab's layer.
struct TallyEvent {
  double x = 0.0, y = 0.0, z = 0.0;
  double path = 0.0;
  double cos_outside = 1.0;
  int order = 0;
  int layer = 0;
};

// The coordinate a filter bins an event by: its position x or y (of an exit, on the surface),
// distance r from the beam axis, depth z, distance rho from the source, the exit angle theta_o,
// time of flight t = path x seconds_per_path, the scattering order (its last bin holding that
// order and more), or a slab's layer.
enum class Coordinate { none, x, y, r, z, rho, exit_angle, t, order, layer };

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
      case Coordinate::none:
        break;
    }
    return -1;
  }
};

struct Filter {
  std::vector<std::string> dims;   // the file's dimension names, e.g. {"theta", "phi"}
  std::vector<std::size_t> shape;  // extent per dimension
  std::vector<double> measures;    // one per bin of this filter, row-major over its dims
  EventBinning binning = {};       // where the filter bins events itself

  std::size_t bins() const { return measures.size(); }
};

// r about the beam axis, by the area of each ring: pi (r1^2 - r0^2), in mfp^2.
Filter radius_filter(const UniformAxis& r);
// A Cartesian coordinate of an exit point on a plane (x, y), by its bin width, in mfp.
Filter length_filter(const std::string& name, const UniformAxis& axis);
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
Filter exit_solid_angle_filter(const UniformAxis& theta_o);
// A slab's layers, counted from the lit side: measure 1.
Filter layer_filter(std::size_t layers);
// On a sphere of radius R, a point's polar angle psi from the lit pole and its azimuth about the
// z axis, by the area of each patch: R^2 (cos psi0 - cos psi1) (azimuth1 - azimuth0), in mfp^2.
Filter sphere_patch_filter(const UniformAxis& psi, const UniformAxis& azimuth, double radius);
// The triangles of a mesh, by each triangle's area (in mfp^2).
Filter triangle_filter(const std::vector<double>& areas);
// The components of a vector (E_r, E_z): measure 1.
Filter component_filter(std::size_t components);

}  // namespace scatterlab
