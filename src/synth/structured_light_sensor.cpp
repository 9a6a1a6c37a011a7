#include "synth/structured_light_sensor.hpp"

#include <cmath>
#include <limits>

#include "synth/random.hpp"

namespace depthtrack::synth {

namespace {
// A depth discontinuity: some 4-neighbour inside the image is empty or further than threshold away
// in depth. The projector's pattern is shadowed or smeared there, so real sensors lose such pixels.
bool at_edge(std::span<const float> z, int width, int height, int u, int v, double threshold) {
  const float here = z[static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u)];
  const int du[4] = {-1, 1, 0, 0}, dv[4] = {0, 0, -1, 1};
  for (int k = 0; k < 4; ++k) {
    const int nu = u + du[k], nv = v + dv[k];
    if (nu < 0 || nv < 0 || nu >= width || nv >= height) continue;
    const float there = z[static_cast<size_t>(nv) * static_cast<size_t>(width) + static_cast<size_t>(nu)];
    if (there <= 0.0f || std::abs(there - here) > threshold) return true;
  }
  return false;
}
}  // namespace

std::vector<float> sense_depth(const SensorModel& sensor, const Camera& camera, std::span<const float> true_depth,
                               std::mt19937_64& rng) {
  constexpr float kMissing = std::numeric_limits<float>::quiet_NaN();
  // Disparity (pixels) times depth: the triangulation constant of projector and camera.
  const double focal_baseline = camera.fx * sensor.baseline;
  std::vector<float> measured(true_depth.size(), kMissing);
  StandardNormal gaussian;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const size_t i = static_cast<size_t>(v) * static_cast<size_t>(camera.width) + static_cast<size_t>(u);
      const auto [random_draw, edge_draw] = uniform_pair(rng);
      const double noise = gaussian(rng);
      const double z = true_depth[i];
      if (!(z >= sensor.min_depth && z <= sensor.max_depth)) continue;  // also the empty (0) pixels
      if (random_draw < sensor.random_dropout) continue;
      if (edge_draw < sensor.edge_dropout &&
          at_edge(true_depth, camera.width, camera.height, u, v, sensor.edge_threshold))
        continue;
      // Noise enters in disparity, then the matcher's subpixel step quantizes it: depth error grows as z^2.
      const double disparity = focal_baseline / z + sensor.disparity_noise * noise;
      const double quantized = std::floor(disparity / sensor.disparity_step + 0.5) * sensor.disparity_step;
      if (quantized <= 0) continue;  // no match at all
      measured[i] = static_cast<float>(focal_baseline / quantized);
    }
  }
  return measured;
}

}  // namespace depthtrack::synth
