#pragma once
// Where global search places the object: measured surface points inside the hint's region.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/init_hint.hpp>
#include <vector>

namespace depthtrack::search {

// The camera-frame points of valid sensor depth inside the hint's region (the whole image; the
// box; within radius of the point), one every `stride` pixels in each direction, keeping only
// points with depth at least half the radius farther within the object's reach when there are any
// (without a hint: always, so possibly none, when nothing stands out of the scene). InputError for an empty box, a box
// outside the image, a point behind the camera, or a region without valid depth.
std::vector<Eigen::Vector3d> surface_points(const DepthImage& depth, const Camera& camera, const InitHint& hint,
                                            double radius, int stride);

}  // namespace depthtrack::search
