#pragma once
// The lit sphere's scene as the Sphere and Mesh rows set it (bench_lit_sphere.cpp,
// bench_mesh.cpp): a medium, an index, a radius in mfp and a light.
#include "scatterlab/transport/lit_object.hpp"

namespace scatterlab::bench {

inline LitObjectSpec lit_sphere(double albedo, double g, double eta, double radius,
                                ObjectLight light) {
  LitObjectSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.radius = radius;
  spec.light = light;
  return spec;
}

}  // namespace scatterlab::bench
