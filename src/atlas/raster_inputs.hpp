#pragma once
// The mesh as cl/rasterize.cl's drawing functions read it, on the device: vertices, triangles, the
// triangles' planes (the camera is model::camera_params). The atlas rasterizer and the pose
// refinement both draw with them.
#include <depthtrack/mesh.hpp>

#include "compute/buffer.hpp"

namespace depthtrack {

struct MeshBuffers {
  MeshBuffers(compute::Queue& queue, const Mesh& mesh);  // uploads the mesh and its planes
  unsigned triangle_count() const { return static_cast<unsigned>(planes.size() / 4); }
  unsigned vertex_count() const { return static_cast<unsigned>(vertices.size() / 3); }

  compute::Buffer<float> vertices;      // 3 per vertex, object frame
  compute::Buffer<unsigned> triangles;  // 3 vertex indices each
  compute::Buffer<float> planes;        // render::triangle_planes
};

}  // namespace depthtrack
