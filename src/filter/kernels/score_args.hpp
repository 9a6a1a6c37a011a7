#pragma once
// The arguments of the pose scorer's kernels: cl/rasterize.cl's rasterize (RasterizeArgs, the atlas
// layer's) and cl/score.cl's score.
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

}  // namespace depthtrack::kernels
