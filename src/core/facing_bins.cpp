#include "core/facing_bins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace depthtrack {

namespace {
// The cube map cell of a unit normal: its largest coordinate's axis and sign pick the face, the other two
// divided by that one (in [-1, 1]) the cell.
int cube_cell(const Eigen::Vector3f& n, int cells) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const float major = n[axis];
  const int face = 2 * axis + (major < 0 ? 1 : 0);
  const float s = n[(axis + 1) % 3] / std::abs(major), t = n[(axis + 2) % 3] / std::abs(major);
  const auto cell_of = [cells](float x) { return std::clamp(static_cast<int>((x + 1.0f) * 0.5f * cells), 0, cells - 1); };
  return (face * cells + cell_of(s)) * cells + cell_of(t);
}
}  // namespace

FacingOrder facing_order(const Mesh& mesh, int cells_per_face) {
  const size_t count = mesh.triangles.size();
  const int cells = 6 * cells_per_face * cells_per_face, no_normal = cells;
  std::vector<int> cell(count);
  std::vector<Eigen::Vector3f> normal(count);
  for (size_t i = 0; i < count; ++i) {
    const Eigen::Vector3i& t = mesh.triangles[i];
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    const float length = n.norm();
    normal[i] = length > 0 && std::isfinite(length) ? Eigen::Vector3f(n / length) : Eigen::Vector3f::Zero();
    cell[i] = normal[i].isZero() ? no_normal : cube_cell(normal[i], cells_per_face);
  }
  FacingOrder result;
  result.order.resize(count);
  std::iota(result.order.begin(), result.order.end(), 0u);
  std::stable_sort(result.order.begin(), result.order.end(), [&](uint32_t x, uint32_t y) { return cell[x] < cell[y]; });
  result.bin_of.resize(count);
  for (size_t first = 0; first < count;) {
    size_t end = first;
    while (end < count && cell[result.order[end]] == cell[result.order[first]]) ++end;
    FacingBin bin;
    Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), high = -low, sum = Eigen::Vector3f::Zero();
    for (size_t i = first; i < end; ++i) {
      for (int corner = 0; corner < 3; ++corner) {
        const Eigen::Vector3f& p = mesh.vertices[mesh.triangles[result.order[i]][corner]];
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      sum += normal[result.order[i]];
    }
    bin.centre = 0.5f * (low + high);
    for (size_t i = first; i < end; ++i)
      for (int corner = 0; corner < 3; ++corner)
        bin.radius = std::max(bin.radius, (mesh.vertices[mesh.triangles[result.order[i]][corner]] - bin.centre).norm());
    // Rounded outward: the sphere a little larger, the cone a little wider than the floats found.
    bin.radius = bin.radius * (1.0f + 1e-5f) + 1e-7f;
    if (cell[result.order[first]] != no_normal && sum.norm() > 0) {
      bin.axis = sum.normalized();
      float least = 1.0f;
      for (size_t i = first; i < end; ++i) least = std::min(least, normal[result.order[i]].dot(bin.axis));
      bin.cos_half_angle = least - 1e-5f;
    }
    for (size_t i = first; i < end; ++i) result.bin_of[i] = static_cast<uint16_t>(result.bins.size());
    result.bins.push_back(bin);
    first = end;
  }
  return result;
}

// Every normal n lies within the cone (angle to axis at most theta), every corner p within the sphere:
// n . (p - camera) >= n . d - radius for d = centre - camera, and n . d >= |d| cos(phi + theta), phi the
// angle between axis and d, which is x cos(theta) - sqrt(|d|^2 - x^2) sin(theta) for x = axis . d (a lower
// bound also where phi + theta passes pi: it is negative there, and nothing is skipped).
bool bin_faces_away(const FacingBin& bin, const Eigen::Vector3f& camera) {
  if (!(bin.cos_half_angle > 0.0f)) return false;
  const Eigen::Vector3f d = bin.centre - camera;
  const float length_squared = d.dot(d), x = bin.axis.dot(d);
  const float sine = std::sqrt(std::max(0.0f, 1.0f - bin.cos_half_angle * bin.cos_half_angle));
  const float least = x * bin.cos_half_angle - std::sqrt(std::max(0.0f, length_squared - x * x)) * sine;
  return least > bin.radius + kFacingMargin * std::sqrt(length_squared);
}

std::vector<float> packed_bins(const std::vector<FacingBin>& bins) {
  std::vector<float> packed;
  packed.reserve(8 * bins.size());
  for (const FacingBin& b : bins)
    packed.insert(packed.end(), {b.centre.x(), b.centre.y(), b.centre.z(), b.radius, b.axis.x(), b.axis.y(),
                                 b.axis.z(), b.cos_half_angle});
  return packed;
}

}  // namespace depthtrack
