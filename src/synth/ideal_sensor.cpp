#include "synth/ideal_sensor.hpp"

#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <limits>

namespace depthtrack {

const char* to_string(SensorKind kind) {
  return kind == SensorKind::Ideal ? "ideal" : "structured-light";
}

SensorKind sensor_kind_from_string(const std::string& name) {
  for (auto kind : {SensorKind::StructuredLight, SensorKind::Ideal})
    if (name == to_string(kind)) return kind;
  throw InputError("unknown sensor '" + name + "' (choose structured-light or ideal)");
}

namespace synth {
std::vector<float> ideal_depth(std::span<const float> true_depth) {
  std::vector<float> measured(true_depth.begin(), true_depth.end());
  for (float& z : measured)
    if (!(z > 0.0f)) z = std::numeric_limits<float>::quiet_NaN();
  return measured;
}
}  // namespace synth

}  // namespace depthtrack
