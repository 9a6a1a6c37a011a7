#pragma once
// What a structured-light depth camera reports for a scene's true z-depth.
#include <depthtrack/camera.hpp>
#include <depthtrack/synth.hpp>
#include <random>
#include <span>
#include <vector>

namespace depthtrack::synth {

// true_depth: camera.width * camera.height metric z-depths, row-major, 0 where the scene is empty.
// Returns the measured depths in metres, NaN where the sensor reports nothing. Every pixel draws its
// variates whether it is measured or not, so the random stream does not depend on the scene.
std::vector<float> sense_depth(const SensorModel& sensor, const Camera& camera, std::span<const float> true_depth,
                               std::mt19937_64& rng);

}  // namespace depthtrack::synth
