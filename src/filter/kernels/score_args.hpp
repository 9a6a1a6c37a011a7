#pragma once
// The arguments of the pose scorer's kernels: cl/rasterize.cl's rasterize (RasterizeArgs, the atlas
// layer's), cl/score.cl's score and cl/visible_box.cl's visible_box.
#include "atlas/rasterize_args.hpp"
#include "compute/kernel_launch.hpp"
#include "dt_atlas.h"
#include "dt_params.h"

namespace depthtrack::kernels {

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

// Each pose's visible box over the mesh's vertices, against the observed depth.
struct VisibleBoxArgs {
  Buf<float> states, vertices;
  unsigned vertex_count;
  Buf<float> observed;
  dt_camera camera;
  dt_model model;
  float pixel_sigmas;
  Buf<float> boxes;  // written: 4 a pose
  auto in_order() const {
    return std::tie(states, vertices, vertex_count, observed, camera, model, pixel_sigmas, boxes);
  }
};

}  // namespace depthtrack::kernels
