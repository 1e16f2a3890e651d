#pragma once
// Scores one photon's events into the flat buffer laid out by TallyBook: the hot path of every
// tally. Raw sums are per photon: a count per collision (collision estimator, weight
// 1 / sigma_t = 1 in mfp), a path length (track-length estimator), a count per exit through the
// surface or per end of a walk; TallyBook::finish divides by the filters' measures afterwards.
// A score that no tally declares costs one predictable branch and nothing else. Frames are
// those of tally_axes.hpp.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/tally/angle_binning.hpp"
#include "scatterlab/tally/surface_exit.hpp"
#include "scatterlab/tally/tally_axes.hpp"
#include "scatterlab/tally/tally_book.hpp"

namespace scatterlab {

class Scorer {
 public:
  Scorer(const TallyAxes& axes, const TallyBook& book);

  // Per-thread scratch for the track-length estimator's crossing points; sized once.
  std::vector<double> make_crossing_scratch() const;

  // Collision estimator: a photon travelling along `direction` collides at `position` after
  // `order` scatterings. Inlined into the walk, where the branches on absent scores fold into
  // one predictable test (a call per collision costs more than the scoring).
  [[gnu::always_inline]] void collision(double* buffer, const Vec3& position, const Vec3& direction,
                                        int order) const;

  // Where the one volume score is the fluence phi(r, z), a walk may find the cells itself (the
  // lane walk, several at once): the grid of collision() above, and the add it makes there.
  struct FluenceCells {
    AxisLookup r, z;
    std::size_t z_bins;
  };
  std::optional<FluenceCells> fluence_cells() const {
    if (!fluence_only_) return std::nullopt;
    return FluenceCells{r_cells_, z_cells_, z_bins_};
  }
  // A collision in cell ir * z_bins + iz of fluence_cells(), after `order` scatterings.
  [[gnu::always_inline]] void collision_in_cell(double* buffer, std::size_t cell, int order) const {
    add(buffer, fluence_ + cell, split_ ? book_.order_block(order) : 0, 1.0);
  }

  // Track-length estimator: the flight from `start` along `direction` for `length` mfp.
  void flight(double* buffer, std::vector<double>& crossings, const Vec3& start,
              const Vec3& direction, double length, int order) const;

  // A photon of weight `weight` leaves through the surface at `where` after `order`
  // scatterings (surface_exit.hpp): through a slab's far side, the transmitted scores; else the
  // exit scores of the side it entered.
  [[gnu::always_inline]] void exit(double* buffer, const SurfaceExit& where, int order,
                                   double weight = 1.0) const {
    const std::size_t block = split_ ? book_.order_block(order) : 0;
    const SideScores& side = where.transmitted ? transmitted_ : exited_;
    if (side.total != absent) add(buffer, side.total, block, weight);
    if (exit_by_polar_angle_ != absent) {
      const std::size_t zone =
          exit_by_polar_angle_ +
          static_cast<std::size_t>(polar_binning_.bin(where.cos_polar)) * azimuth_bins_;
      // One azimuth bin (a light symmetric about z) needs no angle.
      if (azimuth_bins_ == 1) {
        add(buffer, zone, block, weight);
      } else {
        add_by_azimuth(buffer, zone, block, where.x, where.y, weight);
      }
    }
    if (exit_by_triangle_ != absent) add(buffer, exit_by_triangle_ + where.triangle, block, weight);
    if (exit_by_position_ != absent) {
      const int ix = x_cells_.index(where.x), iy = y_cells_.index(where.y);
      if (ix >= 0 && iy >= 0) {
        add(buffer,
            exit_by_position_ + static_cast<std::size_t>(ix) * y_bins_ +
                static_cast<std::size_t>(iy),
            block, weight);
      }
    }
    const double cos_outside = where.cos_outside;
    if (side.by_angle != absent) {
      add(buffer, side.by_angle + static_cast<std::size_t>(exit_binning_.bin(cos_outside)), block,
          weight);
    }
    if (side.by_radius == absent && side.by_radius_angle == absent) return;
    const double x = where.x, y = where.y;
    const int ir = r_cells_.index(std::sqrt(x * x + y * y));
    if (ir < 0) return;
    const auto ring = static_cast<std::size_t>(ir);
    if (side.by_radius != absent) add(buffer, side.by_radius + ring, block, weight);
    if (side.by_radius_angle != absent) {
      add(buffer,
          side.by_radius_angle + ring * theta_o_bins_ +
              static_cast<std::size_t>(exit_binning_.bin(cos_outside)),
          block, weight);
    }
  }

