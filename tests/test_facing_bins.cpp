// Facing bins (src/core/facing_bins.hpp): a bin said to face away from a camera holds only triangles that
// camera sees from behind, checked triangle by triangle in double, and on a closed mesh seen from outside
// about half the triangles go in such bins.
#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <cmath>
#include <random>

#include "core/facing_bins.hpp"
#include "core/mesh_topology.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {
// How far (metres) the camera lies behind triangle t's plane, in double: positive where it sees the back.
double behind(const Mesh& mesh, uint32_t t, const Eigen::Vector3d& camera) {
  const Eigen::Vector3i& c = mesh.triangles[t];
  const Eigen::Vector3d a = mesh.vertices[c[0]].cast<double>(), b = mesh.vertices[c[1]].cast<double>(),
                        p = mesh.vertices[c[2]].cast<double>();
  const Eigen::Vector3d n = (b - a).cross(p - a).normalized();
  return std::min({n.dot(a - camera), n.dot(b - camera), n.dot(p - camera)});
}

// Cameras around the mesh, 0.3 to 2 m from its centre in every direction.
std::vector<Eigen::Vector3f> cameras_around(const Mesh& mesh, int count) {
  std::mt19937 rng(3);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> distance(0.3f, 2.0f);
  std::vector<Eigen::Vector3f> cameras;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3f direction(normal(rng), normal(rng), normal(rng));
    cameras.push_back(mesh.centre() + distance(rng) * direction.normalized());
  }
  return cameras;
}
}  // namespace

TEST_CASE("A facing bin skipped for a camera holds only triangles that camera sees from behind", "[facing]") {
  std::vector<std::pair<std::string, Mesh>> meshes = {{"built-in box", builtin_demo_mesh()}};
  for (const char* name : {"meshes/ycb/025_mug.obj", "meshes/dbot/handset.obj"})
    if (const auto path = test::shared_data(name)) meshes.emplace_back(name, Mesh::load(*path));
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    REQUIRE(bounds_solid_outward(mesh));
    const FacingOrder order = facing_order(mesh);
    // A permutation of the triangles, each bin's a contiguous run, at most kMostFacingBins bins.
    REQUIRE(order.order.size() == mesh.triangles.size());
    std::vector<int> seen(mesh.triangles.size(), 0);
    for (uint32_t t : order.order) ++seen.at(t);
    CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    CHECK(order.bins.size() <= kMostFacingBins);
    CHECK(std::is_sorted(order.bin_of.begin(), order.bin_of.end()));
    CHECK(static_cast<size_t>(order.bin_of.back()) + 1 == order.bins.size());
    size_t skipped = 0, tested = 0;
    for (const Eigen::Vector3f& camera : cameras_around(mesh, 200)) {
      std::vector<bool> away(order.bins.size());
      for (size_t b = 0; b < order.bins.size(); ++b) away[b] = bin_faces_away(order.bins[b], camera);
      for (size_t i = 0; i < order.order.size(); ++i) {
        ++tested;
        if (!away[order.bin_of[i]]) continue;
        ++skipped;
        // Behind its plane by more than the margin's share of the distance to its bin (half of it, for floats).
        const double depth = behind(mesh, order.order[i], camera.cast<double>());
        INFO("triangle " << order.order[i] << ", camera " << camera.transpose() << ": " << depth << " m behind");
        const double distance = (order.bins[order.bin_of[i]].centre - camera).cast<double>().norm();
        REQUIRE(depth > 0.5 * kFacingMargin * distance);
      }
    }
    const double share = static_cast<double>(skipped) / static_cast<double>(tested);
    std::printf("%s: %zu triangles in %zu facing bins, %.0f %% skipped over 200 cameras\n", name.c_str(),
                mesh.triangles.size(), order.bins.size(), 100 * share);
    // A closed mesh shows about half its triangles' backs: the bins find most of them.
    CHECK(share > 0.2);
    CHECK(share < 0.55);
  }
}

TEST_CASE("A bin without a normal, or wider than a half turn, is never skipped", "[facing]") {
  FacingBin bin;  // the default: cos_half_angle -1 (triangles without a normal)
  bin.centre = Eigen::Vector3f(0, 0, 1);
  bin.radius = 0.01f;
  CHECK_FALSE(bin_faces_away(bin, Eigen::Vector3f::Zero()));
  bin.axis = Eigen::Vector3f(0, 0, 1);  // normals pointing away from a camera at the origin
  bin.cos_half_angle = 0.99f;
  CHECK(bin_faces_away(bin, Eigen::Vector3f::Zero()));
  CHECK_FALSE(bin_faces_away(bin, Eigen::Vector3f(0, 0, 2)));  // the camera on their side
  bin.cos_half_angle = 0.0f;                                      // a half turn wide
  CHECK_FALSE(bin_faces_away(bin, Eigen::Vector3f::Zero()));
  // Seen edge-on within the margin: not skipped.
  bin.cos_half_angle = 1.0f;
  bin.radius = 0;
  bin.axis = Eigen::Vector3f(1, 0, 0.5f * kFacingMargin).normalized();
  CHECK_FALSE(bin_faces_away(bin, Eigen::Vector3f::Zero()));
}
