#pragma once
// The mesh as cl/rasterize.cl's drawing functions read it, on the device: vertices, triangles, the
// triangles' planes, and whether its back faces may be culled (the camera is model::camera_params). The
// atlas rasterizer and the pose refinement both draw with them.
#include <depthtrack/mesh.hpp>
#include <string>
#include <vector>

#include "compute/buffer.hpp"

namespace depthtrack {

struct MeshBuffers {
  MeshBuffers(compute::Queue& queue, const Mesh& mesh);  // uploads the mesh and its planes
  unsigned triangle_count() const { return static_cast<unsigned>(planes.size() / 4); }
  unsigned vertex_count() const { return static_cast<unsigned>(vertices.size() / 3); }

  compute::Buffer<float> vertices;      // 3 per vertex, object frame
  compute::Buffer<unsigned> triangles;  // 3 vertex indices each
  compute::Buffer<float> planes;        // render::triangle_planes
  bool cull_back_faces;                 // bounds_solid_outward: the kernels skip triangles facing away
};

// Work-group memory of dt_pose_box's reduction (cl/rasterize.cl: 5 floats a work-item), which rasterize
// and render_weigh declare.
constexpr size_t pose_box_scratch_bytes(size_t group_size) {
  return 5 * group_size * sizeof(float);
}

// cl/rasterize.cl's definitions for groups of group_size work-items on this device: the group size and
// DT_RESIDENT_GROUPS for its pose-box reduction, all the memory it declares. The kernel atlas source and
// the pose scorer ask for the same, so they share one program.
std::vector<std::string> rasterize_definitions(size_t group_size, const compute::DeviceInfo& device);

}  // namespace depthtrack
