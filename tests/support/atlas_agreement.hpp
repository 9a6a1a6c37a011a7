#pragma once
// Comparing a rendered pose atlas (GL or the compute kernel) with the reference rasterizer, pixel by
// pixel. Away from edges (the pixel and its 4 neighbours all covered or all uncovered in the
// reference, depths within 1 cm) coverage must be identical and depth equal to float tolerance; at
// edges, where float vs double and sub-pixel rules may legitimately differ, mismatches are counted.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/mesh.hpp>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "reference/rasterizer.hpp"

namespace depthtrack::test {

// Random orientations, the mesh's centre at about `distance` in front of the camera.
inline std::vector<Pose> random_poses(const Mesh& mesh, int count, double distance, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> offset(-0.06, 0.06);
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  std::vector<Pose> poses;
  for (int i = 0; i < count; ++i) {
    const Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Vector3d at(offset(rng) * distance, offset(rng) * distance, distance * (1 + offset(rng)));
    poses.emplace_back(at - q.normalized() * centre, q);
  }
  return poses;
}

struct Agreement {
  long compared = 0, compared_covered = 0, reference_covered = 0;
  long coverage_mismatch = 0, depth_mismatch = 0, edge_mismatch = 0, edge_ties = 0;
  double max_relative = 0;
};

// True when the rendered depth at pixel (u, v) is that of a triangle whose projected edge passes
// within `tie_px` of the pixel centre: a tie the two rasterizers may break differently. Seen on
// grazing sliver triangles, whose depth changes by 0.1 mm within 0.001 px, which the 1 cm
// neighbour rule cannot see.
inline bool edge_tie(const Mesh& mesh, const Camera& camera, const Pose& pose, int u, int v, float depth,
                     double tie_px) {
  const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Eigen::Vector3d p[3];
    Eigen::Vector2d s[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = pose.apply(mesh.vertices[static_cast<size_t>(t[k])].cast<double>());
      s[k] = camera.project(p[k]);
    }
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (std::abs(n.dot(p[0]) / n.dot(ray) - depth) > 1e-5 * depth) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = s[k], e = s[(k + 1) % 3] - a;
      if (std::abs(e.x() * (v - a.y()) - e.y() * (u - a.x())) / e.norm() < tie_px) return true;
    }
  }
  return false;
}

inline void compare_tile(const Mesh& mesh, const Camera& camera, const Pose& pose, const std::vector<float>& ref,
                         const float* tile, double tie_px, Agreement& a) {
  const int w = camera.width, h = camera.height;
  auto at = [&](int u, int v) { return ref[static_cast<size_t>(v * w + u)]; };
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float r = at(u, v), d = tile[v * w + u];
      a.reference_covered += r > 0;
      bool smooth = true;
      const int du[] = {1, -1, 0, 0}, dv[] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const int nu = u + du[k], nv = v + dv[k];
        if (nu < 0 || nv < 0 || nu >= w || nv >= h) continue;
        smooth = smooth && (at(nu, nv) > 0) == (r > 0) && std::abs(at(nu, nv) - r) < 0.01f;
      }
      if (!smooth) {
        a.edge_mismatch += (r > 0) != (d > 0);
        continue;
      }
      ++a.compared;
      if ((r > 0) != (d > 0)) {
        ++a.coverage_mismatch;
        continue;
      }
      if (r == 0) continue;
      ++a.compared_covered;
      const double relative = std::abs(double(d) - double(r)) / double(r);
      if (relative > 1e-5 && edge_tie(mesh, camera, pose, u, v, d, tie_px)) {
        ++a.edge_ties;
        continue;
      }
      a.max_relative = std::max(a.max_relative, relative);
      a.depth_mismatch += relative > 1e-5;
    }
}

// `tiles`: one width x height tile per pose, in pose order.
inline Agreement compare_with_rasterizer(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses,
                                         const std::vector<float>& tiles, double near, double far, double tie_px) {
  const reference::Rasterizer rasterizer(mesh, camera, near, far);
  std::vector<float> ref(static_cast<size_t>(camera.pixel_count()));
  Agreement a;
  for (size_t i = 0; i < poses.size(); ++i) {
    rasterizer.render(poses[i], ref);
    compare_tile(mesh, camera, poses[i], ref, tiles.data() + i * ref.size(), tie_px, a);
  }
  return a;
}

// Prints the agreement and checks it. min_covered: the least fraction of the reference's covered
// pixels that must be compared (steep faces of the small built-in boxes exceed 1 cm per pixel).
inline void check_agreement(const Agreement& a, const std::string& what, double min_covered = 0.25) {
  std::cout << what << ": compared " << a.compared << " pixels (" << a.compared_covered << " covered of "
            << a.reference_covered << "), max relative depth difference " << a.max_relative << ", coverage mismatches "
            << a.coverage_mismatch << ", edge-pixel mismatches " << a.edge_mismatch << ", sub-pixel edge ties "
            << a.edge_ties << "\n";
  INFO(what);
  CHECK(a.coverage_mismatch == 0);
  CHECK(a.depth_mismatch == 0);
  CHECK(a.max_relative <= 1e-5);
  CHECK(a.edge_ties * 1000 <= a.compared_covered);  // ties are rare
  CHECK(double(a.compared_covered) > min_covered * double(a.reference_covered));
}

}  // namespace depthtrack::test
