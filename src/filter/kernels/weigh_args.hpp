#pragma once
// The arguments of cl/weigh.cl's weigh and cl/render_weigh.cl's render_weigh.
#include <cstdint>

#include "compute/kernel_launch.hpp"
#include "dt_atlas.h"
#include "dt_params.h"

namespace depthtrack::kernels {

// Draws each particle's tile in work-group memory and weighs it (a group per particle).
struct RenderWeighArgs {
  Buf<float> states;  // moved here where propagate is set
  Buf<float> vertices;
  Buf<unsigned> triangles;
  Buf<float> planes;
  unsigned triangle_count, vertex_count;
  dt_camera cam;
  Buf<float> observed;
  Buf<unsigned> parents;  // particle i's state rows are row parents[i] of the _from buffers
  Buf<float> occlusion_from;
  Buf<uint16_t> time_from;
  Buf<float> occlusion_to;  // written, row i
  Buf<uint16_t> time_to;    // written, row i
  Buf<float> frame_times;
  Buf<float> log_likelihood, log_weight;  // written
  dt_model model;
  float now;
  unsigned now_index;
  float dt;
  Buf<float> atlas;  // written where keep_atlas
  unsigned keep_atlas;
  dt_window window;
  unsigned propagate;  // the motion step first (seed, frame and motion are its)
  unsigned seed_lo, seed_hi, frame;
  dt_motion motion;

  auto in_order() const {
    return std::tie(states, vertices, triangles, planes, triangle_count, vertex_count, cam, observed, parents,
                    occlusion_from, time_from, occlusion_to, time_to, frame_times, log_likelihood, log_weight, model,
                    now, now_index, dt, atlas, keep_atlas, window, propagate, seed_lo, seed_hi, frame, motion);
  }
};

// Weighs the atlas' tiles first .. first + groups (a group per particle).
struct WeighArgs {
  Buf<float> atlas;
  Buf<float> observed;
  Buf<unsigned> parents;
  Buf<float> occlusion_from;
  Buf<uint16_t> time_from;
  Buf<float> occlusion_to;  // written, row i
  Buf<uint16_t> time_to;    // written, row i
  Buf<float> frame_times;
  Buf<float> log_likelihood, log_weight;  // written
  unsigned pixels;
  dt_model model;
  float now;
  unsigned now_index;
  float dt;
  dt_atlas_layout layout;
  dt_window window;
  Buf<unsigned> boxes;  // each tile's drawn box where boxed
  unsigned boxed;
  unsigned first;  // the first particle of this turn

  auto in_order() const {
    return std::tie(atlas, observed, parents, occlusion_from, time_from, occlusion_to, time_to, frame_times,
                    log_likelihood, log_weight, pixels, model, now, now_index, dt, layout, window, boxes, boxed, first);
  }
};

}  // namespace depthtrack::kernels
