#pragma once
// A bar in front of the object that hides a chosen share of its pixels and sweeps across it.
#include <span>

namespace depthtrack::synth {

// Period of the occluder's sweep across the object (seconds).
inline constexpr double kOccluderSweepPeriod = 4.0;

// object: the object's own rendering (0 = not the object); scene: the full true depth, which gets the
// bar drawn into it. Picks a contiguous band of columns holding about `fraction` of the object's
// pixels, its position swept by t, and returns the share of object pixels the bar actually hid.
double add_occluder(std::span<float> scene, std::span<const float> object, int width, int height, double fraction,
                    double t);

}  // namespace depthtrack::synth
