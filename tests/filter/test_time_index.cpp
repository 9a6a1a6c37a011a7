// Per-pixel-time occlusion's 16-bit frame indices (cl/dt_time_index.h): the retirement kernel before an
// index comes round again, and the host's table of frame times.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "device_support.hpp"
#include "dt_state.h"
#include "dt_time_index.h"
#include "filter/device_filter.hpp"
#include "filter/device_filter_probe.hpp"
#include "filter/frame_time_table.hpp"
#include "reference/reference_filter.hpp"

using namespace depthtrack;

namespace {
std::unique_ptr<compute::Program> resample_program(compute::Queue& q) {
  return q.build("resample.cl", compute::kernel_source("resample.cl"), {"DT_GROUP_SIZE=64", "DT_OCCLUSION=0"});
}
}  // namespace

TEST_CASE("indices last written 32768 frames ago or more are retired to time 0, counted round the cycle",
          "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  auto program = resample_program(*q);
  auto retire = program->kernel("retire_time_indices");
  const unsigned now = 100;  // indices above it were written in the previous round of the cycle
  // (index, its age in frames): the age is (now - index) mod 65535.
  const std::vector<std::pair<unsigned, unsigned>> cases = {
      {100, 0}, {99, 1}, {0, 100}, {65534, 101}, {32868, 32767}, {32867, 32768}, {32767, 32868}, {101, 65534}};
  std::vector<uint16_t> indices;
  for (const auto& c : cases) indices.push_back(static_cast<uint16_t>(c.first));
  indices.push_back(static_cast<uint16_t>(DT_TIME_NEVER));
  // Many more than the grid's work-items, so the grid-stride loop is exercised too.
  const std::vector<uint16_t> one_round = indices;
  for (int r = 0; r < 500; ++r) indices.insert(indices.end(), one_round.begin(), one_round.end());
  compute::Buffer<uint16_t> buffer(*q, indices.size());
  buffer.upload(indices);
  q->launch(*retire, compute::NdRange::linear(64 * 4, 64), buffer, static_cast<uint64_t>(indices.size()), now)->wait();
  const auto got = buffer.download();
  for (size_t i = 0; i < got.size(); ++i) {
    const size_t c = i % one_round.size();
    INFO("value " << i << ": index " << one_round[c]);
    if (c == cases.size()) {
      CHECK(got[i] == DT_TIME_NEVER);
    } else {
      const bool old = cases[c].second >= DT_TIME_RETIRE_AGE;
      CHECK(got[i] == (old ? DT_TIME_NEVER : one_round[c]));
    }
  }
}

TEST_CASE("the frame time table hands out indices in turn, retires on schedule and maps times both ways", "[device]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  FrameTimeTable table(*q);
  CHECK_FALSE(table.retire_due());
  // The start: every pixel at DT_TIME_NEVER, which is time 0.
  CHECK(table.times({static_cast<uint16_t>(DT_TIME_NEVER)}) == std::vector<float>{0.0f});
  CHECK(table.indices({0.0f}) == std::vector<uint16_t>{static_cast<uint16_t>(DT_TIME_NEVER)});
  for (unsigned f = 0; f < 3; ++f) CHECK(table.begin_frame(0.25f * static_cast<float>(f + 1)) == f);
  CHECK(table.times({0, 1, 2}) == std::vector<float>{0.25f, 0.5f, 0.75f});
  CHECK(table.indices({0.5f, 0.75f, 0.0f}) == std::vector<uint16_t>{1, 2, static_cast<uint16_t>(DT_TIME_NEVER)});
  CHECK_THROWS_WITH(table.indices({0.6f}), Catch::Contains("occlusion time 0.6") && Catch::Contains("not the time"));
  // Retirement every DT_TIME_RETIRE_EVERY frames; the indices come round after DT_TIME_CYCLE.
  unsigned last = 2;
  for (unsigned f = 3; f < DT_TIME_RETIRE_EVERY; ++f) last = table.begin_frame(1.0f + static_cast<float>(f));
  CHECK(last == DT_TIME_RETIRE_EVERY - 1);
  CHECK(table.retire_due());
  table.retired();
  CHECK_FALSE(table.retire_due());
  for (unsigned f = DT_TIME_RETIRE_EVERY; f < DT_TIME_CYCLE; ++f)
    last = table.begin_frame(1.0f + static_cast<float>(f));
  CHECK(last == DT_TIME_CYCLE - 1);
  CHECK(table.begin_frame(1e5f) == 0);  // round again
  CHECK(table.indices({1e5f}) == std::vector<uint16_t>{0});
  CHECK_THROWS_AS(table.indices({0.25f}), InputError);  // frame 0's first time has been overwritten
  table.reset();
  CHECK(table.begin_frame(0.0f) == 0);
}

