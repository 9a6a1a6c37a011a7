#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>

#include "tracker/mutual_occlusion.hpp"

namespace depthtrack {

MultiTracker::MultiTracker(std::shared_ptr<Device> device, const std::vector<Mesh>& meshes, const Camera& sensor,
                           const TrackerConfig& config, bool mutual_occlusion)
    : device_(std::move(device)) {
  if (!device_) throw InputError("several-object tracker: the device is null (open one with Device::open)");
  if (meshes.empty()) throw InputError("several-object tracker: no mesh given");
  for (const Mesh& mesh : meshes) trackers_.emplace_back(device_, mesh, sensor, config);
  poses_.resize(meshes.size());
  initialized_.assign(meshes.size(), false);
  const Camera& working = trackers_.front().working_camera();
  if (mutual_occlusion && meshes.size() > 1)
    occlusion_ = std::make_unique<MutualOcclusion>(meshes, working, sensor.width / working.width, config.near_plane,
                                                   config.observation.max_depth);
}

MultiTracker::~MultiTracker() = default;
MultiTracker::MultiTracker(MultiTracker&&) noexcept = default;
MultiTracker& MultiTracker::operator=(MultiTracker&&) noexcept = default;

const Tracker& MultiTracker::tracker(size_t object) const {
  if (object >= trackers_.size())
    throw InputError("object " + std::to_string(object) + " does not exist: there are " +
                     std::to_string(trackers_.size()));
  return trackers_[object];
}

void MultiTracker::initialize(size_t object, const Pose& pose, const InitialSpread& spread) {
  tracker(object);  // checks the index
  trackers_[object].initialize(pose, spread);
  poses_[object] = pose;
  initialized_[object] = true;
}

void MultiTracker::check_initialized() const {
  for (size_t j = 0; j < trackers_.size(); ++j)
    if (!initialized_[j]) throw InputError("object " + std::to_string(j) + " was not initialized");
}

std::vector<Estimate> MultiTracker::update(const DepthImage& depth, double timestamp) {
  check_initialized();
  std::vector<Estimate> estimates;
  for (size_t j = 0; j < trackers_.size(); ++j) {
    // Objects before j hide pixels with this frame's estimates, those after with the last frame's.
    estimates.push_back(occlusion_ ? trackers_[j].update(occlusion_->frame_for(j, depth, poses_), timestamp)
                                   : trackers_[j].update(depth, timestamp));
    poses_[j] = estimates.back().pose;
  }
  return estimates;
}

std::vector<Estimate> MultiTracker::update(const DepthView& depth, double timestamp) {
  if (occlusion_) return update(depth.to_image(), timestamp);  // the masks are written into a copy
  check_initialized();
  std::vector<Estimate> estimates;
  for (size_t j = 0; j < trackers_.size(); ++j) {
    estimates.push_back(trackers_[j].update(depth, timestamp));
    poses_[j] = estimates.back().pose;
  }
  return estimates;
}

}  // namespace depthtrack
