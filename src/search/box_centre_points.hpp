#pragma once
// Extra places for the object's centre under a box hint: the box's middle, at the depths measured in it.
#include <depthtrack/camera.hpp>
#include <depthtrack/init_hint.hpp>
#include <span>
#include <vector>

namespace depthtrack::search {

// Points on the ray through the middle of the box (sensor pixels), one at each distinct depth of
// `surface` (depths closer than `spacing` to one already taken are skipped). The search puts the
// object's centre behind a measured point along its ray; an occluder across the middle of the
// object (a bar in front of a handset) leaves no measured point whose ray passes near the centre,
// so the grid's centres all lie half the object's length to the side or on the occluder's depth.
// A detector's box is centred on the object: its middle at the depths of the object's visible
// parts puts a centre near the truth. Empty unless the hint is a box.
std::vector<Eigen::Vector3d> box_centre_points(const InitHint& hint, const Camera& camera,
                                               std::span<const Eigen::Vector3d> surface, double spacing);

}  // namespace depthtrack::search
