#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <exception>
#include <optional>

#include "core/stopwatch.hpp"
#include "core/thread_pool.hpp"
#include "tracker/mutual_occlusion.hpp"

namespace depthtrack {

MultiTracker::MultiTracker(std::shared_ptr<Device> device, const std::vector<Mesh>& meshes, const Camera& sensor,
                           const TrackerConfig& config, bool mutual_occlusion, int host_threads)
    : device_(std::move(device)) {
  if (!device_) throw InputError("several-object tracker: the device is null (open one with Device::open)");
  if (meshes.empty()) throw InputError("several-object tracker: no mesh given");
  if (host_threads < 0 || host_threads > 1024)
    throw InputError("several-object tracker: host_threads is " + std::to_string(host_threads) +
                     ": give 0 (one per object) or a count from 1 to 1024");
  for (const Mesh& mesh : meshes) trackers_.emplace_back(device_, mesh, sensor, config);
  poses_.resize(meshes.size());
  initialized_.assign(meshes.size(), false);
  const Camera& working = trackers_.front().working_camera();
  if (mutual_occlusion && meshes.size() > 1) occlusion_ = std::make_unique<MutualOcclusion>(meshes, working);
  const int objects = static_cast<int>(std::min<size_t>(meshes.size(), 1024));
  pool_ = std::make_unique<ThreadPool>(host_threads > 0 ? host_threads : std::min(objects, hardware_threads()));
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
  const Stopwatch clock;
  timings_ = MultiStageTimings{};
  DepthImage storage;
  // Every tracker has the sensor's camera and the working one: the frame is checked and decimated once.
  const DepthImage& working = trackers_.front().working_frame(depth, storage);
  timings_.working_ms = clock.elapsed_ms();
  std::vector<Estimate> estimates = run(
      working, [&depth]() -> const DepthImage& { return depth; }, timestamp);
  timings_.total_ms = clock.elapsed_ms();
  return estimates;
}

std::vector<Estimate> MultiTracker::update(const DepthView& depth, double timestamp) {
  check_initialized();
  const Stopwatch clock;
  timings_ = MultiStageTimings{};
  const DepthImage working = trackers_.front().working_frame(depth);
  timings_.working_ms = clock.elapsed_ms();
  std::optional<DepthImage> sensor;  // converted whole only if a lost object's search needs it
  std::vector<Estimate> estimates = run(
      working,
      [&]() -> const DepthImage& {
        if (!sensor) sensor = depth.to_image();
        return *sensor;
      },
      timestamp);
  timings_.total_ms = clock.elapsed_ms();
  return estimates;
}

// The confidence of the previous frame rendered each object at its estimate, which is poses_[k]: that
// rendering is the layer, so only a start (or a frame without data, which assesses nothing) draws.
std::vector<std::vector<float>> MultiTracker::occluder_layers() {
  std::vector<std::vector<float>> layers(trackers_.size());
  pool_->run(trackers_.size(), [&](size_t k, int) { layers[k] = trackers_[k].silhouette(poses_[k]); });
  return layers;
}

// Every object's frame is enqueued (each tracker has a compute queue of its own), then every estimate
// is collected: the device runs the objects' work side by side. With mutual occlusion each object's
// working frame hides what the others' previous estimates cover, so none waits for another's estimate.
// The estimates are collected on this thread (a GL renderer's timer events are read on its thread), their
// confidences assessed on the pool as each arrives: each tracker's assessment touches its own state only.
// collect_ms ends with the last collection, confidence_ms is what the assessments take after it.
std::vector<Estimate> MultiTracker::run(const DepthImage& working,
                                        const std::function<const DepthImage&()>& sensor_frame, double timestamp) {
  const size_t n = trackers_.size();
  std::vector<DepthImage> masked(occlusion_ ? n : 0);
  const auto frame_of = [&](size_t j) -> const DepthImage& { return occlusion_ ? masked[j] : working; };
  size_t started = 0;
  std::exception_ptr failure;
  try {
    if (occlusion_) {
      Stopwatch clock;
      // Every mask is made before any object starts: a lost object's search redraws its silhouette.
      const std::vector<std::vector<float>> layers = occluder_layers();
      timings_.occluders_ms = clock.lap_ms();
      for (size_t j = 0; j < n; ++j) masked[j] = occlusion_->frame_for(j, working, poses_, layers);
      timings_.masks_ms = clock.lap_ms();
    }
    Stopwatch clock;
    for (; started < n; ++started) {
      trackers_[started].start_frame(frame_of(started), sensor_frame, timestamp);
      timings_.object_enqueue_ms.push_back(clock.lap_ms());
      timings_.enqueue_ms += timings_.object_enqueue_ms.back();
    }
  } catch (...) {
    failure = std::current_exception();
  }
  // Every started frame is collected, even after a failure, so that no tracker is left mid-frame;
  // each collected estimate's confidence is assessed on the pool while the next is collected.
  Stopwatch clock;
  std::vector<Estimate> estimates(started);
  std::vector<size_t> collected(started);  // sized once: the pool reads entries as they are released
  try {
    pool_->run_as_released(
        started,
        [&](const std::function<void()>& release) {
          size_t count = 0;
          for (size_t j = 0; j < started; ++j) {
            try {
              estimates[j] = trackers_[j].collect_frame();
              collected[count++] = j;
              release();
            } catch (...) {
              if (!failure) failure = std::current_exception();
            }
          }
          timings_.collect_ms = clock.lap_ms();
        },
        [&](size_t i, int) {
          const size_t j = collected[i];
          trackers_[j].assess_frame(estimates[j], frame_of(j));
        });
  } catch (...) {
    if (!failure) failure = std::current_exception();
  }
  timings_.confidence_ms = clock.lap_ms();
  if (failure) std::rethrow_exception(failure);
  for (size_t j = 0; j < n; ++j) poses_[j] = estimates[j].pose;
  return estimates;
}

}  // namespace depthtrack
