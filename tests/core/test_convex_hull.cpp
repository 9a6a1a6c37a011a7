// The convex hull's vertices (core/convex_hull.hpp) and the automatic state window sized from them,
// against hand-built point sets and against every vertex of real meshes projected by brute force.
#include <catch2/catch.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <random>

#include "core/convex_hull.hpp"
#include "model/state_window.hpp"
#include "support.hpp"

using namespace depthtrack;

TEST_CASE("the convex hull keeps a cube's corners and drops points inside it or on its faces", "[window]") {
  std::vector<Eigen::Vector3f> points;
  // Interior and face-centre points first, so that the corners' indices are not simply 0..7.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> inside(-0.9f, 0.9f);
  for (int i = 0; i < 50; ++i) points.emplace_back(inside(random), inside(random), inside(random));
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      Eigen::Vector3f centre = Eigen::Vector3f::Zero();
      centre[axis] = side;
      points.push_back(centre);
    }
  std::vector<int> corners;
  for (int i = 0; i < 8; ++i) {
    corners.push_back(static_cast<int>(points.size()));
    points.emplace_back((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f);
  }
  const auto hull = convex_hull_vertices(points);
  REQUIRE(hull);
  CHECK(*hull == corners);
}

TEST_CASE("the convex hull of points that span no volume is reported as none", "[window]") {
  CHECK_FALSE(convex_hull_vertices({}));
  CHECK_FALSE(convex_hull_vertices({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));  // fewer than 4
  // A flat square with its centre: all on the plane z = 0.
  CHECK_FALSE(convex_hull_vertices({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5f, 0.5f, 0}}));
  CHECK_FALSE(convex_hull_vertices({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}}));
  // The smallest solid: a tetrahedron, every point a vertex.
  const auto tetrahedron = convex_hull_vertices({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  REQUIRE(tetrahedron);
  CHECK(*tetrahedron == std::vector<int>{0, 1, 2, 3});
}

namespace {
// The automatic window sized from every vertex of the mesh: what the hull's vertices must reproduce.
model::ObjectExtent every_vertex(const Mesh& mesh) {
  model::ObjectExtent extent;
  extent.centre = mesh.centre().cast<double>();
  for (const auto& v : mesh.vertices) extent.bounding_points.push_back(v.cast<double>());
  return extent;
}
}  // namespace

TEST_CASE("the automatic window from the hull's vertices is the window from every vertex", "[window]") {
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  std::vector<std::pair<std::string, Mesh>> meshes{{"demo", builtin_demo_mesh()}};
  if (const auto mug = test::shared_data("meshes/ycb/025_mug.obj")) meshes.emplace_back("mug", Mesh::load(*mug));
  for (const auto& [name, mesh] : meshes) {
    INFO(name);
    const model::ObjectExtent hull = model::object_extent(mesh), all = every_vertex(mesh);
    CHECK(hull.bounding_points.size() >= 4);
    CHECK(hull.bounding_points.size() <= mesh.vertices.size());
    if (name == "mug") CHECK(hull.bounding_points.size() < mesh.vertices.size() / 4);  // worth the host's time
    // The bounding box's corners, as the window was sized before: never smaller.
    model::ObjectExtent box = all;
    box.bounding_points.clear();
    Eigen::Vector3d low = all.centre, high = all.centre;
    for (const auto& p : all.bounding_points) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    for (int c = 0; c < 8; ++c)
      box.bounding_points.emplace_back((c & 1) ? high.x() : low.x(), (c & 2) ? high.y() : low.y(),
                                       (c & 4) ? high.z() : low.z());
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), depth(0.25, 1.5);
    int narrower_than_the_box = 0;
    for (int i = 0; i < 500; ++i) {
      const Eigen::Quaterniond q =
          Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized();
      const double z = depth(random);
      const Pose pose({0.3 * z * unit(random), 0.2 * z * unit(random), z}, q);
      const auto from_hull = model::automatic_window_size(hull, pose, camera);
      const auto from_all = model::automatic_window_size(all, pose, camera);
      REQUIRE(from_hull.has_value() == from_all.has_value());
      if (!from_hull) continue;
      CHECK(*from_hull == *from_all);
      const auto from_box = model::automatic_window_size(box, pose, camera);
      REQUIRE(from_box);
      CHECK(from_box->width >= from_hull->width);
      CHECK(from_box->height >= from_hull->height);
      narrower_than_the_box += from_box->pixels() > from_hull->pixels();
    }
    CHECK(narrower_than_the_box > 100);
  }
}
