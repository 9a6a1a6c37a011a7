#include "filter/device_refiner.hpp"

#include "compute/kernel_sources.hpp"
#include "dt_state.h"
#include "filter/model_args.hpp"

namespace depthtrack {

namespace {
// Work-items of the fit's one group. 128 (the filter's) left each work-item ~38 of the 80x60 pixels
// and ~7 triangles per rendering in sequence; 256 halves that and keeps the 29 sums' local memory
// (29.7 KB) within CUDA's 48 KB of static shared memory and the registers within a multiprocessor.
constexpr size_t kRefineGroup = 256;
constexpr size_t kLinearGroup = 64;  // shift: a work-item per particle

struct RefineArgs {  // cl/refine.cl's dt_refine_args
  float damping, min_incidence, centre_x, centre_y, centre_z, now;
  int iterations;
  float radius, converged_motion;
  unsigned vertex_count;
};

size_t round_up(size_t n, size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}
}  // namespace

DeviceRefiner::DeviceRefiner(compute::Queue& queue, const Mesh& mesh, const Camera& camera, const TrackerConfig& config,
                             int occlusion_mode)
    : queue_(queue),
      config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      radius_(mesh.radius()),
      program_(queue.build(
          "refine.cl", compute::kernel_source("refine.cl"),
          {"DT_GROUP_SIZE=" + std::to_string(kRefineGroup), "DT_OCCLUSION=" + std::to_string(occlusion_mode)})),
      refine_(program_->kernel("refine")),
      shift_(program_->kernel("shift_particles")),
      mesh_(queue, mesh),
      pose_(queue, DT_STATE_STRIDE),
      correction_(queue, 6),
      tile_(queue, static_cast<size_t>(camera.pixel_count())),
      ids_(queue, static_cast<size_t>(camera.pixel_count())) {}

compute::EventPtr DeviceRefiner::refine(compute::Buffer<float>& estimate, const RefineInputs& in) {
  const Refinement& r = config_.refine;
  const RefineArgs args{static_cast<float>(r.damping),
                        static_cast<float>(r.min_incidence),
                        static_cast<float>(centre_.x()),
                        static_cast<float>(centre_.y()),
                        static_cast<float>(centre_.z()),
                        static_cast<float>(in.time),
                        r.iterations,
                        static_cast<float>(radius_),
                        static_cast<float>(r.converged_motion),
                        static_cast<unsigned>(mesh_.vertices.size() / 3)};
  compute::Kernel& k = *refine_;
  compute::set_arg(k, 0, estimate);
  compute::set_arg(k, 1, in.states);
  compute::set_arg(k, 2, in.observed);
  compute::set_arg(k, 3, in.occlusion);
  compute::set_arg(k, 4, in.occlusion_time);
  compute::set_arg(k, 5, in.priors);
  compute::set_arg(k, 6, in.atlas);
  k.set_arg(7, in.layout.kernel_args());
  compute::set_arg(k, 8, mesh_.vertices);
  compute::set_arg(k, 9, mesh_.triangles);
  compute::set_arg(k, 10, mesh_.planes);
  k.set_arg(11, mesh_.triangle_count());
  k.set_arg(12, raster_camera_args(camera_, config_));
  k.set_arg(13, model_args(config_));
  k.set_arg(14, args);
  compute::set_arg(k, 15, pose_);
  compute::set_arg(k, 16, tile_);
  compute::set_arg(k, 17, ids_);
  compute::set_arg(k, 18, correction_);
  return queue_.launch(k, compute::NdRange::linear(kRefineGroup, kRefineGroup));
}

compute::EventPtr DeviceRefiner::shift(const compute::Buffer<float>& from, compute::Buffer<float>& to, size_t count) {
  compute::Kernel& k = *shift_;
  compute::set_arg(k, 0, from);
  compute::set_arg(k, 1, to);
  k.set_arg(2, static_cast<unsigned>(count));
  compute::set_arg(k, 3, correction_);
  k.set_arg(4, static_cast<float>(centre_.x()));
  k.set_arg(5, static_cast<float>(centre_.y()));
  k.set_arg(6, static_cast<float>(centre_.z()));
  return queue_.launch(k, compute::NdRange::linear(round_up(count, kLinearGroup), kLinearGroup));
}

}  // namespace depthtrack
