#include "search/surface_points.hpp"

#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>
#include <sstream>

namespace depthtrack::search {

namespace {
struct Region {
  int u0, v0, u1, v1;  // inclusive
};

Region checked_region(const DepthImage& depth, const Camera& camera, const InitHint& hint, double radius) {
  const Region whole{0, 0, depth.width() - 1, depth.height() - 1};
  if (hint.kind == InitHint::Kind::None) return whole;
  if (hint.kind == InitHint::Kind::Box) {
    std::ostringstream m;
    m << "initialization box (" << hint.u0 << ", " << hint.v0 << ") - (" << hint.u1 << ", " << hint.v1 << ")";
    if (hint.u0 > hint.u1 || hint.v0 > hint.v1) throw InputError(m.str() + " is empty: it needs u0 <= u1 and v0 <= v1");
    if (hint.u0 < 0 || hint.v0 < 0 || hint.u1 >= depth.width() || hint.v1 >= depth.height()) {
      m << " is not inside the " << depth.width() << "x" << depth.height() << " image (pixels 0.." << depth.width() - 1
        << ", 0.." << depth.height() - 1 << ")";
      throw InputError(m.str());
    }
    return {hint.u0, hint.v0, hint.u1, hint.v1};
  }
  if (!hint.point.allFinite() || hint.point.z() <= 0)
    throw InputError("initialization point must be finite and in front of the camera (z > 0)");
  // The point's neighbourhood in the image: its projection, give or take the object's radius.
  const Eigen::Vector2d c = camera.project(hint.point);
  const double reach = camera.fx * radius / std::max(hint.point.z() - radius, 0.05);
  Region r{static_cast<int>(std::floor(c.x() - reach)), static_cast<int>(std::floor(c.y() - reach)),
           static_cast<int>(std::ceil(c.x() + reach)), static_cast<int>(std::ceil(c.y() + reach))};
  r.u0 = std::max(r.u0, 0);
  r.v0 = std::max(r.v0, 0);
  r.u1 = std::min(r.u1, whole.u1);
  r.v1 = std::min(r.v1, whole.v1);
  return r;
}

bool admitted(const InitHint& hint, const Eigen::Vector3d& p, double radius) {
  return hint.kind != InitHint::Kind::Point || (p - hint.point).norm() <= radius;
}

// Whether the depth within the object's reach of pixel (u, v) lies farther than z by half the
// object's radius somewhere: an object stands in front of what is behind it. Only such points are
// tried when there are any (without a hint: only ever), which keeps a flat wall (where a flat face
// fits as well as anywhere) out of the search and the grid small.
bool in_front(const DepthImage& depth, const Camera& camera, int u, int v, float z, double radius, int stride) {
  const int reach = static_cast<int>(std::ceil(camera.fx * radius / z));
  const int step = std::max(1, std::min(stride, reach / 4));
  for (int dv = -reach; dv <= reach; dv += step)
    for (int du = -reach; du <= reach; du += step) {
      const int nu = u + du, nv = v + dv;
      if (nu < 0 || nv < 0 || nu >= depth.width() || nv >= depth.height()) continue;
      const float y = depth.at(nu, nv);
      if (DepthImage::is_valid(y) && y > z + 0.5 * radius) return true;
    }
  return false;
}
}  // namespace

std::vector<Eigen::Vector3d> surface_points(const DepthImage& depth, const Camera& camera, const InitHint& hint,
                                            double radius, int stride) {
  const Region r = checked_region(depth, camera, hint, radius);
  stride = std::max(stride, 1);
  std::vector<Eigen::Vector3d> points, behind;  // standing out in front of their surroundings, or not
  // Centred in the region, so a small box still gets its middle.
  const int su = r.u0 + ((r.u1 - r.u0) % stride) / 2, sv = r.v0 + ((r.v1 - r.v0) % stride) / 2;
  for (int v = sv; v <= r.v1; v += stride)
    for (int u = su; u <= r.u1; u += stride) {
      const float z = depth.at(u, v);
      if (!DepthImage::is_valid(z)) continue;
      const Eigen::Vector3d p = camera.back_project(u, v, z);
      if (!admitted(hint, p, radius)) continue;
      (in_front(depth, camera, u, v, z, radius, stride) ? points : behind).push_back(p);
    }
  // A box or point region whose points all lie flat (an object pressed against a wall, or one
  // filling the box) keeps them all.
  if (!points.empty() || hint.kind == InitHint::Kind::None) return points;
  if (!behind.empty()) return behind;
  // A region narrower than the stride: every valid pixel of it.
  for (int v = r.v0; v <= r.v1; ++v)
    for (int u = r.u0; u <= r.u1; ++u) {
      const float z = depth.at(u, v);
      if (!DepthImage::is_valid(z)) continue;
      const Eigen::Vector3d p = camera.back_project(u, v, z);
      if (admitted(hint, p, radius)) points.push_back(p);
    }
  if (!points.empty()) return points;
  std::ostringstream m;
  if (hint.kind == InitHint::Kind::Box)
    m << "initialization box (" << r.u0 << ", " << r.v0 << ") - (" << r.u1 << ", " << r.v1 << ") holds no valid depth";
  else if (hint.kind == InitHint::Kind::Point)
    m << "no valid depth within " << radius << " m of the initialization point";
  else
    m << "the depth image holds no valid pixel";
  throw InputError(m.str());
}

}  // namespace depthtrack::search