// The filter launches the retirement itself every DT_TIME_RETIRE_EVERY frames. A tiny scene (20x15, two
// particles that do not move) is seen for a few frames, then the sensor drops out for 49,152 frames, so
// the pixels it saw are last seen longer than DT_TIME_RETIRE_AGE frames ago: the device retires them to
// time 0, the reference keeps their float times, and when the depth comes back both age them to the
// same stationary value (1,638 s at c = 0.6: c^age underflows), so the filter still equals the reference.
TEST_CASE("a device filter retires time indices unseen for 32,768 frames and still equals the reference",
          "[device][slow]") {
  if (!test::device_available()) return;
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = 1;
  const Synthesizer synthesizer(mesh, synth);
  const Camera camera = synth.camera.decimated(32);  // 20x15
  const SynthFrame first = synthesizer.frame(0);
  const DepthImage seen = first.depth.decimated(32);
  DepthImage dropout = seen;
  for (int v = 0; v < dropout.height(); ++v)
    for (int u = 0; u < dropout.width(); ++u) dropout.at(u, v) = NAN;
  TrackerConfig config;
  config.particles = 2;
  config.refine.enabled = false;
  config.motion.sigma_linear = config.motion.sigma_angular = 0;  // still particles: no float drift
  config.backend = test::device_selector();
  reference::ReferenceFilter reference(mesh, camera, config);
  DeviceFilter device(compute::open_device(config.backend), mesh, camera, config);
  reference.initialize(first.ground_truth, InitialSpread{0.002, 0.01});
  device.initialize(first.ground_truth, InitialSpread{0.002, 0.01});
  const double dt = 1.0 / 30;
  const unsigned seen_frames = 3, dark = DT_TIME_RETIRE_AGE + DT_TIME_RETIRE_EVERY;
  for (unsigned f = 0; f < seen_frames + dark; ++f) {
    const DepthImage& depth = f < seen_frames ? seen : dropout;
    reference.update(depth, f == 0 ? 0.0 : dt);
    device.update(depth, f == 0 ? 0.0 : dt);
  }
  // Retired: the pixels seen at the start read time 0 on the device, their own time on the reference.
  const auto device_times = DeviceFilterProbe(device).occlusion_times(), reference_times = reference.occlusion_times();
  REQUIRE(device_times.size() == reference_times.size());
  size_t retired = 0;
  for (size_t k = 0; k < device_times.size(); ++k) {
    CHECK(device_times[k] == 0.0f);
    retired += reference_times[k] > 0.0f;
  }
  CHECK(retired > 0);
  // The depth comes back: the same likelihoods and estimate.
  const Estimate a = reference.update(seen, dt), b = device.update(seen, dt);
  CHECK(translation_error(a.pose, b.pose) <= 1e-5);
  const auto ll_ref = reference.last_log_likelihoods(), ll_dev = DeviceFilterProbe(device).last_log_likelihoods();
  for (size_t i = 0; i < ll_ref.size(); ++i) CHECK(ll_dev[i] == Approx(ll_ref[i]).epsilon(1e-4));
}
