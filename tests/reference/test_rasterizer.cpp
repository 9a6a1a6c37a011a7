// The reference rasterizer against analytic depth: planes and boxes intersected ray by ray.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <depthtrack/error.hpp>
#include <vector>

#include "reference/rasterizer.hpp"

using namespace depthtrack;

namespace {
const Camera camera = Camera::make(64, 48, 60.0, 62.0, 31.5, 23.5);

Eigen::Vector3d ray(int u, int v) {
  return {(u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0};
}

// Depth z where the ray through pixel (u, v) enters the axis-aligned box [lo, hi] placed by pose;
// 0 if it misses (slab method, in the box's frame).
double box_depth(const Pose& pose, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int u, int v) {
  const Pose inv = pose.inverse();
  const Eigen::Vector3d origin = inv.translation, dir = inv.rotation * ray(u, v);
  double t_near = 0, t_far = 1e9;
  for (int k = 0; k < 3; ++k) {
    double t0 = (lo[k] - origin[k]) / dir[k], t1 = (hi[k] - origin[k]) / dir[k];
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
  }
  return t_near < t_far ? t_near : 0.0;  // dir has z = 1 in the camera frame, so t is the depth
}
}  // namespace

TEST_CASE("a tilted plane renders its analytic depth at every pixel", "[rasterizer]") {
  Mesh quad;
  quad.vertices = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Pose pose({0.1, -0.05, 1.5}, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0).normalized())));
  reference::Rasterizer r(quad, camera, 0.05, 10.0);
  std::vector<float> depth(camera.pixel_count());
  r.render(pose, depth);
  const Eigen::Vector3d normal = pose.rotation * Eigen::Vector3d::UnitZ();
  const double offset = normal.dot(pose.translation);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const double expected = offset / normal.dot(ray(u, v));  // plane n.x = d along the ray
      REQUIRE(depth[static_cast<size_t>(v * camera.width + u)] == Approx(expected).epsilon(1e-6));
    }
}

TEST_CASE("a rotated box renders the depth where each ray enters it", "[rasterizer]") {
  const Eigen::Vector3d size(0.3, 0.2, 0.25);
  const Mesh box = make_box(size.cast<float>());
  const Pose pose({0.02, 0.01, 1.2},
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, 1, 0.2).normalized())));
  reference::Rasterizer r(box, camera, 0.05, 10.0);
  std::vector<float> depth(camera.pixel_count());
  const auto covered_box = r.render(pose, depth);
  int covered = 0, compared = 0;
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const double expected = box_depth(pose, -size / 2, size / 2, u, v);
      const float got = depth[static_cast<size_t>(v * camera.width + u)];
      // Away from the silhouette (rays that clear the edge by a margin), coverage must agree.
      const bool near_edge = [&] {
        for (int dv = -1; dv <= 1; ++dv)
          for (int du = -1; du <= 1; ++du)
            if ((box_depth(pose, -size / 2, size / 2, u + du, v + dv) > 0) != (expected > 0)) return true;
        return false;
      }();
      if (got > 0) {
        ++covered;
        CHECK(u >= covered_box.u0);
        CHECK(u < covered_box.u1);
      }
      if (near_edge) continue;
      ++compared;
      if (expected == 0) {
        REQUIRE(got == 0.0f);
      } else {
        REQUIRE(got == Approx(expected).epsilon(1e-6));
      }
    }
  CHECK(covered > 200);
  CHECK(compared > 2000);
}

