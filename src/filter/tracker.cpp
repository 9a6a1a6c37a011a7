#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <sstream>

#include "filter/filter_backend.hpp"

namespace depthtrack {

Tracker::Tracker(const Mesh& mesh, const Camera& sensor, const TrackerConfig& config) : sensor_(sensor) {
  sensor.validate();
  config.validate();
  Mesh checked = mesh;
  checked.validate_and_clean("tracker mesh");
  decimation_ = sensor.decimation_factor_for(config.width, config.height);
  working_ = sensor.decimated(decimation_);
  config_ = config;
  backend_ = make_filter_backend(checked, working_, config);
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
  initialized_ = true;
  has_previous_ = false;
}

Estimate Tracker::update(const DepthImage& depth, double timestamp) {
  if (!initialized_) throw InputError("Tracker::update called before initialize()");
  if (depth.width() != sensor_.width || depth.height() != sensor_.height) {
    std::ostringstream m;
    m << "depth image is " << depth.width() << "x" << depth.height() << " but the camera is " << sensor_.width << "x"
      << sensor_.height;
    throw InputError(m.str());
  }
  if (!std::isfinite(timestamp)) throw InputError("timestamp is not finite");
  if (has_previous_ && timestamp <= previous_timestamp_) {
    std::ostringstream m;
    m.precision(17);
    m << "timestamps must increase: " << timestamp << " s follows " << previous_timestamp_ << " s";
    throw InputError(m.str());
  }
  // Decimate only when needed: at the sensor's resolution the caller's image is used as it is.
  DepthImage decimated;
  if (decimation_ > 1) decimated = depth.decimated(decimation_);
  const DepthImage& working = decimation_ > 1 ? decimated : depth;
  if (working.valid_count() == 0) {
    std::ostringstream m;
    m << "depth frame at " << timestamp << " s has no valid pixel (all missing) at the working resolution";
    throw InputError(m.str());
  }
  const double dt = has_previous_ ? timestamp - previous_timestamp_ : 0.0;
  Estimate e = backend_->update(working, dt);
  previous_timestamp_ = timestamp;
  has_previous_ = true;
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