  // A photon absorbed at `position`, in a slab's `layer`, after `order` scatterings: all of its
  // weight (analog absorption, weight 1) or the part deposited at a collision (implicit capture).
  void absorption(double* buffer, const Vec3& position, int order, int layer = 0,
                  double weight = 1.0) const {
    if (absorbed_ != absent) {
      buffer[absorbed_] += weight;
      if (absorbed_by_order_) buffer[absorbed_ + book_.order_block(order)] += weight;
    }
    if (absorbed_in_grid_ != absent) {
      buffer[in_grid(position) ? absorbed_in_grid_ : absorbed_outside_grid_] += weight;
    }
    if (absorption_depth_ != absent) buffer[absorption_depth_] += weight * position.z();
    if (absorbed_by_layer_ != absent) {
      buffer[absorbed_by_layer_ + static_cast<std::size_t>(layer)] += weight;
    }
    if (absorbed_by_depth_ == absent && absorbed_by_radius_depth_ == absent) return;
    const int iz = z_cells_.index(position.z());
    if (iz < 0) return;
    const auto slice = static_cast<std::size_t>(iz);
    if (absorbed_by_depth_ != absent) buffer[absorbed_by_depth_ + slice] += weight;
    if (absorbed_by_radius_depth_ != absent) {
      const int ir =
          r_cells_.index(std::sqrt(position.x() * position.x() + position.y() * position.y()));
      if (ir >= 0) {
        buffer[absorbed_by_radius_depth_ + static_cast<std::size_t>(ir) * z_bins_ + slice] +=
            weight;
      }
    }
  }

  // A light's photon reflected off the surface before it entered.
  void reflection_at_entry(double* buffer) const {
    if (reflected_at_entry_ != absent) buffer[reflected_at_entry_] += 1.0;
  }

  void escape(double* buffer, double weight = 1.0) const {
    if (escaped_ != absent) buffer[escaped_] += weight;
  }

  // The chained tallies (TallyDeclaration::chained), which the walk scores only when a run has
  // them (random_walk.hpp): each adds `weight` at the cell its filters bin the event into, and
  // nothing when one of them puts it outside its axis. An exit is binned at its point on the
  // surface, with its angle outside and the direction it left along inside; a collision (the
  // fluence's collision estimator: 1 mfp) and an absorption at their point in the volume, with
  // the direction the photon travelled there. `path`, `order` and `layer` as TallyEvent has
  // them.
  void chained_exit(double* buffer, const SurfaceExit& where, const Vec3& direction, double path,
                    int order, double weight) const {
    TallyEvent event = event_at(Vec3(where.x, where.y, 0.0), direction, path, order, 0);
    event.cos_outside = where.cos_outside;
    event.cos_polar = where.cos_polar;
    event.triangle = where.triangle;
    add_chained(where.transmitted ? transmitted_chains_ : exit_chains_, buffer, event, weight);
  }
  void chained_collision(double* buffer, const Vec3& position, const Vec3& direction, double path,
                         int order) const {
    add_chained(collision_chains_, buffer, event_at(position, direction, path, order, 0), 1.0);
  }
  void chained_absorption(double* buffer, const Vec3& position, const Vec3& direction, double path,
                          int order, int layer, double weight) const {
    add_chained(absorption_chains_, buffer, event_at(position, direction, path, order, layer),
                weight);
  }

  bool in_grid(const Vec3& p) const {
    return r_cells_.index(std::sqrt(p.x() * p.x() + p.y() * p.y())) >= 0 &&
           z_cells_.index(p.z()) >= 0;
  }

 private:
  static constexpr std::size_t absent = TallyBook::absent;

