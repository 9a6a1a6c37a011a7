#include "atlas/raster_inputs.hpp"

#include "atlas/triangle_planes.hpp"
#include "compute/resident_groups.hpp"
#include "core/mesh_topology.hpp"

namespace depthtrack {

MeshBuffers::MeshBuffers(compute::Queue& queue, const Mesh& mesh)
    : vertices(queue, mesh.vertices.size() * 3),
      triangles(queue, mesh.triangles.size() * 3),
      planes(queue, mesh.triangles.size() * 4),
      cull_back_faces(bounds_solid_outward(mesh)) {
  // Eigen's Vector3f and Vector3i are packed: the mesh uploads as it is.
  vertices.upload(std::span<const float>(mesh.vertices.front().data(), vertices.size()));
  triangles.upload(
      std::span<const unsigned>(reinterpret_cast<const unsigned*>(mesh.triangles.front().data()), triangles.size()));
  planes.upload(render::triangle_planes(mesh));
}

std::vector<std::string> rasterize_definitions(size_t group_size, const compute::DeviceInfo& device) {
  const size_t groups = compute::resident_groups(pose_box_scratch_bytes(group_size), group_size, device);
  return {"DT_GROUP_SIZE=" + std::to_string(group_size), "DT_RESIDENT_GROUPS=" + std::to_string(groups)};
}

}  // namespace depthtrack
