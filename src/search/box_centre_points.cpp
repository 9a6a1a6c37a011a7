#include "search/box_centre_points.hpp"

#include <algorithm>

namespace depthtrack::search {

std::vector<Eigen::Vector3d> box_centre_points(const InitHint& hint, const Camera& camera,
                                               std::span<const Eigen::Vector3d> surface, double spacing) {
  std::vector<Eigen::Vector3d> out;
  if (hint.kind != InitHint::Kind::Box) return out;
  std::vector<double> depths;
  for (const auto& p : surface) depths.push_back(p.z());
  std::sort(depths.begin(), depths.end());
  const double u = 0.5 * (hint.u0 + hint.u1), v = 0.5 * (hint.v0 + hint.v1);
  for (const double z : depths)
    if (out.empty() || z - out.back().z() >= spacing) out.push_back(camera.back_project(u, v, z));
  return out;
}

}  // namespace depthtrack::search
