// Programs built at run time from the prelude plus a kernel, with -D definitions, launched and timed.
#include <catch2/catch.hpp>
#include <optional>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute_support.hpp"

using namespace depthtrack;

namespace {
const char* const kAxpy = R"(
__kernel void axpy(float a, __global const float* x, __global float* y, uint count) {
  const uint i = get_global_id(0);
  if (i < count) y[i] = a * x[i] + OFFSET;
}
)";

std::vector<float> run_axpy(compute::Queue& queue, const std::string& offset, compute::EventPtr* event = nullptr) {
  const unsigned count = 1000;
  std::vector<float> x(count);
  for (unsigned i = 0; i < count; ++i) x[i] = static_cast<float>(i);
  compute::Buffer<float> xs(queue, count), ys(queue, count);
  xs.upload(x);
  auto program = queue.build("axpy", compute::kernel_source("dt_prelude.h") + kAxpy, {"OFFSET=" + offset});
  auto kernel = program->kernel("axpy");
  CHECK(kernel->name() == "axpy");
  auto launched = queue.launch(*kernel, compute::NdRange::linear(1024, 64), 2.0f, xs, ys, count);
  if (event) *event = launched;
  return ys.download();
}
}  // namespace

TEST_CASE("A kernel built with a definition computes a*x + OFFSET", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  compute::EventPtr event;
  const auto y = run_axpy(*queue, "3.5f", &event);
  for (unsigned i = 0; i < y.size(); ++i) CHECK(y[i] == 2.0f * static_cast<float>(i) + 3.5f);
  REQUIRE(event);
  CHECK(event->elapsed_ms() >= 0.0);

  // The definition reaches the compiler: another value, another result.
  const auto z = run_axpy(*queue, "-1.0f");
  for (unsigned i = 0; i < z.size(); ++i) CHECK(z[i] == 2.0f * static_cast<float>(i) - 1.0f);
}

TEST_CASE("A run of launches is timed from the first one's start to the last one's end", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const unsigned count = 1 << 16;
  compute::Buffer<float> xs(*queue, count), ys(*queue, count), zs(*queue, count);
  xs.upload(std::vector<float>(count, 1.0f));
  auto program = queue->build("axpy", compute::kernel_source("dt_prelude.h") + kAxpy, {"OFFSET=0.0f"});
  auto kernel = program->kernel("axpy");
  const auto range = compute::NdRange::linear(count, 64);
  const compute::EventPtr first = queue->launch(*kernel, range, 2.0f, xs, ys, count);
  queue->launch_untimed(*kernel, range, 3.0f, ys, zs, count);  // z = 3 y = 6, between the timed two
  const compute::EventPtr last = queue->launch(*kernel, range, 0.5f, zs, ys, count);  // y = 0.5 z = 3
  const std::optional<double> span = last->elapsed_since_ms(*first);
  REQUIRE(span);  // both backends (OpenCL's profiling counters, CUDA's event pairs) have a common clock
  // In order on one queue, the launches do not overlap: the span holds the three and the gaps between.
  CHECK(*span >= (first->elapsed_ms() + last->elapsed_ms()) * (1 - 1e-6) - 1e-6);
  CHECK(*first->elapsed_since_ms(*first) == Approx(first->elapsed_ms()).margin(1e-6));
  const auto y = ys.download(), z = zs.download();
  CHECK(z[0] == 6.0f);
  CHECK(z[count - 1] == 6.0f);
  CHECK(y[count / 2] == 3.0f);
}

TEST_CASE("Kernels launch over two-dimensional ranges", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const char* source = R"(
__kernel void index2d(__global uint* out, uint width) {
  out[get_global_id(1) * width + get_global_id(0)] = get_global_id(1) * 1000u + get_global_id(0);
}
)";
  auto program = queue->build("index2d", compute::kernel_source("dt_prelude.h") + source, {});
  auto kernel = program->kernel("index2d");
  compute::Buffer<unsigned> out(*queue, 32 * 8);
  queue->launch(*kernel, compute::NdRange{{32, 8, 1}, {16, 4, 1}, 2}, out, 32u);
  queue->finish();
  const auto result = out.download();
  for (unsigned y = 0; y < 8; ++y)
    for (unsigned x = 0; x < 32; ++x) CHECK(result[y * 32 + x] == y * 1000 + x);
}

// A batch (Queue::begin_batch .. end_batch; a CUDA graph replayed from the second batch on) computes what
// the same launches made one by one compute: the arguments that change from batch to batch reach the
// device, a read inside a batch sees the launches before it, and the timed events time the batch's work.
TEST_CASE("Batched launches equal the same launches made one by one, batch after batch", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const unsigned count = 4096;
  std::vector<float> x(count);
  for (unsigned i = 0; i < count; ++i) x[i] = static_cast<float>(i % 97);
  compute::Buffer<float> xs(*queue, count), ys(*queue, count), zs(*queue, count);
  xs.upload(x);
  auto program = queue->build("axpy", compute::kernel_source("dt_prelude.h") + kAxpy, {"OFFSET=1.0f"});
  auto kernel = program->kernel("axpy");
  const auto range = compute::NdRange::linear(count, 64);
  for (int frame = 0; frame < 4; ++frame) {
    const float a = 0.5f + static_cast<float>(frame);
    // Buffers swap roles from batch to batch, as the filter's state and scratch do.
    compute::Buffer<float>& into = frame % 2 ? zs : ys;
    compute::LaunchBatch batch(*queue, true);
    const compute::EventPtr first = queue->launch(*kernel, range, a, xs, into, count);     // a x + 1
    queue->launch_untimed(*kernel, range, 2.0f, into, xs, count);                          // 2 (a x + 1) + 1
    const std::vector<float> middle = into.download();                                     // hands over
    const compute::EventPtr last = queue->launch(*kernel, range, 0.25f, xs, into, count);  // into = 0.25 xs + 1
    batch.submit();
    const std::vector<float> got = into.download();
    for (unsigned i = 0; i < count; i += 131) {
      const float first_value = a * x[i] + 1.0f, second = 2.0f * first_value + 1.0f;
      REQUIRE(middle[i] == first_value);
      REQUIRE(got[i] == 0.25f * second + 1.0f);
    }
    const std::vector<float> next_x = xs.download();  // the second launch wrote xs = 2 (a x + 1) + 1
    for (unsigned i = 0; i < count; i += 131) REQUIRE(next_x[i] == 2.0f * (a * x[i] + 1.0f) + 1.0f);
    x = next_x;
    REQUIRE(first);
    REQUIRE(last);
    CHECK(first->elapsed_ms() >= 0.0);
    const std::optional<double> span = last->elapsed_since_ms(*first);
    if (span) CHECK(*span >= last->elapsed_ms() * (1 - 1e-6) - 1e-6);
  }
}
