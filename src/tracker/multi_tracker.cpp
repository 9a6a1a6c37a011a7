#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <exception>
#include <optional>

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
    occlusion_ = std::make_unique<MutualOcclusion>(meshes, working, config.near_plane, config.observation.max_depth);
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
  DepthImage storage;
  // Every tracker has the sensor's camera and the working one: the frame is checked and decimated once.
  const DepthImage& working = trackers_.front().working_frame(depth, storage);
  return run(
      working, [&depth]() -> const DepthImage& { return depth; }, timestamp);
}

std::vector<Estimate> MultiTracker::update(const DepthView& depth, double timestamp) {
  check_initialized();
  const DepthImage working = trackers_.front().working_frame(depth);
  std::optional<DepthImage> sensor;  // converted whole only if a lost object's search needs it
  return run(
      working,
      [&]() -> const DepthImage& {
        if (!sensor) sensor = depth.to_image();
        return *sensor;
      },
      timestamp);
}

// Every object's frame is enqueued (each tracker has a compute queue of its own), then every estimate
// is collected: the device runs the objects' work side by side. With mutual occlusion each object's
// working frame hides what the others' previous estimates cover, so none waits for another's estimate.
std::vector<Estimate> MultiTracker::run(const DepthImage& working,
                                        const std::function<const DepthImage&()>& sensor_frame, double timestamp) {
  const size_t n = trackers_.size();
  std::vector<DepthImage> masked(occlusion_ ? n : 0);
  const auto frame_of = [&](size_t j) -> const DepthImage& { return occlusion_ ? masked[j] : working; };
  size_t started = 0;
  std::exception_ptr failure;
  try {
    // Each object drawn once (the previous estimates), each object's mask made from those layers.
    std::vector<std::vector<float>> layers;
    if (occlusion_) layers = occlusion_->draw(poses_);
    for (; started < n; ++started) {
      if (occlusion_) masked[started] = occlusion_->frame_for(started, working, poses_, layers);
      trackers_[started].start_frame(frame_of(started), sensor_frame, timestamp);
    }
  } catch (...) {
    failure = std::current_exception();
  }
  // Every started frame is collected, even after a failure, so that no tracker is left mid-frame.
  std::vector<Estimate> estimates;
  for (size_t j = 0; j < started; ++j) {
    try {
      estimates.push_back(trackers_[j].finish_frame(frame_of(j)));
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  for (size_t j = 0; j < n; ++j) poses_[j] = estimates[j].pose;
  return estimates;
}

}  // namespace depthtrack
