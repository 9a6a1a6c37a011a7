// The compute-kernel atlas (cl/rasterize.cl, --renderer kernel) against the reference rasterizer,
// pixel by pixel, then in the device filter against the host atlas. Away from edges (the pixel and
// its 4 neighbours all covered or all uncovered in the reference, depths within 1 cm) coverage must be
// identical and depth equal to float tolerance, as for GL (tests/test_render_atlas.cpp); at
// silhouettes float and double may differ: counted and bounded.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "compute/buffer.hpp"
#include "device_support.hpp"
#include "filter/atlas_source.hpp"
#include "filter/particle_packing.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"
#if defined(DEPTHTRACK_WITH_CUDA)
#include "compute/cuda/cuda_program.hpp"
#include "compute/kernel_sources.hpp"
#endif

using namespace depthtrack;

namespace {

const Camera camera80 = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
const Camera camera160 = Camera::make(160, 120, 131.25, 131.25, 79.9375, 59.9375);

// Random orientations, the mesh's centre at about `distance` in front of the camera; rounded to the
// float state the kernel reads, so that both rasterizers draw the very same pose.
std::vector<Pose> random_poses(const Mesh& mesh, int count, double distance, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> offset(-0.06, 0.06);
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  std::vector<reference::ParticleState> states(static_cast<size_t>(count));
  for (auto& s : states) {
    const Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    const Eigen::Vector3d at(offset(rng) * distance, offset(rng) * distance, distance * (1 + offset(rng)));
    s.pose = Pose(at - q.normalized() * centre, q);
  }
  std::vector<Pose> poses;
  for (const auto& s : unpack_particles(pack_particles(states))) poses.push_back(s.pose);
  return poses;
}

// The kernel's atlas of the poses, tile i = pose i.
std::vector<float> kernel_atlas(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses, double near,
                                double far) {
  auto queue = compute::open_device(test::device_selector());
  TrackerConfig config;
  config.renderer = "kernel";
  config.particles = static_cast<int>(poses.size());
  config.near_plane = near;
  config.observation.max_depth = far;
  auto source = make_atlas_source(*queue, mesh, camera, config);
  std::vector<reference::ParticleState> states(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) states[i].pose = poses[i];
  compute::Buffer<float> state(*queue, states.size() * DT_STATE_STRIDE);
  state.upload(pack_particles(states));
  compute::Buffer<float> atlas(*queue, source->layout().floats());
  StepTimings timings;
  source->draw(state, atlas, timings);
  CHECK(timings.render_ms > 0);
  CHECK(timings.handoff_ms == 0);
  return atlas.download();
}

struct Agreement {
  long compared = 0, compared_covered = 0, reference_covered = 0;
  long coverage_mismatch = 0, depth_mismatch = 0, edge_mismatch = 0, edge_ties = 0;
  double max_relative = 0;
};

// True when the kernel's depth at pixel (u, v) is that of a triangle whose projected edge passes
// within float rounding (1e-3 px allowed) of the pixel centre: a tie float and double may break
// differently, which the 1 cm neighbour rule cannot see on grazing slivers.
bool edge_tie(const Mesh& mesh, const Camera& camera, const Pose& pose, int u, int v, float depth) {
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
      if (std::abs(e.x() * (v - a.y()) - e.y() * (u - a.x())) / e.norm() < 1e-3) return true;
    }
  }
  return false;
}

void compare_tile(const Mesh& mesh, const Camera& camera, const Pose& pose, const std::vector<float>& ref,
                  const float* tile, Agreement& a) {
  const int w = camera.width, h = camera.height;
  auto at = [&](int u, int v) { return ref[static_cast<size_t>(v * w + u)]; };
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float r = at(u, v), k = tile[v * w + u];
      a.reference_covered += r > 0;
      bool smooth = true;
      const int du[] = {1, -1, 0, 0}, dv[] = {0, 0, 1, -1};
      for (int n = 0; n < 4; ++n) {
        const int nu = u + du[n], nv = v + dv[n];
        if (nu < 0 || nv < 0 || nu >= w || nv >= h) continue;
        smooth = smooth && (at(nu, nv) > 0) == (r > 0) && std::abs(at(nu, nv) - r) < 0.01f;
      }
      if (!smooth) {
        a.edge_mismatch += (r > 0) != (k > 0);
        continue;
      }
      ++a.compared;
      if ((r > 0) != (k > 0)) {
        ++a.coverage_mismatch;
        continue;
      }
      if (r == 0) continue;
      ++a.compared_covered;
      const double relative = std::abs(double(k) - double(r)) / double(r);
      if (relative > 1e-5 && edge_tie(mesh, camera, pose, u, v, k)) {
        ++a.edge_ties;
        continue;
      }
      a.max_relative = std::max(a.max_relative, relative);
      a.depth_mismatch += relative > 1e-5;
    }
}

