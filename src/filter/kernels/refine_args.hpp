#pragma once
// The arguments of the fit's kernels: cl/refine.cl's one group, cl/refine_spread.cl's begin, draw and
// sums, and its one-launch loop.
#include <cstdint>

#include "compute/kernel_launch.hpp"
#include "dt_params.h"

namespace depthtrack::kernels {

// The frame's buffers every fit layout reads (the heaviest particle's index is in the estimate).
struct FitFrame {
  Buf<float> states, observed, occlusion;
  Buf<uint16_t> occlusion_time;
  Buf<float> frame_times;
  Buf<unsigned> parents;
};

// The mesh the fit draws.
struct FitMesh {
  Buf<float> vertices;
  Buf<unsigned> triangles;
  Buf<float> planes;
  unsigned triangle_count;
};

struct RefineOneGroupArgs {
  Buf<float> estimate;  // read and written
  FitFrame frame;
  FitMesh mesh;
  dt_camera cam;
  dt_model model;
  dt_refine_args args;
  Buf<float> pose_state;
  Buf<unsigned> tile, ids;
  Buf<float> correction;  // written
  dt_window window;
  auto in_order() const {
    return std::tie(estimate, frame.states, frame.observed, frame.occlusion, frame.occlusion_time, frame.frame_times,
                    frame.parents, mesh.vertices, mesh.triangles, mesh.planes, mesh.triangle_count, cam, model, args,
                    pose_state, tile, ids, correction, window);
  }
};

struct RefineOneLaunchArgs {
  // summarize.cl's inputs and output, read only where summarize
  Buf<float> log_weight, log_likelihood, weights;
  unsigned count;
  float centre_x, centre_y, centre_z, kl_threshold;
  unsigned summarize;
  Buf<float> fit_state;
  Buf<float> estimate;
  FitFrame frame;
  FitMesh mesh;
  dt_camera cam;
  dt_model model;
  dt_refine_args args;
  dt_window window;
  Buf<uint64_t> nearest;
  Buf<float> correction;
  auto in_order() const {
    return std::tie(log_weight, log_likelihood, weights, count, centre_x, centre_y, centre_z, kl_threshold, summarize,
                    fit_state, estimate, frame.states, frame.observed, frame.occlusion, frame.occlusion_time,
                    frame.frame_times, frame.parents, mesh.vertices, mesh.triangles, mesh.planes, mesh.triangle_count,
                    cam, model, args, window, nearest, correction);
  }
};

struct RefineBeginArgs {
  Buf<float> fit_state;
  Buf<float> estimate, states;
  dt_refine_args args;
  dt_window window;
  auto in_order() const { return std::tie(fit_state, estimate, states, args, window); }
};

struct RefineDrawArgs {
  Buf<float> fit_state;
  FitMesh mesh;
  dt_camera cam;
  Buf<uint64_t> nearest;
  auto in_order() const {
    return std::tie(fit_state, mesh.vertices, mesh.triangles, mesh.planes, mesh.triangle_count, cam, nearest);
  }
};

struct RefineSumsArgs {
  Buf<float> fit_state;
  Buf<float> estimate;
  FitFrame frame;
  Buf<float> planes;
  unsigned triangle_count;
  dt_camera cam;
  dt_model model;
  Buf<uint64_t> nearest, partials;
  Buf<float> correction;
  auto in_order() const {
    return std::tie(fit_state, estimate, frame.states, frame.observed, frame.occlusion, frame.occlusion_time,
                    frame.frame_times, frame.parents, planes, triangle_count, cam, model, nearest, partials,
                    correction);
  }
};

}  // namespace depthtrack::kernels
