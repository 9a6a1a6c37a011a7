#pragma once
// The arguments of the pose scorer's kernels: cl/rasterize.cl's rasterize and cl/score.cl's score.
#include "dt_atlas.h"
#include "dt_params.h"
#include "filter/kernels/launch.hpp"

namespace depthtrack::kernels {

// Draws poses first .. first + groups into the atlas' tiles (a group per pose).
struct RasterizeArgs {
  Buf<float> states, vertices;
  Buf<unsigned> triangles;
  Buf<float> planes;
  unsigned triangle_count, vertex_count;
  dt_camera cam;
  dt_atlas_layout layout;
  Buf<float> atlas;     // written
  Buf<unsigned> boxes;  // written where boxed: each tile's drawn box
  unsigned boxed, first;
  auto in_order() const {
    return std::tie(states, vertices, triangles, planes, triangle_count, vertex_count, cam, layout, atlas, boxes, boxed,
                    first);
  }
};

// Each tile's log-likelihood against the observed depth, the occlusion probability fixed at p.
struct ScoreArgs {
  Buf<float> atlas, observed;
  Buf<float> scores;  // written
  unsigned pixels;
  dt_model model;
  float p;
  dt_atlas_layout layout;
  auto in_order() const { return std::tie(atlas, observed, scores, pixels, model, p, layout); }
};

}  // namespace depthtrack::kernels
