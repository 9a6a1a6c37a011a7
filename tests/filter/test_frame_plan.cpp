// The device frame's plan (filter/frame_plan.hpp) for described devices: which steps a frame runs, in
// which layout, over which work sizes, from the configuration, the device's capabilities and the sizes.
// No device is opened; the numbers are worked out by hand from the rules the plan's header states.
#include <algorithm>
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>

#include "filter/frame_plan.hpp"

using namespace depthtrack;

namespace {
// A GPU as CUDA describes one: 48 KiB a group, what a unit holds, graphs replaying its launches.
compute::DeviceInfo graph_gpu() {
  compute::DeviceInfo d;
  d.is_gpu = true;
  d.local_memory = 48 * 1024;
  d.local_memory_per_unit = 228 * 1024;
  d.local_memory_reserved = 1024;
  d.registers_per_unit = 65536;
  d.max_work_group_size = 1024;
  d.max_allocation = size_t{1} << 34;
  d.int64_atomics = true;
  d.replayed_launches = true;
  return d;
}

// A CPU device as PoCL describes one: plenty of local memory, no units' figures, launches one by one.
compute::DeviceInfo cpu_device() {
  compute::DeviceInfo d;
  d.local_memory = 4 * 1024 * 1024;
  d.max_work_group_size = 4096;
  d.max_allocation = size_t{1} << 32;
  d.int64_atomics = true;
  return d;
}

FrameSizes sizes_80x60(size_t triangles = 842, size_t vertices = 423) {
  FrameSizes s;
  s.width = 80;
  s.height = 60;
  s.triangles = triangles;
  s.device_mesh_vertices = vertices;
  return s;
}

TrackerConfig config_of(int particles, Renderer renderer = Renderer::Kernel, bool refine = true) {
  TrackerConfig c;
  c.particles = particles;
  c.renderer = renderer;
  c.refine.enabled = refine;
  c.refine.layout = RefineLayout::Auto;
  return c;
}
}  // namespace

TEST_CASE("a small cloud at 80x60 is drawn, moved and weighed in one launch and resampled by scanning groups",
          "[plan]") {
  const FramePlan plan = make_frame_plan(config_of(2000), graph_gpu(), sizes_80x60());
  CHECK(plan.particles == 2000);
  CHECK(plan.pixels == 4800);
  CHECK(plan.weigh == WeighStep::RenderWeigh);
  CHECK(plan.propagate_in_weigh);
  CHECK_FALSE(plan.builds_propagate());
  CHECK(plan.atlas_tiles == 0);  // no separate atlas
  CHECK_FALSE(plan.needs_atlas());
  // 842 triangles, launches replayed: the fit spreads, so the summary is summarize.cl's one group of
  // 512 work-items (the largest power of two from 128 up to min(512, 1024)).
  REQUIRE(plan.refine);
  CHECK(*plan.refine == RefineLayout::Spread);
  CHECK(plan.summary == SummaryStep::OneGroup);
  CHECK(plan.summary_group == 512);
  CHECK(plan.resample == ResampleStep::Scanning);
  CHECK_FALSE(plan.needs_cumulative());
  // Work sizes: 2,000 rounded up to 64s (2,048) a work-item each; a group of 128 per particle; the
  // scanning gather rounded up to 128s (2,048).
  CHECK(plan.per_particle().global[0] == 2048);
  CHECK(plan.per_particle().local[0] == 64);
  CHECK(plan.group_per_particle(plan.particles).global[0] == 2000 * 128);
  CHECK(plan.group_per_particle(plan.particles).local[0] == 128);
  CHECK(plan.scanning().global[0] == 2048);
  CHECK(plan.scanning().local[0] == 128);
}

TEST_CASE("the cloud's size picks the summary and the resampling", "[plan]") {
  // Just past the fused launches: propagate apart, one-group summary, one-group prefix sum.
  const FramePlan mid = make_frame_plan(config_of(4097), graph_gpu(), sizes_80x60());
  CHECK_FALSE(mid.propagate_in_weigh);
  CHECK(mid.builds_propagate());
  CHECK(mid.summary == SummaryStep::OneGroup);
  CHECK(mid.resample == ResampleStep::PrefixSum);
  CHECK(mid.needs_cumulative());
  // From 16,384 particles the summary and the prefix sum run over many groups.
  const FramePlan wide = make_frame_plan(config_of(16384), graph_gpu(), sizes_80x60());
  CHECK(wide.summary == SummaryStep::Wide);
  CHECK(wide.summary_group == 0);
  CHECK_FALSE(wide.builds_summarize());
  CHECK(wide.resample == ResampleStep::WidePrefixSum);
  const FramePlan below = make_frame_plan(config_of(16383), graph_gpu(), sizes_80x60());
  CHECK(below.summary == SummaryStep::OneGroup);
}

TEST_CASE("where launches are not replayed a small mesh's fit summarizes inside its one launch", "[plan][refine]") {
  compute::DeviceInfo gpu = graph_gpu();
  gpu.replayed_launches = false;  // as NVIDIA's OpenCL reports
  const FramePlan plan = make_frame_plan(config_of(2000), gpu, sizes_80x60());
  REQUIRE(plan.refine);
  CHECK(*plan.refine == RefineLayout::OneLaunch);
  CHECK(plan.summary == SummaryStep::InsideFit);
  CHECK_FALSE(plan.builds_summarize());
  // A large mesh spreads whatever the launches cost; the summary is then its own launch again.
  const FramePlan mug = make_frame_plan(config_of(2000), gpu, sizes_80x60(16384, 8000));
  CHECK(*mug.refine == RefineLayout::Spread);
  CHECK(mug.summary == SummaryStep::OneGroup);
  // Without the fit there is no layout and the summary is summarize.cl's.
  const FramePlan unrefined = make_frame_plan(config_of(2000, Renderer::Kernel, false), gpu, sizes_80x60());
  CHECK_FALSE(unrefined.refine);
  CHECK(unrefined.summary == SummaryStep::OneGroup);
}

