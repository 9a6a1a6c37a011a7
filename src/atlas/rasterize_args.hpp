#pragma once
// The arguments of cl/rasterize.cl's rasterize, in its parameter order.
#include "atlas/raster_inputs.hpp"
#include "compute/kernel_launch.hpp"
#include "dt_atlas.h"
#include "dt_params.h"

namespace depthtrack::kernels {

// Draws particles (or poses) first .. first + groups into the atlas' tiles (a group per particle, striding
// over the triangles): the kernel atlas source's and the pose scorer's launches.
struct RasterizeArgs {
  Buf<float> states;
  Buf<float> vertices;      // object frame, 3 per vertex
  Buf<unsigned> triangles;  // 3 vertex indices each
  Buf<float> planes;        // render::triangle_planes
  unsigned triangle_count, vertex_count;
  dt_camera cam;
  dt_atlas_layout layout;
  Buf<float> atlas;     // written: each pixel's depth as its bits
  Buf<unsigned> boxes;  // written where boxed: each tile's drawn box
  unsigned boxed;
  unsigned first;  // the first particle of this turn

  auto in_order() const {
    return std::tie(states, vertices, triangles, planes, triangle_count, vertex_count, cam, layout, atlas, boxes, boxed,
                    first);
  }
};

// The launch's arguments for one mesh on the device: its buffers and counts filled from `mesh`.
inline RasterizeArgs rasterize_args(const MeshBuffers& mesh, const dt_camera& cam, const dt_atlas_layout& layout,
                                    const Buf<float>& states, const Buf<float>& atlas, const Buf<unsigned>& boxes,
                                    unsigned boxed, unsigned first) {
  return {.states = states,
          .vertices = mesh.vertices,
          .triangles = mesh.triangles,
          .planes = mesh.planes,
          .triangle_count = mesh.triangle_count(),
          .vertex_count = mesh.vertex_count(),
          .cam = cam,
          .layout = layout,
          .atlas = atlas,
          .boxes = boxes,
          .boxed = boxed,
          .first = first};
}

}  // namespace depthtrack::kernels
