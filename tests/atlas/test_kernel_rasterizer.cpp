// The compute-kernel atlas (cl/rasterize.cl, --renderer kernel) against the reference rasterizer,
// pixel by pixel, then in the device filter against the host atlas. Away from edges (the pixel and
// its 4 neighbours all covered or all uncovered in the reference, depths within 1 cm) coverage must be
// identical and depth equal to float tolerance, as for GL (tests/atlas/test_render_atlas.cpp); at
// silhouettes float and double may differ: counted and bounded.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas_agreement.hpp"
#include "compute/buffer.hpp"
#include "device_support.hpp"
#include "model/particle_packing.hpp"
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

// Random poses rounded to the float state the kernel reads, so that both rasterizers draw the very
// same pose.
std::vector<Pose> random_poses(const Mesh& mesh, int count, double distance, unsigned seed) {
  std::vector<model::ParticleState> states;
  for (const Pose& pose : test::random_poses(mesh, count, distance, seed)) {
    states.emplace_back();
    states.back().pose = pose;
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
  config.renderer = Renderer::Kernel;
  config.particles = static_cast<int>(poses.size());
  config.near_plane = near;
  config.observation.max_depth = far;
  compute::ProgramCache programs(*queue);
  auto source = make_atlas_source(programs, mesh, camera, config);
  std::vector<model::ParticleState> states(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) states[i].pose = poses[i];
  compute::Buffer<float> state(*queue, states.size() * DT_STATE_STRIDE);
  state.upload(pack_particles(states));
  compute::Buffer<float> atlas(*queue, source->layout().floats());
  StepTimings timings;
  // Drawn on the queue: its device time comes from the event, as the filter reads it.
  if (const compute::EventPtr drawn = source->draw(state, atlas, timings)) timings.render_ms += drawn->elapsed_ms();
  CHECK(timings.render_ms > 0);
  CHECK(timings.handoff_ms == 0);
  return atlas.download();
}

// Draws the poses with the kernel, compares them with the reference; prints and checks the agreement.
void check_against_reference(const Mesh& mesh, const Camera& camera, const std::vector<Pose>& poses,
                             const std::string& what, double near = 0.05, double far = 10.0,
                             double min_covered = 0.25) {
  // Float edge functions: ties within 1e-3 px may break either way.
  const test::Agreement a =
      test::compare_with_rasterizer(mesh, camera, poses, kernel_atlas(mesh, camera, poses, near, far), near, far, 1e-3);
  test::check_agreement(a, what, min_covered);
  INFO(what);
  CHECK(a.edge_mismatch * 1000 <= a.reference_covered);  // silhouette flips are rare
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
  config.renderer = renderer_from_string("kernel");
  CHECK(config.renderer == Renderer::Kernel);
  CHECK_NOTHROW(config.validate());
  CHECK_THROWS_WITH(renderer_from_string("vulkan"), Catch::Contains("cpu, gl or kernel"));
  if (!test::device_available()) return;
  auto queue = compute::open_device(test::device_selector());
  config.renderer = Renderer::Kernel;
  config.particles = 4;
  compute::ProgramCache programs(*queue);
  const auto source = make_atlas_source(programs, builtin_demo_mesh(), camera80, config);
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

TEST_CASE("Poses that project far beyond int's range draw nothing, at once, in the kernel and the reference",
          "[kernels][robustness]") {
  // Vertices at u ~ 1e9 .. 1e16 pixels: a conversion to int without clamping is undefined there
  // (PoCL looped over 2^31 columns per triangle).
  const Mesh mesh = builtin_demo_mesh();
  std::vector<Pose> poses;
  for (const Eigen::Vector3d& t : {Eigen::Vector3d(1e7, 0, 0.06), Eigen::Vector3d(-1e7, 0, 0.06),
                                   Eigen::Vector3d(0, 1e12, 0.06), Eigen::Vector3d(-3e9, -3e9, 0.2)})
    poses.emplace_back(t, Eigen::Quaterniond::Identity());
  const reference::Rasterizer rasterizer(mesh, camera80, 0.05, 10.0);
  std::vector<float> depth(static_cast<size_t>(camera80.pixel_count()));
  for (const Pose& pose : poses) {
    INFO("translation " << pose.translation.transpose());
    CHECK(rasterizer.render(pose, depth).empty());
    CHECK(std::count(depth.begin(), depth.end(), 0.0f) == camera80.pixel_count());
  }
  if (!test::device_available()) return;
  const std::vector<float> atlas = kernel_atlas(mesh, camera80, poses, 0.05, 10.0);
  CHECK(std::count(atlas.begin(), atlas.end(), 0.0f) == static_cast<std::ptrdiff_t>(atlas.size()));
}
