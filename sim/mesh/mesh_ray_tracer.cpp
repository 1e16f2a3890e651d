#include "scatterlab/mesh/mesh_ray_tracer.hpp"

#include <embree3/rtcore.h>

#include <stdexcept>

namespace scatterlab {

struct MeshRayTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }
};

namespace {

RTCRay make_ray(const Vec3& origin, const Vec3& direction, double t_near, double t_far) {
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  ray.dir_x = static_cast<float>(direction.x());
  ray.dir_y = static_cast<float>(direction.y());
  ray.dir_z = static_cast<float>(direction.z());
  ray.tnear = static_cast<float>(t_near);
  ray.tfar = static_cast<float>(t_far);
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  return ray;
}

}  // namespace

MeshRayTracer::MeshRayTracer(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (impl_->device == nullptr) throw std::runtime_error("Embree: cannot create a device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh.positions.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  if (vertices == nullptr || indices == nullptr) {
    rtcReleaseGeometry(geometry);
    throw std::runtime_error("Embree: cannot allocate the mesh buffers");
  }
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    const Vec3& p = mesh.positions[k];
    for (int c = 0; c < 3; ++c)
      vertices[3 * k + static_cast<std::size_t>(c)] = static_cast<float>(p[c]);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) indices[3 * t + c] = mesh.triangles[t][c];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  epsilon_ = 1e-5 * std::max(mesh.bounds().diagonal(), 1e-300);
}

MeshRayTracer::~MeshRayTracer() = default;

bool MeshRayTracer::intersect(const Vec3& origin, const Vec3& direction, double t_near,
                              double t_far, MeshHit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray = make_ray(origin, direction, t_near, t_far);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &query);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.triangle = query.hit.primID;
  hit.distance = query.ray.tfar;
  hit.bary_a = query.hit.u;
  hit.bary_b = query.hit.v;
  return true;
}

bool MeshRayTracer::occluded(const Vec3& origin, const Vec3& direction, double t_near,
                             double t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = make_ray(origin, direction, t_near, t_far);
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

int MeshRayTracer::count_crossings(const Vec3& origin, const Vec3& direction) const {
  int crossings = 0;
  double t = 0.0;
  MeshHit hit;
  while (intersect(origin, direction, t, 1e300, hit) && crossings < 100000) {
    ++crossings;
    t = hit.distance + epsilon_;
  }
  return crossings;
}

}  // namespace scatterlab
