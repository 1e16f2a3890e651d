#include "scatterlab/tally/scorer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace scatterlab {
namespace {

using C = Coordinate;

// A straight line seen in a plane perpendicular to an axis (the beam axis for cylinders, or
// any plane through the origin for spheres): the radial distance is
//   rho(t) = sqrt(w(t)^2 + d^2),  w(t) = w0 + speed * t,
// where d is the distance of closest approach and w the signed distance along the line from
// that closest point. Crossing a radius R therefore happens at w = +-sqrt(R^2 - d^2).
struct RadialLine {
  double w0;
  double speed;
  double d;

  double radius(double t) const {
    const double w = w0 + speed * t;
    return std::sqrt(w * w + d * d);
  }
  double time_at(double w) const { return (w - w0) / speed; }

  // Narrows [t_lo, t_hi] to where the line is inside `radius`; false when it never is.
  bool clip_inside(double radius, double& t_lo, double& t_hi) const {
    const double half_chord2 = radius * radius - d * d;
    if (half_chord2 <= 0.0) return false;
    const double half_chord = std::sqrt(half_chord2);
    t_lo = std::max(t_lo, time_at(-half_chord));
    t_hi = std::min(t_hi, time_at(half_chord));
    return t_hi > t_lo;
  }
};

// Appends the times in (t_lo, t_hi) at which `line` crosses the edges of `axis` (uniform radii
// starting at 0), for the radii between the smallest and largest reached in that span.
void append_radial_crossings(const RadialLine& line, const UniformAxis& axis, double t_lo,
                             double t_hi, std::vector<double>& out) {
  const double t_closest = std::clamp(-line.w0 / line.speed, t_lo, t_hi);
  const double nearest = line.radius(t_closest);
  const double farthest = std::max(line.radius(t_lo), line.radius(t_hi));
  const int first = static_cast<int>(nearest * axis.inverse_width()) + 1;
  const int last = std::min(static_cast<int>(farthest * axis.inverse_width()), axis.bins - 1);
  for (int k = first; k <= last; ++k) {
    const double edge = axis.edge(k);
    const double half_chord2 = edge * edge - line.d * line.d;
    if (half_chord2 <= 0.0) continue;
    const double half_chord = std::sqrt(half_chord2);
    for (double w : {-half_chord, half_chord}) {
      const double t = line.time_at(w);
      if (t > t_lo && t < t_hi) out.push_back(t);
    }
  }
}

int clamped_index(const UniformAxis& axis, double x) {
  const int i = static_cast<int>(std::floor((x - axis.min) * axis.inverse_width()));
  return std::clamp(i, 0, axis.bins - 1);
}

// Sorts the crossing times and prepends/appends the ends of the span.
void close_span(std::vector<double>& crossings, double t_lo, double t_hi) {
  std::sort(crossings.begin(), crossings.end());
  crossings.insert(crossings.begin(), t_lo);
  crossings.push_back(t_hi);
}

}  // namespace

