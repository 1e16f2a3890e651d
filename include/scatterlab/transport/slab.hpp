#pragma once
// A stack of plane-parallel layers between z = 0 and z = z_N (the last layer may reach to
// infinity), each with its own extinction, albedo, Henyey-Greenstein g and refractive index,
// between an ambient medium above (z < 0) and one below; light enters at z = 0 travelling +z.
// The geometry of MCML (Wang, Jacques & Zheng 1995; the MCML manual, Wang & Jacques 1992, the
// chapter "Rules for photon propagation"), on the one random walk of every geometry
// (random_walk.hpp).
//
// Free paths are drawn in optical depth, tau = -ln xi, and spent layer by layer: a flight that
// reaches an interface with tau left crosses it with the rest, tau - sigma_t d, to be spent at
// the next layer's sigma_t (the manual's "Moving the photon packet" and "Reflection or
// transmission at interface": the step left is carried across in units of mean free paths,
// since the free path is memoryless). A clear layer (sigma_t = 0, MCML's glass)
// spends none.
//
// At every interface, matched or not, the photon is reflected with probability F(cos theta_i),
// the unpolarised Fresnel reflectance for n_i -> n_t (core/fresnel.hpp; MCML's RFresnel is the
// same expression written with angles), and refracted otherwise, its
// tangential direction scaled by n_i / n_t (Snell) and its normal component cos theta_t; beyond
// the critical angle F = 1. The analog choice of half_space.hpp: no weight is split at surfaces.
// A photon refracted out through z = 0 is diffusely reflected, out through z_N transmitted.
//
// Lengths are in the spec's one length unit and sigma_t in its inverse: the slab needs no mean
// free path of its own.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/surface_exit.hpp"

namespace scatterlab {

struct SlabLayer {
  double thickness = 1.0;  // > 0; infinity for a semi-infinite last layer
  double sigma_t = 1.0;    // >= 0, 1 / length unit; 0 is a clear layer
  double albedo = 0.5;
  double g = 0.0;
  double n = 1.0;  // refractive index
};

class Slab {
 public:
  static constexpr bool has_surface = true;
  static constexpr bool layered = true;

  Slab(const std::vector<SlabLayer>& layers, double n_above, double n_below) {
    double top = 0.0;
    for (const SlabLayer& l : layers) {
      const double mean_free_path =
          l.sigma_t > 0.0 ? 1.0 / l.sigma_t : std::numeric_limits<double>::infinity();
      layers_.push_back(
          {top, top + l.thickness, l.sigma_t, mean_free_path, l.albedo, HenyeyGreenstein{l.g}, l.n});
      top += l.thickness;
    }
    n_above_ = n_above;
    n_below_ = n_below;
  }

  // The layer a photon at depth z travelling along `direction` is in: on an interface, the one
  // it is heading into.
  int layer_of(const Vec3& position, const Vec3& direction) const {
    const double z = position.z();
    for (int i = 0; i < count(); ++i) {
      const Layer& l = layers_[static_cast<std::size_t>(i)];
      if (z < l.bottom || (z == l.bottom && direction.z() < 0.0)) return i;
    }
    return count() - 1;
  }

  double albedo(int layer) const { return at(layer).albedo; }
  double g(int layer) const { return at(layer).phase.g; }
  double sample_cos_theta(int layer, double xi) const {
    return at(layer).phase.sample_cos_theta(xi);
  }

  // Spends `optical` (the free path in optical depth) from `position` along `direction` in
  // `layer`, crossing or reflecting at each interface it reaches. Returns false with `position`
  // at the collision, `direction` and `layer` where the photon then is; true when it left the
  // slab, with `exit` filled (exit.transmitted when through the bottom). `timed`: adds to
  // `path` the length travelled times each layer's index, n l, to the collision or the surface
  // (time of flight is path / c).
  template <bool timed = false>
  bool leaves(Vec3& position, Vec3& direction, int& layer, double optical, PhotonRandom& random,
              SurfaceExit& exit, double* path = nullptr) const {
    for (;;) {
      const Layer& l = at(layer);
      const double w = direction.z();
      // Where the whole flight would end in depth: inside the layer (its interfaces included)
      // it collides there, with no division (a clear layer's infinite flight never does).
      const double flight = optical * l.mean_free_path;
      const double z_end = position.z() + flight * w;
      if (z_end >= l.top && z_end <= l.bottom) {
        position += flight * direction;
        if constexpr (timed) *path += l.n * flight;
        return false;
      }
      const bool down = w > 0.0;
      const double to_interface = ((down ? l.bottom : l.top) - position.z()) / w;
      // Never below 0 by rounding: what is left is spent from the interface on.
      optical = std::max(0.0, optical - to_interface * l.sigma_t);
      position.x() += to_interface * direction.x();
      position.y() += to_interface * direction.y();
      position.z() = down ? l.bottom : l.top;  // exactly on the interface
      if constexpr (timed) *path += l.n * to_interface;
      const int beyond = layer + (down ? 1 : -1);
      const double n_beyond = beyond < 0 ? n_above_ : beyond == count() ? n_below_ : at(beyond).n;
      const double cos_incident = std::abs(w);
      double cos_transmitted = cos_incident;
      if (n_beyond != l.n) {
        const FresnelDielectric surface = fresnel_dielectric_terms(cos_incident, n_beyond / l.n);
        if (random.next4()[0] < surface.reflectance()) {
          direction.z() = -w;
          continue;
        }
        // Snell: the tangential components scale by n_i / n_t; the normal one is cos theta_t.
        const double ratio = l.n / n_beyond;
        cos_transmitted = surface.cos_transmitted;
        direction =
            Vec3(direction.x() * ratio, direction.y() * ratio, std::copysign(cos_transmitted, w));
      }
      if (beyond < 0 || beyond == count()) {
        exit.x = position.x();
        exit.y = position.y();
        exit.cos_outside = cos_transmitted;
        exit.transmitted = down;
        return true;
      }
      layer = beyond;
    }
  }

  int count() const { return static_cast<int>(layers_.size()); }

 private:
  struct Layer {
    double top, bottom;
    double sigma_t, mean_free_path, albedo;
    HenyeyGreenstein phase;
    double n;
  };

  const Layer& at(int layer) const { return layers_[static_cast<std::size_t>(layer)]; }

  std::vector<Layer> layers_;
  double n_above_ = 1.0, n_below_ = 1.0;
};

}  // namespace scatterlab
