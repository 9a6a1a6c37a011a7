#pragma once
// What cl/rasterize.cl's drawing functions read, on the device: the mesh (vertices, triangles, the
// triangles' planes) and the camera. The atlas rasterizer and the pose refinement both draw with them.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>

#include "compute/buffer.hpp"

namespace depthtrack {

struct RasterCameraArgs {  // cl/rasterize.cl's dt_camera
  float fx, fy, cx, cy, near, far;
  unsigned width, height;
};
RasterCameraArgs raster_camera_args(const Camera& camera, const TrackerConfig& config);

struct MeshBuffers {
  MeshBuffers(compute::Queue& queue, const Mesh& mesh);  // uploads the mesh and its planes
  unsigned triangle_count() const { return static_cast<unsigned>(planes.size() / 4); }

  compute::Buffer<float> vertices;      // 3 per vertex, object frame
  compute::Buffer<unsigned> triangles;  // 3 vertex indices each
  compute::Buffer<float> planes;        // render::triangle_planes
};

}  // namespace depthtrack