Scorer::Scorer(const TallyAxes& axes, const TallyBook& book)
    : axes_(axes),
      r_cells_(axes.r),
      z_cells_(axes.z),
      rho_cells_(axes.rho),
      x_cells_(axes.x),
      y_cells_(axes.y),
      book_(book),
      split_(book.split_by_order()),
      fluence_(book.offset(Score::fluence, {C::r, C::z})),
      flux_(book.offset(Score::flux, {C::r, C::z, C::component})),
      radiance_(book.offset(Score::radiance, {C::r, C::z, C::direction})),
      fluence_spherical_(book.offset(Score::fluence, {C::rho})),
      exited_{book.offset(Score::exitance), book.offset(Score::exitance, {C::r}),
              book.offset(Score::exitance, {C::exit_angle}),
              book.offset(Score::exitance, {C::r, C::exit_angle})},
      transmitted_{book.offset(Score::transmittance), book.offset(Score::transmittance, {C::r}),
                   book.offset(Score::transmittance, {C::exit_angle}),
                   book.offset(Score::transmittance, {C::r, C::exit_angle})},
      exit_by_polar_angle_(book.offset(Score::exitance, {C::surface_patch})),
      exit_by_triangle_(book.offset(Score::exitance, {C::triangle})),
      exit_by_position_(book.offset(Score::exitance, {C::x, C::y})),
      reflected_at_entry_(book.offset(Score::entry_reflectance)),
      absorbed_(book.offset(Score::absorbed)),
      absorbed_in_grid_(book.offset(Score::absorbed, {C::inside_grid})),
      absorbed_outside_grid_(book.offset(Score::absorbed, {C::outside_grid})),
      absorption_depth_(book.offset(Score::absorbed_depth)),
      escaped_(book.offset(Score::escaped)),
      absorbed_by_layer_(book.offset(Score::absorbed, {C::layer})),
      absorbed_by_depth_(book.offset(Score::absorbed, {C::z})),
      absorbed_by_radius_depth_(book.offset(Score::absorbed, {C::r, C::z})),
      z_bins_(static_cast<std::size_t>(axes.z.bins)),
      theta_bins_(static_cast<std::size_t>(axes.theta.bins)),
      theta_o_bins_(static_cast<std::size_t>(axes.theta_o.bins)) {
  if ((absorbed_in_grid_ == absent) != (absorbed_outside_grid_ == absent)) {
    throw std::invalid_argument("Scorer: absorbed inside and outside the grid go together");
  }
  for (std::size_t i = 0; i < book.declarations().size(); ++i) {
    const TallyDeclaration& d = book.declarations()[i];
    if (!d.chained) {
      if (d.score == Score::absorbed && d.filters.empty())
        absorbed_by_order_ = d.by_order && split_;
      continue;
    }
    add_chain(d, book.offset_of(i));
  }
  fluence_only_ =
      fluence_ != absent && flux_ == absent && radiance_ == absent && fluence_spherical_ == absent;
  if (radiance_ != absent) {
    theta_binning_ = CosineBinning(axes.theta);
    phi_bins_ = axes.phi.bins;
    const UniformAxis half_turn{0.0, std::numbers::pi, axes.fold_phi ? phi_bins_ : phi_bins_ / 2};
    phi_binning_ = CosineBinning(half_turn);
    for (int k = 1; k < half_turn.bins; ++k) {
      phi_cotangents_.push_back(1.0 / std::tan(half_turn.edge(k)));
    }
  }
  for (const SideScores& side : {exited_, transmitted_}) {
    if (side.by_angle != absent || side.by_radius_angle != absent) {
      exit_binning_ = CosineBinning(axes.theta_o);
    }
  }
  y_bins_ = static_cast<std::size_t>(std::max(axes.y.bins, 1));
  if (exit_by_polar_angle_ != absent) {
    polar_binning_ = CosineBinning(axes.psi);
    azimuth_bins_ = static_cast<std::size_t>(std::max(axes.azimuth.bins, 1));
  }
}

std::vector<double> Scorer::make_crossing_scratch() const {
  std::vector<double> scratch;
  const std::size_t most = 2 * static_cast<std::size_t>(axes_.r.bins) +
                           static_cast<std::size_t>(axes_.z.bins) + phi_cotangents_.size() +
                           2 * static_cast<std::size_t>(axes_.rho.bins) + 8;
  scratch.reserve(most);
  return scratch;
}

void Scorer::flight(double* buffer, std::vector<double>& crossings, const Vec3& start,
                    const Vec3& direction, double length, int order) const {
  const std::size_t block = split_ ? book_.order_block(order) : 0;
  if (fluence_spherical_ != absent) {
    flight_spherical(buffer, crossings, start, direction, length, block);
  }
  if (fluence_ != absent || flux_ != absent || radiance_ != absent) {
    flight_cylindrical(buffer, crossings, start, direction, length, block);
  }
}

void Scorer::flight_spherical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                              const Vec3& direction, double length, std::size_t block) const {
  const RadialLine line{start.dot(direction), 1.0, start.cross(direction).norm()};
  double t_lo = 0.0, t_hi = length;
  if (!line.clip_inside(axes_.rho.max, t_lo, t_hi)) return;

  crossings.clear();
  append_radial_crossings(line, axes_.rho, t_lo, t_hi, crossings);
  close_span(crossings, t_lo, t_hi);
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
    const double a = crossings[i], b = crossings[i + 1];
    if (!(b > a)) continue;
    const int shell = clamped_index(axes_.rho, line.radius(0.5 * (a + b)));
    add(buffer, fluence_spherical_ + static_cast<std::size_t>(shell), block, b - a);
  }
}