TEST_CASE("geometry nearer than the near plane is clipped, the rest keeps its depth", "[rasterizer]") {
  // A floor plane y = 0.1 receding from z = 0.01 to z = 3: its near part crosses the near plane.
  Mesh floor;
  floor.vertices = {{-2, 0.1f, 0.01f}, {2, 0.1f, 0.01f}, {2, 0.1f, 3}, {-2, 0.1f, 3}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  const double near = 0.5;
  reference::Rasterizer r(floor, camera, near, 10.0);
  std::vector<float> depth(camera.pixel_count());
  r.render(Pose(), depth);
  int clipped = 0, drawn = 0;
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const double dir_y = (v - camera.cy) / camera.fy;
      const float got = depth[static_cast<size_t>(v * camera.width + u)];
      if (dir_y <= 0) {  // rays at or above the horizon never meet the floor
        CHECK(got == 0.0f);
        continue;
      }
      const double z = 0.1 / dir_y;  // where the ray meets the floor
      if (z < near || z > 3.0) {
        CHECK(got == 0.0f);
        ++clipped;
      } else if (std::abs(u - camera.cx) / camera.fx * z < 1.9) {  // clear of the floor's side edges
        CHECK(got == Approx(z).epsilon(1e-6));
        ++drawn;
      }
    }
  CHECK(clipped > 0);
  CHECK(drawn > 0);
}

TEST_CASE("nothing behind the camera is drawn, and the output size is checked", "[rasterizer]") {
  const Mesh box = make_box({0.2f, 0.2f, 0.2f});
  reference::Rasterizer r(box, camera, 0.05, 10.0);
  std::vector<float> depth(camera.pixel_count(), 7.0f);
  const auto covered = r.render(Pose({0, 0, -1}, Eigen::Quaterniond::Identity()), depth);
  CHECK(covered.empty());
  for (float z : depth) REQUIRE(z == 0.0f);
  std::vector<float> wrong(10);
  CHECK_THROWS_AS(r.render(Pose(), wrong), InputError);
}

namespace {
// A bumpy closed sphere of rings x segments quads, with a second one inside poking through it: many
// triangles per pixel, depths that cross, and ties where the surfaces meet.
Mesh bumpy_spheres(int rings, int segments) {
  Mesh mesh;
  for (const float scale : {1.0f, 0.93f}) {
    const int first = static_cast<int>(mesh.vertices.size());
    for (int i = 0; i <= rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
        const double r = 0.05 * scale * (1.0 + 0.08 * std::sin(7 * phi) * std::sin(5 * theta));
        mesh.vertices.emplace_back(static_cast<float>(r * std::sin(theta) * std::cos(phi)),
                                   static_cast<float>(r * std::sin(theta) * std::sin(phi)),
                                   static_cast<float>(r * std::cos(theta)));
      }
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const int a = first + i * segments + j, b = first + i * segments + (j + 1) % segments;
        mesh.triangles.emplace_back(a, b, a + segments);
        mesh.triangles.emplace_back(b, b + segments, a + segments);
      }
  }
  return mesh;
}
}  // namespace

TEST_CASE("a render split over threads keeps the same depths and box, bit for bit", "[rasterizer]") {
  const Mesh mesh = bumpy_spheres(40, 80);  // 12,800 triangles
  const std::vector<Pose> poses = {
      Pose({0.01, -0.005, 0.3}, Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized()))),
      Pose({0.0, 0.0, 0.12}, Eigen::Quaterniond::Identity()),  // the near plane cuts it
      Pose({0.3, 0.2, 0.5}, Eigen::Quaterniond::Identity()),   // partly off the image
      Pose({0, 0, -1}, Eigen::Quaterniond::Identity())};       // behind the camera: nothing
  reference::Rasterizer plain(mesh, camera, 0.1, 10.0);
  std::vector<float> expected(camera.pixel_count()), got(camera.pixel_count());
  for (const int threads : {2, 3, 4}) {
    reference::Rasterizer split(mesh, camera, 0.1, 10.0);
    split.split_over(std::make_shared<ThreadPool>(threads));
    for (size_t p = 0; p < poses.size(); ++p) {
      CAPTURE(threads, p);
      const reference::PixelBox a = plain.render(poses[p], expected);
      const reference::PixelBox b = split.render(poses[p], got);
      CHECK((a.u0 == b.u0 && a.v0 == b.v0 && a.u1 == b.u1 && a.v1 == b.v1));
      CHECK(std::memcmp(expected.data(), got.data(), expected.size() * sizeof(float)) == 0);
      CHECK((p == 3) == a.empty());
    }
  }
}