  // Adds an exit at (x, y) to its azimuth bin about z (from +x, over [0, 2 pi)) in the zone at
  // `zone`. Light in the plane y = 0 exactly (a beam in the x-z plane that has not scattered out
  // of it: a delta on a bin edge) is shared equally between the two bins that meet there, as the
  // radiance's phi is (add_radiance); on the z axis, where every azimuth meets, among all.
  void add_by_azimuth(double* buffer, std::size_t zone, std::size_t block, double x, double y,
                      double weight) const {
    const std::size_t bins = azimuth_bins_;
    if (y == 0.0) {
      if (x == 0.0) {
        for (std::size_t a = 0; a < bins; ++a) {
          add(buffer, zone + a, block, weight / static_cast<double>(bins));
        }
        return;
      }
      if (x > 0.0) {
        add(buffer, zone, block, 0.5 * weight);
        add(buffer, zone + bins - 1, block, 0.5 * weight);
        return;
      }
      if (bins % 2 == 0) {
        add(buffer, zone + bins / 2 - 1, block, 0.5 * weight);
        add(buffer, zone + bins / 2, block, 0.5 * weight);
        return;
      }
    }
    const double angle = azimuth_of(x, y);
    const int bin = std::clamp(static_cast<int>(angle * axes_.azimuth.inverse_width()), 0,
                               axes_.azimuth.bins - 1);
    add(buffer, zone + static_cast<std::size_t>(bin), block, weight);
  }

  // Adds v at `index` of the all-orders block and, when split, of the order's block.
  [[gnu::always_inline]] void add(double* buffer, std::size_t index, std::size_t order_block,
                                  double v) const {
    buffer[index] += v;
    if (split_) buffer[index + order_block] += v;
  }

  // Adds v to the radiance cell of (cell, theta offset, phi). Unfolded, phi and 2 pi - phi fall
  // in mirrored bins; a direction exactly in the half-plane through the axis (omega . e_phi = 0,
  // as for light scattered once from a pencil beam, a delta in phi on a bin edge) is shared
  // equally between the two bins that meet there.
  [[gnu::always_inline]] void add_radiance(double* buffer, std::size_t base, std::size_t block,
                                           double cos_phi, double sin_phi_sign, double v) const {
    const int folded = phi_binning_.bin(cos_phi);
    if (axes_.fold_phi) {
      add(buffer, base + static_cast<std::size_t>(folded), block, v);
    } else if (sin_phi_sign != 0.0) {
      const int bin = sin_phi_sign > 0.0 ? folded : phi_bins_ - 1 - folded;
      add(buffer, base + static_cast<std::size_t>(bin), block, v);
    } else {
      add(buffer, base + static_cast<std::size_t>(folded), block, 0.5 * v);
      add(buffer, base + static_cast<std::size_t>(phi_bins_ - 1 - folded), block, 0.5 * v);
    }
  }

  // An event at `position` along `direction` (an exit's other fields are chained_exit's).
  static TallyEvent event_at(const Vec3& position, const Vec3& direction, double path, int order,
                             int layer) {
    TallyEvent event{position.x(), position.y(), position.z(), path, 1.0, order, layer};
    event.u_x = direction.x();
    event.u_y = direction.y();
    event.u_z = direction.z();
    return event;
  }

  // A chained tally: its offset, and each filter's binning with its stride (row-major).
  struct ChainLink {
    EventBinning binning;
    std::size_t stride;
  };
  struct Chain {
    std::size_t offset;
    std::vector<ChainLink> links;
    bool by_path = false;  // adds the weight times the event's path (Score::path_length)
  };
  static void add_chained(const std::vector<Chain>& chains, double* buffer, const TallyEvent& event,
                          double weight) {
    for (const Chain& chain : chains) {
      std::size_t cell = chain.offset;
      bool inside = true;
      for (const ChainLink& link : chain.links) {
        const int bin = link.binning.bin(event);
        if (bin < 0) {
          inside = false;
          break;
        }
        cell += static_cast<std::size_t>(bin) * link.stride;
      }
      if (inside) buffer[cell] += chain.by_path ? weight * event.path : weight;
    }
  }

  void add_chain(const TallyDeclaration& d, std::size_t offset);
  void flight_cylindrical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                          const Vec3& direction, double length, std::size_t order_block) const;
  void flight_spherical(double* buffer, std::vector<double>& crossings, const Vec3& start,
                        const Vec3& direction, double length, std::size_t order_block) const;