TEST_CASE("a CPU device keeps the filter's group for the summary and draws inside weigh", "[plan]") {
  // Without the fit, summarize.cl's one group: 128 work-items, the filter's, whatever the device allows.
  const FramePlan plan = make_frame_plan(config_of(200, Renderer::Kernel, false), cpu_device(), sizes_80x60());
  CHECK(plan.summary == SummaryStep::OneGroup);
  CHECK(plan.summary_group == 128);
  // 80x60's tile (19,200 bytes) and the pose box's reduction (2,560) fit in CUDA's static 48 KiB.
  CHECK(plan.weigh == WeighStep::RenderWeigh);
  // With the fit, a small mesh on a CPU fits in one launch, which summarizes first: no group of its own.
  const FramePlan fitted = make_frame_plan(config_of(200), cpu_device(), sizes_80x60());
  CHECK(*fitted.refine == RefineLayout::OneLaunch);
  CHECK(fitted.summary == SummaryStep::InsideFit);
  CHECK(fitted.summary_group == 0);
}

TEST_CASE("an atlas drawn apart is weighed from its tiles, in turns where it holds fewer", "[plan]") {
  // 160x120: the tile (76,800 bytes) is beyond 48 KiB, so the kernel renderer draws a separate atlas.
  FrameSizes large = sizes_80x60();
  large.width = 160;
  large.height = 120;
  TrackerConfig config = config_of(2000);
  config.atlas_particles = 500;
  const FramePlan plan = make_frame_plan(config, graph_gpu(), large);
  CHECK(plan.weigh == WeighStep::DrawThenWeigh);
  CHECK_FALSE(plan.propagate_in_weigh);
  CHECK(plan.atlas_tiles == 500);
  CHECK(plan.needs_atlas());
  // The GL renderer's atlas holds every tile and is no kernel renderer's: none counted apart.
  const FramePlan gl = make_frame_plan(config_of(2000, Renderer::Gl), graph_gpu(), sizes_80x60());
  CHECK(gl.weigh == WeighStep::DrawThenWeigh);
  CHECK(gl.atlas_tiles == 0);
  // A source without a device mesh cannot draw inside weigh, even at 80x60.
  FrameSizes no_mesh = sizes_80x60();
  no_mesh.device_mesh_vertices.reset();
  CHECK(make_frame_plan(config_of(2000), graph_gpu(), no_mesh).weigh == WeighStep::DrawThenWeigh);
}

TEST_CASE("a fit layout the device cannot run is refused when the plan is made", "[plan][refine]") {
  compute::DeviceInfo old_gpu = graph_gpu();
  old_gpu.int64_atomics = false;
  old_gpu.name = "an old GPU";
  TrackerConfig config = config_of(2000);
  config.refine.layout = RefineLayout::Spread;
  CHECK_THROWS_AS(make_frame_plan(config, old_gpu, sizes_80x60()), InputError);
  config.refine.layout = RefineLayout::Auto;
  CHECK(*make_frame_plan(config, old_gpu, sizes_80x60()).refine == RefineLayout::OneGroup);
}

TEST_CASE("a count that changes takes the layouts its counts' plans take, all listed at the start", "[plan][budget]") {
  // Up to 100,000: the fused launches up to 4,096, the one-group prefix sum to 16,383, the wide summary from
  // 16,384; the last listed is the most's plan.
  const TrackerConfig config = config_of(100000);
  const auto layouts = frame_plan_layouts(config, graph_gpu(), sizes_80x60());
  REQUIRE(layouts.size() == 3);
  CHECK(layouts[0].particles == 1);
  CHECK(layouts[0].propagate_in_weigh);
  CHECK(layouts[0].resample == ResampleStep::Scanning);
  CHECK(layouts[1].particles == 4097);
  CHECK_FALSE(layouts[1].propagate_in_weigh);
  CHECK(layouts[1].resample == ResampleStep::PrefixSum);
  CHECK(layouts[2].particles == 100000);
  CHECK(layouts[2].summary == SummaryStep::Wide);
  CHECK(layouts[2].resample == ResampleStep::WidePrefixSum);
  // Every count's plan is one of them but for its count; what is allocated (the atlas) is the most's.
  for (size_t n = 1; n <= 100000; n += n < 20000 ? 1 : 97) {
    const FramePlan plan = make_frame_plan(config, graph_gpu(), sizes_80x60(), n);
    REQUIRE(plan.particles == n);
    REQUIRE(plan.atlas_tiles == layouts.back().atlas_tiles);
    const bool listed = std::any_of(layouts.begin(), layouts.end(), [&](const FramePlan& l) {
      return l.propagate_in_weigh == plan.propagate_in_weigh && l.summary == plan.summary &&
             l.resample == plan.resample && l.summary_group == plan.summary_group && l.refine == plan.refine &&
             l.weigh == plan.weigh;
    });
    if (!listed) FAIL("count " << n << " takes a layout not listed");
  }
  // A small cloud has one layout: its own plan.
  const auto small = frame_plan_layouts(config_of(200), graph_gpu(), sizes_80x60());
  REQUIRE(small.size() == 1);
  CHECK(small[0].particles == 200);
}
