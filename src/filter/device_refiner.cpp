#include "filter/device_refiner.hpp"

#include "compute/program_cache.hpp"
#include "dt_state.h"
#include "model/kernel_params.hpp"

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

DeviceRefiner::DeviceRefiner(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh,
                             const Camera& camera, const TrackerConfig& config, const std::string& occlusion_definition)
    : queue_(queue),
      config_(config),
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      radius_(mesh.radius()),
      program_(programs.program("refine.cl", {"DT_GROUP_SIZE=" + std::to_string(kRefineGroup), occlusion_definition})),
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
  return queue_.launch(*refine_, compute::NdRange::linear(kRefineGroup, kRefineGroup), estimate, in.states, in.observed,
                       in.occlusion, in.occlusion_time, in.priors, in.atlas, in.layout.kernel_args(), mesh_.vertices,
                       mesh_.triangles, mesh_.planes, mesh_.triangle_count(), model::camera_params(camera_, config_),
                       model::model_params(config_), args, pose_, tile_, ids_, correction_);
}

compute::EventPtr DeviceRefiner::shift(const compute::Buffer<float>& from, compute::Buffer<float>& to, size_t count) {
  return queue_.launch(*shift_, compute::NdRange::linear(round_up(count, kLinearGroup), kLinearGroup), from, to,
                       static_cast<unsigned>(count), correction_, static_cast<float>(centre_.x()),
                       static_cast<float>(centre_.y()), static_cast<float>(centre_.z()));
}

}  // namespace depthtrack