  TallyAxes axes_;
  // The hot axes' cell lookups (axis.hpp: no division per event).
  AxisLookup r_cells_, z_cells_, rho_cells_, x_cells_, y_cells_;
  const TallyBook& book_;
  bool split_;
  bool fluence_only_;               // of the volume scores, only the fluence
  bool absorbed_by_order_ = false;  // the absorbed total has per-order siblings in this run
  // Offsets of each score's cells (TallyBook::offset), absent when no tally declares it.
  std::size_t fluence_, flux_, radiance_, fluence_spherical_;
  // The scores of light leaving through one side: the total, by r, by theta_o, by both.
  struct SideScores {
    std::size_t total, by_radius, by_angle, by_radius_angle;
  };
  SideScores exited_, transmitted_;
  std::size_t exit_by_polar_angle_, exit_by_triangle_, exit_by_position_, reflected_at_entry_;
  std::size_t absorbed_, absorbed_in_grid_, absorbed_outside_grid_, absorption_depth_, escaped_;
  std::size_t absorbed_by_layer_, absorbed_by_depth_, absorbed_by_radius_depth_;
  // Strides of the row-major arrays [r][z][theta][phi] and [r][theta_o].
  std::size_t z_bins_, theta_bins_, theta_o_bins_;
  int phi_bins_ = 1;
  CosineBinning theta_binning_;
  CosineBinning phi_binning_;  // over [0, pi]
  CosineBinning exit_binning_;
  CosineBinning polar_binning_;         // psi on a sphere
  std::size_t y_bins_ = 1;              // exit points on a plane
  std::size_t azimuth_bins_ = 1;        // about z, on a sphere
  std::vector<double> phi_cotangents_;  // cot of the interior edges of the [0, pi] phi axis
  // The chained tallies of each event.
  std::vector<Chain> exit_chains_, transmitted_chains_, collision_chains_, absorption_chains_;
};

[[gnu::always_inline]] inline void Scorer::collision(double* buffer, const Vec3& position,
                                                     const Vec3& direction, int order) const {
  const double r2 = position.x() * position.x() + position.y() * position.y();
  if (fluence_only_) {  // the half-space's one volume tally: a cell index and an add
    const int ir = r_cells_.index(std::sqrt(r2));
    const int iz = z_cells_.index(position.z());
    if (ir < 0 || iz < 0) return;
    collision_in_cell(buffer, static_cast<std::size_t>(ir) * z_bins_ + static_cast<std::size_t>(iz),
                      order);
    return;
  }
  const std::size_t block = split_ ? book_.order_block(order) : 0;
  if (fluence_spherical_ != absent) {
    const int shell = rho_cells_.index(std::sqrt(r2 + position.z() * position.z()));
    if (shell >= 0) add(buffer, fluence_spherical_ + static_cast<std::size_t>(shell), block, 1.0);
  }
  const double r = std::sqrt(r2);
  const int ir = r_cells_.index(r);
  const int iz = z_cells_.index(position.z());
  if (ir < 0 || iz < 0) return;
  const std::size_t cell = static_cast<std::size_t>(ir) * z_bins_ + static_cast<std::size_t>(iz);
  if (fluence_ != absent) add(buffer, fluence_ + cell, block, 1.0);
  if (flux_ == absent && radiance_ == absent) return;
  // omega . e_r and omega . e_phi; on the axis e_r is undefined and phi is taken as 0.
  const double radial =
      r > 0.0 ? (direction.x() * position.x() + direction.y() * position.y()) / r : 0.0;
  if (flux_ != absent) {
    add(buffer, flux_ + 2 * cell, block, radial);
    add(buffer, flux_ + 2 * cell + 1, block, direction.z());
  }
  if (radiance_ != absent) {
    double azimuthal =
        r > 0.0 ? (direction.y() * position.x() - direction.x() * position.y()) / r : 0.0;
    const double transverse = std::sqrt(radial * radial + azimuthal * azimuthal);
    // Within rounding of the half-plane through the axis: on it (see add_radiance).
    if (std::abs(azimuthal) <= 1e-12 * transverse) azimuthal = 0.0;
    const double cos_phi = transverse > 0.0 ? radial / transverse : 1.0;
    const std::size_t base = radiance_ + cell * theta_bins_ * static_cast<std::size_t>(phi_bins_) +
                             static_cast<std::size_t>(theta_binning_.bin(direction.z())) *
                                 static_cast<std::size_t>(phi_bins_);
    add_radiance(buffer, base, block, cos_phi, azimuthal, 1.0);
  }
}

}  // namespace scatterlab
