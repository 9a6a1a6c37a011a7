#pragma once
// Small synthetic scenes for filter tests: the built-in mesh rendered by the reference rasterizer
// in front of a wall, optionally with a band of columns hidden by a nearer occluder.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <vector>

#include "reference/rasterizer.hpp"

namespace depthtrack::test {

inline DepthImage render_scene(const Mesh& mesh, const Camera& camera, const Pose& pose, double wall = 1.5,
                               int occluder_u0 = 0, int occluder_u1 = 0, double occluder_depth = 0.5) {
  reference::Rasterizer r(mesh, camera, 0.05, 10.0);
  std::vector<float> z(static_cast<size_t>(camera.pixel_count()));
  r.render(pose, z);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      float& d = z[static_cast<size_t>(v * camera.width + u)];
      if (d == 0.0f) d = static_cast<float>(wall);
      if (u >= occluder_u0 && u < occluder_u1) d = static_cast<float>(occluder_depth);
    }
  return DepthImage::from_metres(camera.width, camera.height, z);
}

}  // namespace depthtrack::test