void Scorer::flight_cylindrical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                                const Vec3& direction, double length, std::size_t block) const {
  double t_lo = 0.0, t_hi = length;

  // Clip to the slab z_min <= z < z_max.
  if (direction.z() != 0.0) {
    const double ta = (axes_.z.min - start.z()) / direction.z();
    const double tb = (axes_.z.max - start.z()) / direction.z();
    t_lo = std::max(t_lo, std::min(ta, tb));
    t_hi = std::min(t_hi, std::max(ta, tb));
  } else if (z_cells_.index(start.z()) < 0) {
    return;
  }

  // Clip to the cylinder r < r_max. With no transverse motion r stays where it is.
  const double transverse2 = direction.x() * direction.x() + direction.y() * direction.y();
  // Below 1e-12 transverse speed a flight (at most ~40 mfp) moves sideways by < 1e-10 mfp.
  const bool moves_across = transverse2 > 1e-24;
  RadialLine line{0.0, 0.0, std::hypot(start.x(), start.y())};
  double angular_momentum = 0.0;  // (start x direction) . z: its sign is that of omega . e_phi
  if (moves_across) {
    const double speed = std::sqrt(transverse2);
    angular_momentum = start.x() * direction.y() - start.y() * direction.x();
    // Within rounding of a line through the axis: on it (see Scorer::add_radiance).
    if (std::abs(angular_momentum) <= 1e-12 * line.d * speed) angular_momentum = 0.0;
    line = RadialLine{(start.x() * direction.x() + start.y() * direction.y()) / speed, speed,
                      std::abs(angular_momentum) / speed};
    if (!line.clip_inside(axes_.r.max, t_lo, t_hi)) return;
  } else if (r_cells_.index(line.d) < 0) {
    return;
  }
  if (!(t_hi > t_lo)) return;

  crossings.clear();
  if (direction.z() != 0.0) {
    const double za = start.z() + t_lo * direction.z(), zb = start.z() + t_hi * direction.z();
    const int first = clamped_index(axes_.z, std::min(za, zb)) + 1;
    const int last = clamped_index(axes_.z, std::max(za, zb));
    for (int k = first; k <= last; ++k) {
      const double t = (axes_.z.edge(k) - start.z()) / direction.z();
      if (t > t_lo && t < t_hi) crossings.push_back(t);
    }
  }
  const bool radiance = radiance_ != absent;
  if (moves_across) {
    append_radial_crossings(line, axes_.r, t_lo, t_hi, crossings);
    if (radiance) {
      // phi along a straight line: cos phi = w / sqrt(w^2 + d^2), so the edge at angle phi_k is
      // crossed where w = d cot(phi_k); when d = 0 the line passes through the axis, where phi
      // jumps from pi to 0.
      if (line.d > 0.0) {
        for (double cotangent : phi_cotangents_) {
          const double t = line.time_at(line.d * cotangent);
          if (t > t_lo && t < t_hi) crossings.push_back(t);
        }
      } else {
        const double t = line.time_at(0.0);
        if (t > t_lo && t < t_hi) crossings.push_back(t);
      }
    }
  }
  close_span(crossings, t_lo, t_hi);

  const std::size_t angles = theta_bins_ * static_cast<std::size_t>(phi_bins_);
  const std::size_t theta_offset =
      radiance ? static_cast<std::size_t>(theta_binning_.bin(direction.z())) *
                     static_cast<std::size_t>(phi_bins_)
               : 0;
  double r_previous = line.radius(t_lo);
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
    const double a = crossings[i], b = crossings[i + 1];
    const double r_next = line.radius(b);
    const double dr = r_next - r_previous;
    r_previous = r_next;
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b);
    const double r_mid = line.radius(mid);
    const int ir = clamped_index(axes_.r, r_mid);
    const int iz = clamped_index(axes_.z, start.z() + mid * direction.z());
    const std::size_t cell = static_cast<std::size_t>(ir) * z_bins_ + static_cast<std::size_t>(iz);
    const double span = b - a;
    if (fluence_ != absent) add(buffer, fluence_ + cell, block, span);
    if (flux_ != absent) {
      // The integral of omega . e_r along the path is the change in r: d r / dt = omega . e_r.
      add(buffer, flux_ + 2 * cell, block, dr);
      add(buffer, flux_ + 2 * cell + 1, block, span * direction.z());
    }
    if (radiance) {
      const double w_mid = line.w0 + line.speed * mid;
      const double cos_phi = (moves_across && r_mid > 0.0) ? w_mid / r_mid : 1.0;
      add_radiance(buffer, radiance_ + cell * angles + theta_offset, block, cos_phi,
                   angular_momentum, span);
    }
  }
}

void Scorer::add_chain(const TallyDeclaration& d, std::size_t offset) {
  Chain chain{offset, {}};
  std::size_t stride = 1;
  for (auto f = d.filters.rbegin(); f != d.filters.rend(); ++f) {
    if (!bins_events(f->coordinate())) {
      throw std::invalid_argument("Scorer: a filter of chained tally " + d.name +
                                  " does not bin events");
    }
    chain.links.insert(chain.links.begin(), ChainLink{f->binning, stride});
    stride *= f->bins();
  }
  switch (d.score) {
    case Score::exitance:
      exit_chains_.push_back(std::move(chain));
      break;
    case Score::transmittance:
      transmitted_chains_.push_back(std::move(chain));
      break;
    case Score::fluence:
    case Score::collisions:
      collision_chains_.push_back(std::move(chain));
      break;
    case Score::path_length:
      chain.by_path = true;
      exit_chains_.push_back(std::move(chain));
      break;
    case Score::absorbed:
      absorption_chains_.push_back(std::move(chain));
      break;
    default:
      throw std::invalid_argument("Scorer: chained tally " + d.name +
                                  " has a score the chain does not score");
  }
}

}  // namespace scatterlab
