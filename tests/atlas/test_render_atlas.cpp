// The GL pose atlas against the reference rasterizer, pixel by pixel, on every GL path here.
// Away from edges (the pixel and its 4 neighbours all covered or all uncovered in the reference,
// depths within 1 cm) coverage must be identical and depth equal to float tolerance; at edges,
// where float vs double and the two rasterizers' sub-pixel rules may legitimately differ, the
// mismatches are only counted and printed.
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

#include "atlas/gl/atlas_renderer.hpp"
#include "atlas_agreement.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"

using namespace depthtrack;
using render::AtlasRenderer;
using render::GlContext;
using render::GlPath;
using test::Agreement;

namespace {

const Camera camera80 = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
constexpr double near_plane = 0.05, far_plane = 10.0;

// A context on that path, or nullptr with a note. A test that gets no context on any path says
// SKIPPED (skipped_if_none): one missing path (OSMesa on a GPU machine) must not hide the others.
std::unique_ptr<GlContext> context_or_skip(GlPath path) {
  try {
    render::GlContextOptions options;
    options.path = path;
    return std::make_unique<GlContext>(options);
  } catch (const BackendError& e) {
    std::cout << "note: " << GlContext::path_name(path) << " unavailable: " << e.what() << "\n";
    return nullptr;
  }
}

void skipped_if_none(int paths_run) {
  if (paths_run == 0) std::cout << "SKIPPED: no headless GL path could be opened\n";
}

// GL's sub-pixel precision is 1/256 px on llvmpipe: ties within 1/128 px may break either way.
Agreement compare(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses, AtlasRenderer& atlas,
                  double near = near_plane, double far = far_plane) {
  atlas.render(poses);
  std::vector<float> tiles(poses.size() * static_cast<size_t>(camera.pixel_count()));
  atlas.read_back(tiles);
  return test::compare_with_rasterizer(mesh, camera, poses, tiles, near, far, 1.0 / 128);
}

constexpr GlPath all_paths[] = {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa};

}  // namespace

TEST_CASE("atlas of the built-in mesh equals the reference rasterizer", "[render]") {
  const Mesh mesh = builtin_demo_mesh();
  const auto poses = test::random_poses(mesh, 16, 0.8, 1);
  int paths_run = 0;
  for (GlPath path : all_paths) {
    auto context = context_or_skip(path);
    if (!context) continue;
    ++paths_run;
    const std::string name = GlContext::path_name(path);
    AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane);
    test::check_agreement(compare(mesh, camera80, poses, atlas), name + " built-in 80x60");
    // A near plane that cuts through the object: both clip at z = near.
    AtlasRenderer cut(*context, mesh, camera80, 0.78, far_plane);
    test::check_agreement(compare(mesh, camera80, poses, cut, 0.78, far_plane),
                          name + " built-in, near plane at 0.78 m", 0.2);
  }
}

TEST_CASE("atlas of real meshes equals the reference rasterizer", "[render]") {
  const char* files[] = {"meshes/dbot/handset.obj", "meshes/ycb/006_mustard_bottle.obj",
                         "meshes/stanford/bunny-69451.obj"};
  std::vector<std::pair<std::string, Mesh>> meshes;
  for (const char* file : files)
    if (const auto path = test::shared_data(file)) meshes.emplace_back(file, Mesh::load(*path));
  if (meshes.empty()) return;
  const Camera camera160 = Camera::make(160, 120, 131.25, 131.25, 79.9375, 59.9375);
  int paths_run = 0;
  for (GlPath path : all_paths) {
    auto context = context_or_skip(path);
    if (!context) continue;
    ++paths_run;
    for (const auto& [file, mesh] : meshes) {
      // Close enough that the object spans about two thirds of the image height.
      const double distance = std::max(0.3, camera80.fx * mesh.radius() / 20.0);
      const auto poses = test::random_poses(mesh, 8, distance, 2);
      const std::string name = std::string(GlContext::path_name(path)) + " " + file;
      AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane);
      test::check_agreement(compare(mesh, camera80, poses, atlas), name + " 80x60");
      if (file == files[2]) {
        AtlasRenderer large(*context, mesh, camera160, near_plane, far_plane);
        test::check_agreement(compare(mesh, camera160, poses, large), name + " 160x120");
      }
    }
  }
  skipped_if_none(paths_run);
}

TEST_CASE("atlas pages split at the texture limit and later pages equal the reference", "[render]") {
  auto context = context_or_skip(GlPath::EglSurfaceless);
  if (!context) context = context_or_skip(GlPath::OSMesa);
  if (!context) return skipped_if_none(0);
  const Mesh mesh = builtin_demo_mesh();
  const auto poses = test::random_poses(mesh, 10, 0.8, 3);
  // 160 pixels: 2 tiles per row, 2 rows per page, so 10 tiles make pages of 4, 4 and 2.
  AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane, {.max_texture_size = 160});
  test::check_agreement(compare(mesh, camera80, poses, atlas), "paged atlas, 4 tiles per page");
  REQUIRE(atlas.pages().size() == 3);
  CHECK(atlas.layout().tiles_per_row == 2);
  CHECK(atlas.layout().tiles_per_page == 4);
  CHECK(atlas.pages()[1].layout.first_tile == 4);
  CHECK(atlas.pages()[2].layout.tile_count == 2);
  CHECK(atlas.pages()[2].layout.height == 60);
  CHECK(atlas.pages()[0].color_texture != atlas.pages()[1].color_texture);
  // Fewer poses next frame: the layout shrinks to one page and still matches.
  const std::vector<Pose> three(poses.begin(), poses.begin() + 3);
  test::check_agreement(compare(mesh, camera80, three, atlas), "paged atlas, re-laid out for 3 poses");
  CHECK(atlas.pages().size() == 1);
  std::vector<float> wrong(5);
  CHECK_THROWS_AS(atlas.read_back(wrong), InputError);
}

TEST_CASE("a mesh or a pose count beyond the GL's buffer limit is refused naming the limit", "[render][errors]") {
  int paths_run = 0;
  for (auto path : {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa}) {
    auto context = context_or_skip(path);
    if (!context) continue;
    ++paths_run;
    render::AtlasOptions options;
    options.max_buffer_texels = 10;                                // stands in for GL_MAX_TEXTURE_BUFFER_SIZE
    const Mesh box = make_box(Eigen::Vector3f(0.1f, 0.1f, 0.1f));  // 12 triangles
    CHECK_THROWS_WITH(AtlasRenderer(*context, box, camera80, near_plane, far_plane, options),
                      Catch::Contains("the mesh has 12 triangles, more than this GL can draw") &&
                          Catch::Contains("GL_MAX_TEXTURE_BUFFER_SIZE 10"));
    options.max_buffer_texels = 12;  // the mesh fits; 4 texels a pose: 3 poses fit, 4 do not
    AtlasRenderer renderer(*context, box, camera80, near_plane, far_plane, options);
    renderer.reserve(3);
    CHECK_THROWS_WITH(renderer.reserve(4), Catch::Contains("4 poses exceed this GL's pose buffer"));
  }
  skipped_if_none(paths_run);
}
