#include "atlas/raster_inputs.hpp"

#include "atlas/triangle_planes.hpp"

namespace depthtrack {

RasterCameraArgs raster_camera_args(const Camera& camera, const TrackerConfig& config) {
  return {static_cast<float>(camera.fx),         static_cast<float>(camera.fy),
          static_cast<float>(camera.cx),         static_cast<float>(camera.cy),
          static_cast<float>(config.near_plane), static_cast<float>(config.observation.max_depth),
          static_cast<unsigned>(camera.width),   static_cast<unsigned>(camera.height)};
}

MeshBuffers::MeshBuffers(compute::Queue& queue, const Mesh& mesh)
    : vertices(queue, mesh.vertices.size() * 3),
      triangles(queue, mesh.triangles.size() * 3),
      planes(queue, mesh.triangles.size() * 4) {
  // Eigen's Vector3f and Vector3i are packed: the mesh uploads as it is.
  vertices.upload(std::span<const float>(mesh.vertices.front().data(), vertices.size()));
  triangles.upload(
      std::span<const unsigned>(reinterpret_cast<const unsigned*>(mesh.triangles.front().data()), triangles.size()));
  planes.upload(render::triangle_planes(mesh));
}

}  // namespace depthtrack
