#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <exception>
#include <functional>
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
  collects_on_pool_ = config.renderer != Renderer::Gl;
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

// The previous frame drew each object at its estimate, which is poses_[k], once it was collected (run,
// or the host confidence): that rendering is the layer, so only a start (or a failed frame) draws here.
std::vector<std::vector<float>> MultiTracker::occluder_layers() {
  std::vector<std::vector<float>> layers(trackers_.size());
  pool_->run(trackers_.size(), [&](size_t k, int) { layers[k] = trackers_[k].silhouette(poses_[k]); });
  return layers;
}

// Every object's frame is enqueued (each tracker has a compute queue of its own): the device runs the
// objects' work side by side. With mutual occlusion each object's working frame hides what the others'
// previous estimates cover, so none waits for another's estimate.
std::vector<Estimate> MultiTracker::run(const DepthImage& working,
                                        const std::function<const DepthImage&()>& sensor_frame, double timestamp) {
  const size_t n = trackers_.size();
  std::vector<DepthImage> masked(occlusion_ ? n : 0);
  const auto frame_of = [&](size_t j) -> const DepthImage& { return occlusion_ ? masked[j] : working; };
  std::vector<Estimate> estimates(n);
  if (occlusion_) {
    Stopwatch clock;
    // Every mask is made before any object starts: a lost object's search redraws its silhouette.
    const std::vector<std::vector<float>> layers = occluder_layers();
    timings_.occluders_ms = clock.lap_ms();
    for (size_t j = 0; j < n; ++j) masked[j] = occlusion_->frame_for(j, working, poses_, layers);
    timings_.masks_ms = clock.lap_ms();
  }
  const auto start = [&](size_t j) {
    const Stopwatch own;
    trackers_[j].start_frame(frame_of(j), sensor_frame, timestamp);
    timings_.object_enqueue_ms.push_back(own.elapsed_ms());
    timings_.enqueue_ms += timings_.object_enqueue_ms.back();
  };
  // After its estimate: the confidence and status, then the next frame's occluder layer (this estimate
  // drawn: the host confidence drew it already; a refining backend's confidence comes from the device,
  // and nothing had drawn it), each tracker's own state only, so on any thread.
  const auto assess = [&](size_t j) {
    trackers_[j].assess_frame(estimates[j], frame_of(j));
    if (occlusion_) trackers_[j].silhouette(estimates[j].pose);
  };
  // Each rethrows the first failure once every started object is collected; the poses then stay.
  if (collects_on_pool_)
    pipelined(n, start, assess, estimates);
  else
    collected_here(n, start, assess, estimates);
  for (size_t j = 0; j < n; ++j) poses_[j] = estimates[j].pose;
  return estimates;
}

// Each object's estimate is waited for, assessed and its next layer drawn on the pool while this thread
// enqueues the objects after it (the device finishes the first objects during the later enqueues: on
// NVIDIA OpenCL an object's enqueue is most of its frame). collect_ms runs from the last enqueue to the
// last collection, confidence_ms from there to the last assessment. A failed start drops the objects
// after it; every started one is still collected (ThreadPool::run_as_released), so none is left mid-frame.
void MultiTracker::pipelined(size_t n, const std::function<void(size_t)>& start,
                             const std::function<void(size_t)>& assess, std::vector<Estimate>& estimates) {
  const Stopwatch clock;
  double enqueued_at = 0;
  std::vector<double> collected_at(n, 0.0);
  std::exception_ptr failure;
  try {
    pool_->run_as_released(
        n,
        [&](const std::function<void()>& release) {
          for (size_t j = 0; j < n; ++j) {
            start(j);
            // Before the last release, so that the last collection cannot precede it.
            if (j + 1 == n) enqueued_at = clock.elapsed_ms();
            release();
          }
        },
        [&](size_t j, int) {
          estimates[j] = trackers_[j].collect_frame();
          collected_at[j] = clock.elapsed_ms();
          assess(j);
        });
  } catch (...) {
    failure = std::current_exception();
  }
  const double last_collected = *std::max_element(collected_at.begin(), collected_at.end());
  timings_.collect_ms = std::max(0.0, last_collected - enqueued_at);
  timings_.confidence_ms = std::max(0.0, clock.elapsed_ms() - std::max(enqueued_at, last_collected));
  if (failure) std::rethrow_exception(failure);
}

// With the GL renderer the estimates are collected on this thread (its timer events are read on the
// thread whose context it is), after every object is enqueued; each estimate's assessment runs on the
// pool while the next is collected. collect_ms ends with the last collection, confidence_ms is what the
// assessments take after it.
void MultiTracker::collected_here(size_t n, const std::function<void(size_t)>& start,
                                  const std::function<void(size_t)>& assess, std::vector<Estimate>& estimates) {
  std::exception_ptr failure;
  size_t started = 0;
  try {
    for (; started < n; ++started) start(started);
  } catch (...) {
    failure = std::current_exception();
  }
  // Every started frame is collected, even after a failure, so that no tracker is left mid-frame.
  Stopwatch clock;
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
        [&](size_t i, int) { assess(collected[i]); });
  } catch (...) {
    if (!failure) failure = std::current_exception();
  }
  timings_.confidence_ms = clock.lap_ms();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace depthtrack
