#pragma once
// Scores batches of poses on the compute device for global search: the kernel rasterizer
// (cl/rasterize.cl) draws a batch into an atlas, cl/score.cl sums each tile's likelihood terms
// with a fresh occlusion prior, and one download per batch brings the scores back. No filter state
// is read or written.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <span>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "compute/buffer.hpp"

namespace depthtrack {

class DevicePoseScorer {
 public:
  DevicePoseScorer(compute::Queue& queue, const Mesh& mesh, const Camera& camera, const TrackerConfig& config);
  ~DevicePoseScorer();

  // One log-likelihood per pose, in order, under `model`.
  std::vector<double> score(std::span<const Pose> poses, const DepthImage& depth, const ObservationModel& model);
  // Poses drawn and scored per kernel launch (sized to fit device memory).
  size_t batch_size() const { return batch_; }

 private:
  compute::Queue& queue_;
  TrackerConfig config_;
  size_t pixels_, batch_;
  std::unique_ptr<AtlasSource> atlas_source_;
  std::unique_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> kernel_;
  compute::Buffer<float> states_, atlas_, observed_, scores_;
};

}  // namespace depthtrack
