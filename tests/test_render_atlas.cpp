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

#include "reference/rasterizer.hpp"
#include "render/atlas_renderer.hpp"
#include "support.hpp"

using namespace depthtrack;
using render::AtlasRenderer;
using render::GlContext;
using render::GlPath;

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

// Random orientations, the mesh's centre at about `distance` in front of the camera.
std::vector<Pose> random_poses(const Mesh& mesh, int count, double distance, unsigned seed) {
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

// True when the GL depth at pixel (u, v) is that of a triangle whose projected edge passes within
// GL's sub-pixel precision (1/256 px on llvmpipe; 1/128 allowed) of the pixel centre: a tie the two
// rasterizers may break differently. Seen on grazing sliver triangles, whose depth changes by
// 0.1 mm within 0.001 px, which the 1 cm neighbour rule cannot see.
bool edge_tie(const Mesh& mesh, const Camera& camera, const Pose& pose, int u, int v, float gl) {
  const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Eigen::Vector3d p[3];
    Eigen::Vector2d s[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = pose.apply(mesh.vertices[static_cast<size_t>(t[k])].cast<double>());
      s[k] = camera.project(p[k]);
    }
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (std::abs(n.dot(p[0]) / n.dot(ray) - gl) > 1e-5 * gl) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = s[k], e = s[(k + 1) % 3] - a;
      const double distance = std::abs(e.x() * (v - a.y()) - e.y() * (u - a.x())) / e.norm();
      if (distance < 1.0 / 128) return true;
    }
  }
  return false;
}

// Compares one tile with the reference depth image (see the file comment for the rules).
void compare_tile(const Mesh& mesh, const Camera& camera, const Pose& pose, const std::vector<float>& ref,
                  const float* gl, Agreement& a) {
  const int w = camera.width, h = camera.height;
  auto at = [&](int u, int v) { return ref[static_cast<size_t>(v * w + u)]; };
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float r = at(u, v), g = gl[v * w + u];
      a.reference_covered += r > 0;
      bool smooth = true;
      const int du[] = {1, -1, 0, 0}, dv[] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const int nu = u + du[k], nv = v + dv[k];
        if (nu < 0 || nv < 0 || nu >= w || nv >= h) continue;
        const float n = at(nu, nv);
        smooth = smooth && (n > 0) == (r > 0) && std::abs(n - r) < 0.01f;
      }
      if (!smooth) {
        a.edge_mismatch += (r > 0) != (g > 0);
        continue;
      }
      ++a.compared;
      if ((r > 0) != (g > 0)) {
        ++a.coverage_mismatch;
        continue;
      }
      if (r == 0) continue;
      ++a.compared_covered;
      const double relative = std::abs(double(g) - double(r)) / double(r);
      if (relative > 1e-5 && edge_tie(mesh, camera, pose, u, v, g)) {
        ++a.edge_ties;
        continue;
      }
      a.max_relative = std::max(a.max_relative, relative);
      a.depth_mismatch += relative > 1e-5;
    }
}

Agreement compare(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses, AtlasRenderer& atlas,
                  double near = near_plane, double far = far_plane) {
  atlas.render(poses);
  std::vector<float> tiles(poses.size() * static_cast<size_t>(camera.pixel_count()));
  atlas.read_back(tiles);
  const reference::Rasterizer rasterizer(mesh, camera, near, far);
  std::vector<float> ref(static_cast<size_t>(camera.pixel_count()));
  Agreement a;
  for (size_t i = 0; i < poses.size(); ++i) {
    rasterizer.render(poses[i], ref);
    compare_tile(mesh, camera, poses[i], ref, tiles.data() + i * ref.size(), a);
  }
  return a;
}

// min_covered: the least fraction of the reference's covered pixels that must be compared.
void check(const Agreement& a, const std::string& what, double min_covered = 0.25) {
  std::cout << what << ": compared " << a.compared << " pixels (" << a.compared_covered << " covered of "
            << a.reference_covered << "), max relative depth difference " << a.max_relative << ", coverage mismatches "
            << a.coverage_mismatch << ", edge-pixel mismatches " << a.edge_mismatch << ", sub-pixel edge ties "
            << a.edge_ties << "\n";
  INFO(what);
  CHECK(a.coverage_mismatch == 0);
  CHECK(a.depth_mismatch == 0);
  CHECK(a.max_relative <= 1e-5);
  CHECK(a.edge_ties * 1000 <= a.compared_covered);  // ties are rare
  // A good part of the object is compared, not just background (steep faces of the small built-in
  // boxes exceed 1 cm per pixel, hence only a quarter).
  CHECK(double(a.compared_covered) > min_covered * double(a.reference_covered));
}

constexpr GlPath all_paths[] = {GlPath::EglDevice, GlPath::EglSurfaceless, GlPath::OSMesa};

}  // namespace

TEST_CASE("atlas of the built-in mesh equals the reference rasterizer", "[render]") {
  const Mesh mesh = builtin_demo_mesh();
  const auto poses = random_poses(mesh, 16, 0.8, 1);
  int paths_run = 0;
  for (GlPath path : all_paths) {
    auto context = context_or_skip(path);
    if (!context) continue;
    ++paths_run;
    const std::string name = GlContext::path_name(path);
    AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane);
    check(compare(mesh, camera80, poses, atlas), name + " built-in 80x60");
    // A near plane that cuts through the object: both clip at z = near.
    AtlasRenderer cut(*context, mesh, camera80, 0.78, far_plane);
    check(compare(mesh, camera80, poses, cut, 0.78, far_plane), name + " built-in, near plane at 0.78 m", 0.2);
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
      const auto poses = random_poses(mesh, 8, distance, 2);
      const std::string name = std::string(GlContext::path_name(path)) + " " + file;
      AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane);
      check(compare(mesh, camera80, poses, atlas), name + " 80x60");
      if (file == files[2]) {
        AtlasRenderer large(*context, mesh, camera160, near_plane, far_plane);
        check(compare(mesh, camera160, poses, large), name + " 160x120");
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
  const auto poses = random_poses(mesh, 10, 0.8, 3);
  // 160 pixels: 2 tiles per row, 2 rows per page, so 10 tiles make pages of 4, 4 and 2.
  AtlasRenderer atlas(*context, mesh, camera80, near_plane, far_plane, {.max_texture_size = 160});
  check(compare(mesh, camera80, poses, atlas), "paged atlas, 4 tiles per page");
  REQUIRE(atlas.pages().size() == 3);
  CHECK(atlas.layout().tiles_per_row == 2);
  CHECK(atlas.layout().tiles_per_page == 4);
  CHECK(atlas.pages()[1].layout.first_tile == 4);
  CHECK(atlas.pages()[2].layout.tile_count == 2);
  CHECK(atlas.pages()[2].layout.height == 60);
  CHECK(atlas.pages()[0].color_texture != atlas.pages()[1].color_texture);
  // Fewer poses next frame: the layout shrinks to one page and still matches.
  const std::vector<Pose> three(poses.begin(), poses.begin() + 3);
  check(compare(mesh, camera80, three, atlas), "paged atlas, re-laid out for 3 poses");
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
    options.max_buffer_texels = 10;  // stands in for GL_MAX_TEXTURE_BUFFER_SIZE
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
