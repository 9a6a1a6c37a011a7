#pragma once
// What the Tracker asks of an implementation of the particle filter. The reference filter is one;
// the compute-layer filter (OpenCL, CUDA) is another. Inputs are already at working resolution.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker.hpp>
#include <memory>
#include <string>

namespace depthtrack {

class FilterBackend {
 public:
  virtual ~FilterBackend() = default;
  virtual void initialize(const Pose& pose, const InitialSpread& spread) = 0;
  // dt: seconds since the previous frame, 0 for the first frame after initialize().
  virtual Estimate update(const DepthImage& depth, double dt) = 0;
  virtual std::string description() const = 0;
};

// The backend a TrackerConfig::backend string names; InputError listing the names otherwise.
std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config);

}  // namespace depthtrack
