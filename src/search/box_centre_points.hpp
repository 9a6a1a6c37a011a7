#pragma once
// Extra places for the object's centre under a box hint: the box's middle, at the depths measured in it.
#include <depthtrack/camera.hpp>
#include <depthtrack/init_hint.hpp>
#include <span>
#include <vector>

namespace depthtrack::search {

// Points on the ray through the middle of the box (sensor pixels), one at each distinct depth of
// `surface` (depths closer than `spacing` to one already taken are skipped). The grid puts the
// object's centre behind a measured point along that point's ray, so where it lies sideways and how
// deep are tied to one pixel's depth. That misses the centre when an occluder hides the object's
// middle (a bar across the synthetic handset: the centres lie half its length to the side, or at
// the bar's depth) and when an elongated object is tilted in depth (its middle's surface is nearer
// the centre than the grid's offset assumes). A detector's box is centred on the object: its middle
// at every depth seen in the box has a centre near the truth. Empty unless the hint is a box.
std::vector<Eigen::Vector3d> box_centre_points(const InitHint& hint, const Camera& camera,
                                               std::span<const Eigen::Vector3d> surface, double spacing);

}  // namespace depthtrack::search
