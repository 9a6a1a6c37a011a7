// Tracker's entry points for a caller's depth buffer in place (DepthView).
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <optional>
#include <sstream>

#include "tracker/tracker_impl.hpp"

namespace depthtrack {

namespace {
void check_view(const DepthView& depth, const Camera& sensor) {
  depth.validate();
  if (depth.width != sensor.width || depth.height != sensor.height) {
    std::ostringstream m;
    m << "depth view is " << depth.width << "x" << depth.height << " but the camera is " << sensor.width << "x"
      << sensor.height;
    throw InputError(m.str());
  }
}
}  // namespace

DepthImage Tracker::Impl::working_frame(const DepthView& depth) const {
  check_view(depth, sensor_);
  // As update(DepthImage) does: decimated, and depths beyond max_depth count as missing.
  return depth.sample(decimation_, static_cast<float>(config_.observation.max_depth));
}

Estimate Tracker::update(const DepthView& depth, double timestamp) {
  if (!impl_->initialized_) throw InputError("Tracker::update called before initialize()");
  const DepthImage working = impl_->working_frame(depth);
  std::optional<DepthImage> sensor;  // converted whole only if a search needs it
  return impl_->track_frame(
      working,
      [&]() -> const DepthImage& {
        if (!sensor) sensor = depth.to_image();
        return *sensor;
      },
      timestamp);
}

Estimate Tracker::initialize_global(const DepthView& depth, double timestamp, const InitHint& hint) {
  check_view(depth, impl_->sensor_);
  return initialize_global(depth.to_image(), timestamp, hint);
}

}  // namespace depthtrack
