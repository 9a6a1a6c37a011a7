#pragma once
// A perfect depth camera: it reports the scene's z-depth exactly, so tracking precision can be
// measured without sensor noise.
#include <span>
#include <vector>

namespace depthtrack::synth {

// true_depth: metric z-depths, 0 where the scene is empty; returns them as they are, NaN where empty.
std::vector<float> ideal_depth(std::span<const float> true_depth);

}  // namespace depthtrack::synth
