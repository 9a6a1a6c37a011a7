#pragma once
// The pose refinement on the device (cl/refine.cl): after weighing, one work-group fits the heaviest
// particle's pose to the frame's likelihood and writes the refined pose, its covariance and the
// steps it tried into the estimate buffer; shift then moves every particle by the same correction.
// Its own program, built with a larger work-group than the filter's kernels: the fit is one group,
// so its per-pixel and per-triangle loops are the refinement's latency. Reference:
// reference::PoseRefiner and ReferenceFilter::refine.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <string>

#include "atlas/atlas_layout.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/program_cache.hpp"

namespace depthtrack {

// The buffers of the filter that the fit reads (the heaviest particle's index is in estimate).
struct RefineInputs {
  const compute::Buffer<float>& states;
  const compute::Buffer<float>& observed;
  const compute::Buffer<float>& occlusion;
  const compute::Buffer<float>& occlusion_time;
  const compute::Buffer<float>& priors;  // weigh's occlusion priors of this frame
  const compute::Buffer<float>& atlas;
  const render::AtlasLayout& layout;
  double time;  // seconds since the first frame
};

class DeviceRefiner {
 public:
  // occlusion_definition: the filter kernels' DT_OCCLUSION definition (model::occlusion_definition).
  // refine.cl comes from programs, the cache of queue's device.
  DeviceRefiner(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                const TrackerConfig& config, const std::string& occlusion_definition);

  // Enqueues the fit; estimate holds summarize's output and receives the refined pose.
  compute::EventPtr refine(compute::Buffer<float>& estimate, const RefineInputs& in);
  // Enqueues the shift of count particles by the last fit's correction, from `from` into `to` (which
  // may be the same buffer).
  compute::EventPtr shift(const compute::Buffer<float>& from, compute::Buffer<float>& to, size_t count);

 private:
  compute::Queue& queue_;
  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  double radius_;
  std::shared_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> refine_, shift_;
  MeshBuffers mesh_;
  // One-pose scratch (state, depth bits, triangle ids) and the correction twist.
  compute::Buffer<float> pose_, correction_;
  compute::Buffer<unsigned> tile_, ids_;
};

}  // namespace depthtrack
