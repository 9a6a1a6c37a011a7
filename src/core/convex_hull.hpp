#pragma once
// The vertices of a point set's convex hull (Qhull), for bounding where a mesh can appear in an image:
// under a perspective projection with every point in front of the camera, the projection of the hull is
// the hull of the projected hull vertices, so their projections reach exactly as far as all the points'.
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace depthtrack {

// The indices of the points that are vertices of their convex hull, in ascending order; nothing where
// the points span no volume (fewer than 4, or all on one plane or line) or Qhull fails otherwise.
std::optional<std::vector<int>> convex_hull_vertices(const std::vector<Eigen::Vector3f>& points);

}  // namespace depthtrack
