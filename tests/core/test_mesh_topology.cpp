// Whether a mesh bounds a solid wound outward (core/mesh_topology.hpp), which lets the rasterizers cull
// back faces: hand-built closed, open, inverted and broken meshes; the real scans; and the reference
// rasterizer's depths with and without culling.
#include <catch2/catch.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <random>
#include <vector>

#include "cli_support.hpp"
#include "core/mesh_simplify.hpp"
#include "core/mesh_topology.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {
Mesh inverted(Mesh mesh) {
  for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}
}  // namespace

TEST_CASE("a closed mesh wound outward bounds a solid; open, inverted or broken ones do not", "[topology]") {
  const Mesh box = make_box({0.1f, 0.2f, 0.3f});
  CHECK(bounds_solid_outward(box));
  CHECK(bounds_solid_outward(builtin_demo_mesh()));  // two boxes sharing a face's plane
  CHECK_FALSE(bounds_solid_outward(inverted(box)));  // closed, normals inward

  Mesh open = box;
  open.triangles.pop_back();  // a hole: three edges have no partner
  CHECK_FALSE(bounds_solid_outward(open));

  Mesh flipped_one = box;
  std::swap(flipped_one.triangles[3][1], flipped_one.triangles[3][2]);  // closed, wound inconsistently
  CHECK_FALSE(bounds_solid_outward(flipped_one));

  Mesh sheet;  // a single quad: every edge once
  sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  CHECK_FALSE(bounds_solid_outward(sheet));
  CHECK_FALSE(bounds_solid_outward(Mesh{}));

  // Two solids apart: each part is checked on its own.
  Mesh two = box;
  append_mesh(two, make_box({0.1f, 0.1f, 0.1f}, {1.0f, 0.0f, 0.0f}));
  CHECK(bounds_solid_outward(two));
  // A part wound inward beside one wound outward and larger: the total volume is positive, but the
  // inverted part would be drawn from behind, so no culling.
  Mesh mixed = make_box({0.5f, 0.5f, 0.5f});
  append_mesh(mixed, inverted(make_box({0.1f, 0.1f, 0.1f}, {2.0f, 0.0f, 0.0f})));
  CHECK_FALSE(bounds_solid_outward(mixed));

  Mesh out_of_range = box;
  out_of_range.triangles[0][0] = 8;
  CHECK_FALSE(bounds_solid_outward(out_of_range));
}

TEST_CASE("the real scans bound solids, as given and as the tracker simplifies them", "[topology]") {
  for (const char* name : {"ycb/009_gelatin_box.obj", "ycb/025_mug.obj", "ycb/061_foam_brick.obj",
                           "ycb/006_mustard_bottle.obj", "dbot/handset.obj"}) {
    const auto path = test::shared_data(std::string("meshes/") + name);
    if (!path) continue;
    INFO(name);
    const Mesh mesh = Mesh::load(*path);
    CHECK(bounds_solid_outward(mesh));
    for (const double error : {0.0005, 0.0015}) CHECK(bounds_solid_outward(simplify_for_drawing(mesh, error).mesh));
  }
}

TEST_CASE("culling a solid's back faces keeps every depth and triangle of the reference rasterizer", "[topology]") {
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const Mesh solid = builtin_demo_mesh();
  // The same solid with a sheet a kilometre away, beyond every far limit: never drawn, but the mesh is
  // open, so nothing is culled.
  Mesh with_sheet = solid;
  Mesh sheet;
  sheet.vertices = {{1000, 0, 0}, {1001, 0, 0}, {1000, 1, 0}};
  sheet.triangles = {{0, 1, 2}};
  append_mesh(with_sheet, sheet);
  const double near = 0.05, far = 10.0;
  const reference::Rasterizer culled(solid, camera, near, far), drawn_all(with_sheet, camera, near, far);
  REQUIRE(culled.culls_back_faces());
  REQUIRE_FALSE(drawn_all.culls_back_faces());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const size_t pixels = static_cast<size_t>(camera.pixel_count());
  std::vector<float> depth_culled(pixels), depth_all(pixels);
  std::vector<int> ids_culled(pixels), ids_all(pixels);
  int covered = 0;
  for (int i = 0; i < 200; ++i) {
    // Whole in front of the near plane (a solid cut open by it shows its inside only when not culled).
    const Pose pose({0.1 * unit(random), 0.08 * unit(random), 0.5 + 0.3 * unit(random)},
                    rotation_exp(Eigen::Vector3d(3 * unit(random), 3 * unit(random), 3 * unit(random))));
    culled.render(pose, depth_culled, ids_culled);
    drawn_all.render(pose, depth_all, ids_all);
    INFO("pose " << i);
    REQUIRE(depth_culled == depth_all);
    REQUIRE(ids_culled == ids_all);
    for (const float z : depth_culled) covered += z > 0;
  }
  CHECK(covered > 200 * 100);
}

TEST_CASE("track notes a mesh whose back faces cannot be culled, and says nothing of a closed one", "[topology][cli]") {
  const auto dir = test::write_cli_sequence("cli_topology_note", 2);
  const Mesh closed = make_box({0.1f, 0.08f, 0.06f});
  Mesh open = closed;
  open.triangles.pop_back();
  test::write_obj(dir / "closed.obj", closed);
  test::write_obj(dir / "open.obj", open);
  const auto run = [&](const std::string& mesh) {
    return test::run_cli("track --mesh " + (dir / mesh).string() + " --sequence " + (dir / "seq").string() +
                             " --resolution 80x60 --particles 20 --init-from-gt --out " + (dir / "out.csv").string(),
                         dir / ("log_" + mesh + ".txt"));
  };
  const auto [open_status, open_output] = run("open.obj");
  INFO(open_output);
  CHECK(open_status == 0);
  CHECK_THAT(open_output, Catch::Contains("does not bound a solid wound outward"));
  const auto [closed_status, closed_output] = run("closed.obj");
  INFO(closed_output);
  CHECK(closed_status == 0);
  CHECK_THAT(closed_output, !Catch::Contains("does not bound a solid"));
}
