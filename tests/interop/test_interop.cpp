// The atlas hand-offs (src/interop): each must deliver exactly the pixels GL rendered, every tile at
// the place cl/dt_atlas.h says, from poses that came from device memory.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <iostream>

#include "atlas/gl/atlas_renderer.hpp"
#include "compute/buffer.hpp"
#include "device_support.hpp"
#include "gl_support.hpp"
#include "interop/atlas_handoff.hpp"
#include "interop_support.hpp"

using namespace depthtrack;
using test::random_particles;
using test::through;

namespace {

const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);

}  // namespace

TEST_CASE("the staged hand-off delivers every page as GL rendered it, poses taken from device memory",
          "[device][render][interop]") {
  if (!test::device_available()) return;
  auto context = test::gl_context_or_skip();
  if (!context) return;
  auto queue = compute::open_device(test::device_selector());
  // 200 px pages: 2 tiles per row, 6 per page, so 14 poses fill two pages and part of a third.
  render::AtlasRenderer renderer(*context, builtin_demo_mesh(), camera, 0.05, 6.0, render::AtlasOptions{200});
  const auto particles = random_particles(14, 3);
  renderer.reserve(14);
  REQUIRE(renderer.layout().tiles_per_row == 2);
  REQUIRE(renderer.layout().pages.size() == 3);
  auto staged = interop::make_staged_handoff(*queue, renderer, "test");
  const std::vector<float> pages = through(*staged, *queue, renderer, particles);

  // Independently: the same poses given to GL from the host, read back tile by tile.
  std::vector<Pose> poses;
  for (const auto& p : particles) poses.push_back(p.pose);
  renderer.render(poses);
  std::vector<float> expected(14 * 4800);
  renderer.read_back(expected);
  const std::vector<float> got = renderer.layout().tiles_in_order(pages, 14);
  size_t covered = 0;
  for (size_t k = 0; k < expected.size(); ++k) {
    INFO("tile " << k / 4800 << " pixel " << k % 4800);
    REQUIRE(got[k] == expected[k]);
    covered += expected[k] > 0;
  }
  CHECK(covered > 14 * 100);  // the object is in view in every tile
}

// On NVIDIA (DEPTHTRACK_TEST_DEVICE=cuda or opencl:nvidia) the GL context is on the compute GPU and
// the best hand-off is a zero-copy one; it must deliver exactly what the staged copy delivers.
TEST_CASE("the platform's best hand-off is chosen and equals the staged copy", "[device][render][interop]") {
  if (!test::device_available()) return;
  auto queue = compute::open_device(test::device_selector());
  render::GlContextOptions options;
  options.device_uuid = queue->info().uuid;
  auto context = [&]() -> std::unique_ptr<render::GlContext> {
    try {
      return std::make_unique<render::GlContext>(options);
    } catch (const BackendError& e) {
      std::cout << "SKIPPED: no OpenGL context: " << e.what() << "\n";
      return nullptr;
    }
  }();
  if (!context) return;
  std::cout << "GL: " << context->describe() << "\n";
  render::AtlasRenderer renderer(*context, builtin_demo_mesh(), camera, 0.05, 6.0, render::AtlasOptions{200});
  renderer.reserve(14);
  auto best = interop::make_atlas_handoff(*queue, renderer);
  std::cout << queue->info().selector << " hand-off: " << best->name() << "\n";
  const bool nvidia_gl = context->describe().find("NVIDIA") != std::string::npos;
  if (nvidia_gl && queue->info().backend == "cuda") CHECK(best->name() == "CUDA-GL interop (zero-copy)");
  if (nvidia_gl && queue->info().backend == "opencl" && queue->info().platform.find("NVIDIA") != std::string::npos &&
      queue->info().external_memory)
    CHECK(best->name().rfind("GL-OpenCL bridge", 0) == 0);
  if (best->name().rfind("staged copy", 0) == 0) {
    std::cout << "SKIPPED: this platform has only the staged copy (tested above)\n";
    return;
  }
  const auto particles = random_particles(14, 4);
  const std::vector<float> zero_copy = through(*best, *queue, renderer, particles);
  auto staged = interop::make_staged_handoff(*queue, renderer, "test");
  const std::vector<float> copied = through(*staged, *queue, renderer, particles);
  REQUIRE(zero_copy == copied);
  size_t covered = 0;
  for (float d : zero_copy) covered += d > 0;
  CHECK(covered > 14 * 100);
}
