#pragma once
// An object bounded by a closed triangle mesh under the lit sphere's lights (a LitObjectSpec with
// a mesh, transport/lit_object.hpp; Vavassori §4.3; Bitterli 2013, §3.2): the checks that need
// the mesh's ray tracer, and the run on the transport engine with the mesh's geometry and light
// (mesh_boundary.hpp, mesh_light.hpp). Tallies, per unit power that meets the object: the
// exitance per triangle, the power that leaves, the power absorbed and the light reflected off
// the object without entering; they sum to 1 photon by photon.

#include "scatterlab/transport/lit_object.hpp"

namespace scatterlab {

// Throws InputError naming the field: an open or inside-out mesh ("mesh"), a beam whose origin
// is inside the mesh ("source.origin") or whose line misses it ("source.direction").
void check_lit_mesh(const LitObjectSpec& spec);

// Runs spec (spec.mesh set) on the transport engine; only the root rank gets tallies. Lengths
// in medium.length_unit, as run_lit_sphere's.
TransportOutput run_lit_mesh(const LitObjectSpec& spec, const ProgressCallback& progress = {},
                             const RunControl& control = {});

}  // namespace scatterlab
