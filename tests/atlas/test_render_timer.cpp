// GL's draw timed by GL_TIME_ELAPSED queries (atlas/gl/gl_draw_timer.hpp) and reported by the device
// filter after the frame's wait: a real, positive time that fits inside the host's wall time around it.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <iostream>

#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_draw_timer.hpp"
#include "atlas_agreement.hpp"
#include "core/stopwatch.hpp"
#include "device_support.hpp"
#include "filter/device_filter.hpp"
#include "gl_support.hpp"

using namespace depthtrack;

namespace {

const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);

}  // namespace

TEST_CASE("a GL timer query times the atlas draw, positive and no longer than the host's wall time around it",
          "[render][timer]") {
  auto context = test::gl_context_or_skip();
  if (!context) return;
  render::AtlasRenderer renderer(*context, builtin_demo_mesh(), camera, 0.05, 6.0);
  renderer.render(test::random_poses(builtin_demo_mesh(), 500, 0.7, 5));  // allocation and shader compilation, untimed
  render::GlDrawTimer timer(*context);
  if (!timer.available()) {
    std::cout << "SKIPPED: " << context->describe() << " has no timer queries: " << timer.why_unavailable() << "\n";
    return;
  }
  for (int repeat = 0; repeat < 3; ++repeat) {
    const Stopwatch wall;
    timer.begin();
    renderer.draw();
    const compute::EventPtr drawn = timer.end();
    renderer.finish();
    const double wall_ms = wall.elapsed_ms();
    const double gl_ms = drawn->elapsed_ms();
    INFO("GL " << gl_ms << " ms, wall " << wall_ms << " ms (" << context->describe() << ")");
    CHECK(gl_ms > 0);
    CHECK(gl_ms <= wall_ms);
    CHECK(drawn->elapsed_ms() == gl_ms);  // read once, then kept
  }
}

TEST_CASE("a GL draw time is refused once the next timed draw began or its timer is gone", "[render][timer]") {
  auto context = test::gl_context_or_skip();
  if (!context) return;
  render::AtlasRenderer renderer(*context, builtin_demo_mesh(), camera, 0.05, 6.0);
  renderer.reserve(4);
  auto timer = std::make_unique<render::GlDrawTimer>(*context);
  if (!timer->available()) {
    std::cout << "SKIPPED: no timer queries: " << timer->why_unavailable() << "\n";
    return;
  }
  timer->begin();
  renderer.draw();
  const compute::EventPtr first = timer->end();
  timer->begin();
  CHECK_THROWS_WITH(first->elapsed_ms(), Catch::Contains("after the next GL draw began"));
  CHECK_THROWS_WITH(timer->begin(), Catch::Contains("begun twice"));
  renderer.draw();
  const compute::EventPtr second = timer->end();
  timer.reset();
  CHECK_THROWS_WITH(second->elapsed_ms(), Catch::Contains("timer was destroyed"));
}

TEST_CASE("with the GL atlas the device filter reports GL's draw time, device-timed where GL has timer queries",
          "[device][render][timer]") {
  if (!test::device_available()) return;
  if (!test::gl_context_or_skip()) return;
  SynthConfig synth;
  synth.frames = 4;
  const Synthesizer synthesizer(builtin_demo_mesh(), synth);
  TrackerConfig config;
  config.renderer = Renderer::Gl;
  config.step_timings = true;
  config.particles = 300;
  config.backend = test::device_selector();
  const Camera working = synth.camera.decimated(8);
  DeviceFilter filter(compute::open_device(config.backend), builtin_demo_mesh(), working, config);
  const bool timed_by_gl = filter.description().find("draw timed by GL timer queries") != std::string::npos;
  std::cout << filter.description() << "\n";
  filter.initialize(synthesizer.frame(0).ground_truth, InitialSpread{});
  for (int f = 0; f < synth.frames; ++f) {
    const SynthFrame frame = synthesizer.frame(f);
    const Estimate e = filter.update(frame.depth.decimated(8), f == 0 ? 0.0 : 1.0 / 30);
    INFO("frame " << f << ": render " << e.timings.render_ms << " ms, hand-off " << e.timings.handoff_ms
                  << " ms, total " << e.timings.total_ms << " ms");
    CHECK(e.timings.render_on_device == timed_by_gl);
    CHECK(e.timings.render_ms > 0);
    CHECK(e.timings.render_ms <= e.timings.total_ms);
    CHECK(e.timings.handoff_ms <= e.timings.total_ms);
  }
}
