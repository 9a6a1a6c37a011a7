#include "atlas/raster_inputs.hpp"

#include <algorithm>

#include "atlas/triangle_planes.hpp"
#include "compute/resident_groups.hpp"
#include "core/facing_bins.hpp"
#include "core/mesh_topology.hpp"

namespace depthtrack {

MeshBuffers::MeshBuffers(compute::Queue& queue, const Mesh& mesh, bool facing_bins)
    : vertices(queue, mesh.vertices.size() * 3),
      triangles(queue, mesh.triangles.size() * 3),
      planes(queue, mesh.triangles.size() * 4),
      cull_back_faces(bounds_solid_outward(mesh)) {
  Mesh ordered;  // the triangles in facing order, where they are binned
  FacingOrder order;
  if (facing_bins && cull_back_faces && !mesh.triangles.empty()) {
    order = facing_order(mesh);
    ordered.vertices = mesh.vertices;
    ordered.triangles.reserve(mesh.triangles.size());
    for (const uint32_t t : order.order) ordered.triangles.push_back(mesh.triangles[t]);
    facing_bin_count = static_cast<unsigned>(order.bins.size());
  }
  const Mesh& drawn = facing_bin_count > 0 ? ordered : mesh;
  // Eigen's Vector3f and Vector3i are packed: the mesh uploads as it is.
  vertices.upload(std::span<const float>(drawn.vertices.front().data(), vertices.size()));
  triangles.upload(
      std::span<const unsigned>(reinterpret_cast<const unsigned*>(drawn.triangles.front().data()), triangles.size()));
  planes.upload(render::triangle_planes(drawn));
  this->facing_bins = compute::Buffer<float>(queue, std::max<size_t>(8 * order.bins.size(), 8));
  triangle_bins = compute::Buffer<uint16_t>(queue, std::max<size_t>(order.bin_of.size(), 2));
  if (facing_bin_count > 0) {
    this->facing_bins.upload(packed_bins(order.bins));
    triangle_bins.upload(order.bin_of);
  }
}

std::vector<std::string> rasterize_definitions(size_t group_size, const compute::DeviceInfo& device) {
  const size_t groups = compute::resident_groups(pose_box_scratch_bytes(group_size), group_size, device);
  return {"DT_GROUP_SIZE=" + std::to_string(group_size), "DT_RESIDENT_GROUPS=" + std::to_string(groups)};
}

}  // namespace depthtrack
