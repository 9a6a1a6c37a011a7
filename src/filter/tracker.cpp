#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <sstream>

#include "core/stopwatch.hpp"
#include "filter/filter_backend.hpp"
#include "filter/track_supervisor.hpp"

namespace depthtrack {

namespace {
// Particle spread around search candidates: the search's last steps are finer than this, the
// filter's first frames settle the rest.
constexpr InitialSpread kSearchSpread{0.005, 0.05};
}  // namespace

const char* to_string(TrackStatus status) {
  return status == TrackStatus::Lost ? "lost" : "tracking";
}

Tracker::Tracker(const Mesh& mesh, const Camera& sensor, const TrackerConfig& config) : sensor_(sensor) {
  sensor.validate();
  config.validate();
  Mesh checked = mesh;
  checked.validate_and_clean("tracker mesh");
  decimation_ = sensor.decimation_factor_for(config.width, config.height);
  working_ = sensor.decimated(decimation_);
  config_ = config;
  backend_ = make_filter_backend(checked, working_, config);
  supervisor_ = std::make_unique<TrackSupervisor>(checked, sensor_, working_, decimation_, config);
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

void Tracker::initialize(const Pose& pose, const InitialSpread& spread) {
  if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite())
    throw InputError("initial pose is not finite");
  if (!(std::isfinite(spread.metres) && spread.metres >= 0 && std::isfinite(spread.radians) && spread.radians >= 0))
    throw InputError("initial spread must be finite and non-negative");
  backend_->initialize(pose, spread);
  supervisor_->reset();
  initialized_ = true;
  has_previous_ = false;
}

const DepthImage& Tracker::working_frame(const DepthImage& depth, DepthImage& storage) const {
  if (depth.width() != sensor_.width || depth.height() != sensor_.height) {
    std::ostringstream m;
    m << "depth image is " << depth.width() << "x" << depth.height() << " but the camera is " << sensor_.width << "x"
      << sensor_.height;
    throw InputError(m.str());
  }
  // Decimate only when needed: at the sensor's resolution the caller's image is used as it is.
  if (decimation_ == 1) return depth;
  storage = depth.decimated(decimation_);
  return storage;
}

Estimate Tracker::initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint) {
  if (!std::isfinite(timestamp)) throw InputError("timestamp is not finite");
  DepthImage storage;
  const DepthImage& working = working_frame(depth, storage);
  const Stopwatch clock;
  const search::SearchResult found = supervisor_->search(*backend_, depth, working, hint, 0.0, 0u);
  if (found.candidates.empty())
    throw InputError(
        "global initialization: nothing in the frame stands out in front of its surroundings by half the "
        "object's size; give a box or a point");
  const std::vector<Pose> seeds = TrackSupervisor::seeds(found);
  backend_->initialize_modes(seeds, kSearchSpread);
  const double search_ms = clock.elapsed_ms();
  supervisor_->reset();
  initialized_ = true;
  has_previous_ = false;
  Estimate e = run_frame(working, timestamp);
  e.timings.search_ms += search_ms;
  e.timings.total_ms += search_ms;
  e.search_poses = found.poses_scored;
  return e;
}

Estimate Tracker::update(const DepthImage& depth, double timestamp) {
  if (!initialized_) throw InputError("Tracker::update called before initialize()");
  DepthImage storage;
  const DepthImage& working = working_frame(depth, storage);
  if (!std::isfinite(timestamp)) throw InputError("timestamp is not finite");
  if (has_previous_ && timestamp <= previous_timestamp_) {
    std::ostringstream m;
    m.precision(17);
    m << "timestamps must increase: " << timestamp << " s follows " << previous_timestamp_ << " s";
    throw InputError(m.str());
  }
  if (working.valid_count() == 0) {
    std::ostringstream m;
    m << "depth frame at " << timestamp << " s has no valid pixel (all missing) at the working resolution";
    throw InputError(m.str());
  }
  // While lost, search this frame; a candidate the depth explains well enough re-seeds the filter.
  double search_ms = 0;
  size_t search_poses = 0;
  bool recovered = false;
  if (supervisor_->status() == TrackStatus::Lost && config_.recovery.enabled) {
    const Stopwatch clock;
    const search::SearchResult found = supervisor_->search(*backend_, depth, working, InitHint::anywhere(),
                                                           config_.recovery.budget_ms, ++search_round_);
    if (!found.candidates.empty() && supervisor_->found(found.candidates.front().pose, working)) {
      backend_->initialize_modes(TrackSupervisor::seeds(found), kSearchSpread);
      supervisor_->reset();
      has_previous_ = false;
      recovered = true;
    }
    search_ms = clock.elapsed_ms();
    search_poses = found.poses_scored;
  }
  Estimate e = run_frame(working, timestamp);
  e.recovered = recovered;
  e.search_poses = search_poses;
  e.timings.search_ms += search_ms;
  e.timings.total_ms += search_ms;
  return e;
}

Estimate Tracker::run_frame(const DepthImage& working, double timestamp) {
  const double dt = has_previous_ ? timestamp - previous_timestamp_ : 0.0;
  Estimate e = backend_->update(working, dt);
  previous_timestamp_ = timestamp;
  has_previous_ = true;
  e.confidence = supervisor_->assess(e.pose, working).confidence();
  e.status = supervisor_->observe(e.confidence);
  return e;
}

const Camera& Tracker::working_camera() const {
  return working_;
}
const TrackerConfig& Tracker::config() const {
  return config_;
}
std::string Tracker::backend_description() const {
  return backend_->description();
}

}  // namespace depthtrack
