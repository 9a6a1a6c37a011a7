#include "synth/validate_config.hpp"

#include <cmath>
#include <depthtrack/error.hpp>
#include <sstream>
#include <string>

namespace depthtrack::synth {

namespace {
// "name = value must ..." with the value printed as given (std::to_string would print 1e-5 as 0.000010).
[[noreturn]] void fail(const std::string& name, double value, const std::string& requirement) {
  std::ostringstream message;
  message << "synthetic sequence: " << name << " = " << value << " " << requirement;
  throw InputError(message.str());
}
void require(bool ok, const std::string& name, double value, const std::string& requirement) {
  if (!ok) fail(name, value, requirement);
}
bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}
}  // namespace

void validate_config(const SynthConfig& c) {
  c.camera.validate();
  require(c.frames >= 1, "frames", c.frames, "must be at least 1");
  require(std::isfinite(c.rate) && c.rate > 0, "rate", c.rate, "must be a positive number of frames per second");
  require(c.occluder_fraction >= 0 && c.occluder_fraction <= 0.9, "occluder_fraction", c.occluder_fraction,
          "must lie in [0, 0.9]");
  require(std::isfinite(c.background_depth), "background_depth", c.background_depth, "must be finite (<= 0 for none)");
  require(std::isfinite(c.metres_per_unit) && c.metres_per_unit > 0, "metres_per_unit", c.metres_per_unit,
          "must be positive");
  require(std::isfinite(c.hidden_from), "hidden_from", c.hidden_from, "must be finite (seconds)");
  require(std::isfinite(c.hidden_until), "hidden_until", c.hidden_until, "must be finite (seconds)");
  if (!c.reappear_offset.allFinite()) fail("reappear_offset", c.reappear_offset.norm(), "must be finite (metres)");

  const SensorModel& s = c.sensor;
  require(std::isfinite(s.baseline) && s.baseline > 0, "sensor.baseline", s.baseline, "must be positive");
  require(std::isfinite(s.disparity_step) && s.disparity_step > 0, "sensor.disparity_step", s.disparity_step,
          "must be positive");
  require(std::isfinite(s.disparity_noise) && s.disparity_noise >= 0, "sensor.disparity_noise", s.disparity_noise,
          "must be non-negative");
  require(std::isfinite(s.edge_threshold) && s.edge_threshold > 0, "sensor.edge_threshold", s.edge_threshold,
          "must be positive");
  require(s.edge_dropout >= 0 && s.edge_dropout <= 1, "sensor.edge_dropout", s.edge_dropout, "must be a probability");
  require(s.random_dropout >= 0 && s.random_dropout <= 1, "sensor.random_dropout", s.random_dropout,
          "must be a probability");
  require(std::isfinite(s.min_depth) && s.min_depth >= 0, "sensor.min_depth", s.min_depth, "must be non-negative");
  require(std::isfinite(s.max_depth) && s.max_depth > s.min_depth, "sensor.max_depth", s.max_depth,
          "must exceed sensor.min_depth");

  const TrajectoryModel& t = c.trajectory;
  if (!finite(t.centre) || !finite(t.amplitude) || !finite(t.rotation_amplitude))
    throw InputError("synthetic sequence: trajectory centre and amplitudes must be finite");
  require(std::isfinite(t.period) && t.period > 0, "trajectory.period", t.period, "must be positive seconds");
}

}  // namespace depthtrack::synth
