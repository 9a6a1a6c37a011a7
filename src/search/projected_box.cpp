#include <algorithm>
#include <cmath>
#include <depthtrack/init_hint.hpp>

namespace depthtrack {

InitHint projected_box(const Mesh& mesh, const Camera& camera, const Pose& pose) {
  double u0 = camera.width, v0 = camera.height, u1 = 0, v1 = 0;
  for (const auto& v : mesh.vertices) {
    const Eigen::Vector2d p = camera.project(pose.apply(v.cast<double>()));
    u0 = std::min(u0, p.x());
    v0 = std::min(v0, p.y());
    u1 = std::max(u1, p.x());
    v1 = std::max(v1, p.y());
  }
  auto pixel = [](double x, int size) { return std::clamp(static_cast<int>(std::lround(x)), 0, size - 1); };
  return InitHint::box(pixel(u0, camera.width), pixel(v0, camera.height), pixel(u1, camera.width),
                       pixel(v1, camera.height));
}

}  // namespace depthtrack