// Draws the poses with the kernel, compares them with the reference; prints and checks the agreement.
void check_against_reference(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses,
                             const std::string& what, double near = 0.05, double far = 10.0,
                             double min_covered = 0.25) {
  INFO(what);
  const std::vector<float> atlas = kernel_atlas(mesh, camera, poses, near, far);
  const reference::Rasterizer rasterizer(mesh, camera, near, far);
  std::vector<float> ref(static_cast<size_t>(camera.pixel_count()));
  Agreement a;
  for (size_t i = 0; i < poses.size(); ++i) {
    rasterizer.render(poses[i], ref);
    compare_tile(mesh, camera, poses[i], ref, atlas.data() + i * ref.size(), a);
  }
  std::printf(
      "%s: compared %ld pixels (%ld covered of %ld), max relative depth difference %.3g, coverage mismatches %ld, "
      "edge-pixel mismatches %ld, sub-pixel edge ties %ld\n",
      what.c_str(), a.compared, a.compared_covered, a.reference_covered, a.max_relative, a.coverage_mismatch,
      a.edge_mismatch, a.edge_ties);
  CHECK(a.coverage_mismatch == 0);
  CHECK(a.depth_mismatch == 0);
  CHECK(a.max_relative <= 1e-5);
  CHECK(a.edge_ties * 1000 <= a.compared_covered);
  CHECK(a.edge_mismatch * 1000 <= a.reference_covered);  // silhouette flips are rare
  CHECK(double(a.compared_covered) > min_covered * double(a.reference_covered));
}

}  // namespace

TEST_CASE("kernel atlas of real meshes equals the reference rasterizer", "[device][render][kernel]") {
  if (!test::device_available()) return;
  const char* files[] = {"meshes/dbot/handset.obj", "meshes/ycb/006_mustard_bottle.obj",
                         "meshes/stanford/bunny-69451.obj"};
  int meshes = 0;
  for (const char* file : files) {
    const auto path = test::shared_data(file);
    if (!path) continue;
    ++meshes;
    const Mesh mesh = Mesh::load(*path);
    // Close enough that the object spans about two thirds of the image height.
    const auto poses = random_poses(mesh, 50, std::max(0.3, camera80.fx * mesh.radius() / 20.0), 2);
    check_against_reference(mesh, camera80, poses, std::string(file) + " 80x60");
    check_against_reference(mesh, camera160, poses, std::string(file) + " 160x120");
  }
  if (meshes == 0) std::printf("SKIPPED: no mesh of ../shared/data found\n");
}

TEST_CASE("kernel atlas clips at the near plane and discards beyond the far plane", "[device][render][kernel]") {
  if (!test::device_available()) return;
  const Mesh mesh = builtin_demo_mesh();
  const auto poses = random_poses(mesh, 16, 0.8, 1);
  check_against_reference(mesh, camera80, poses, "built-in 80x60", 0.05, 10.0);
  check_against_reference(mesh, camera80, poses, "built-in, near plane at 0.78 m", 0.78, 10.0, 0.2);
  check_against_reference(mesh, camera80, poses, "built-in, far plane at 0.8 m", 0.05, 0.8, 0.2);
}

TEST_CASE("kernel renderer is a valid choice and says where it draws", "[device][kernel]") {
  TrackerConfig config;
  config.renderer = "kernel";
  CHECK_NOTHROW(config.validate());
  config.renderer = "vulkan";
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("cpu, gl or kernel"));
  if (!test::device_available()) return;
  auto queue = compute::open_device(test::device_selector());
  config.renderer = "kernel";
  config.particles = 4;
  const auto source = make_atlas_source(*queue, builtin_demo_mesh(), camera80, config);
  CHECK_THAT(source->description(), Catch::Contains("compute-kernel rasterizer on " + queue->info().name));
  CHECK(source->layout() == render::AtlasLayout::particle_major(4, 80, 60));
}

#if defined(DEPTHTRACK_WITH_CUDA)
TEST_CASE("rasterize.cl compiles as CUDA", "[cuda][kernel]") {
  const std::string reason = compute::cuda::nvrtc_unavailable_reason();
  if (!reason.empty()) {
    std::printf("SKIPPED: %s\n", reason.c_str());
    return;
  }
  const std::string ptx =
      compute::cuda::compile_to_ptx(compute::kernel_source("rasterize.cl"), {"DT_GROUP_SIZE=128"}, 90);
  CHECK(ptx.find(".entry rasterize") != std::string::npos);
  CHECK(ptx.find(".global.min.u32") != std::string::npos);  // the atomic minimum (atom or red)
}
#endif
