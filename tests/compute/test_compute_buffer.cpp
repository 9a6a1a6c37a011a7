// Typed buffers on the test device: round trips, sub-ranges, device-side copies.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <numeric>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute_support.hpp"

using namespace depthtrack;

TEST_CASE("Buffer<float> round trip, whole and in sub-ranges", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  std::vector<float> data(1000);
  std::iota(data.begin(), data.end(), 0.5f);
  compute::Buffer<float> buffer(*queue, data.size());
  REQUIRE(buffer.size() == 1000);
  REQUIRE(buffer.memory().bytes() == 4000);
  buffer.upload(data);
  CHECK(buffer.download() == data);

  // Overwrite [100, 150) and read back [90, 160).
  const std::vector<float> patch(50, -1.0f);
  buffer.upload(patch, 100);
  std::vector<float> window(70);
  buffer.download(window, 90);
  for (size_t i = 0; i < window.size(); ++i) {
    const size_t element = 90 + i;
    CHECK(window[i] == (element >= 100 && element < 150 ? -1.0f : data[element]));
  }
  // The last element alone.
  std::vector<float> last(1);
  buffer.download(last, 999);
  CHECK(last[0] == data[999]);
}

// An enqueued upload takes the bytes before it returns: the host's array may change at once, and
// uploads, launches and copies keep their order on the queue.
TEST_CASE("Enqueued uploads take their bytes at once and stay in order with the queue's work", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  std::vector<float> frame(4096);
  std::iota(frame.begin(), frame.end(), 1.0f);
  compute::Buffer<float> a(*queue, frame.size()), b(*queue, frame.size()), kept(*queue, frame.size());
  a.upload_enqueued(frame);
  const std::vector<float> first = frame;
  std::fill(frame.begin(), frame.end(), -7.0f);  // the next frame, before the first copy is awaited
  queue->copy(a.memory(), 0, kept.memory(), 0, frame.size() * sizeof(float));
  a.upload_enqueued(frame);  // over the buffer the copy reads: after it, in order
  b.upload_enqueued(std::span<const float>(frame).subspan(10, 20), 100);
  CHECK(kept.download() == first);
  CHECK(a.download() == frame);
  std::vector<float> part(20);
  b.download(part, 100);
  CHECK(part == std::vector<float>(20, -7.0f));
  CHECK_THROWS_AS(b.upload_enqueued(frame, 1), InputError);  // past the end: refused, nothing written
}

// The backends stage enqueued transfers through one host area each way, made larger when a transfer
// needs more: the first write may still be in flight when the area is replaced.
TEST_CASE("Enqueued transfers larger than every one before them arrive intact", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  std::vector<float> big(8192);
  std::iota(big.begin(), big.end(), 0.5f);
  compute::Buffer<float> buffer(*queue, big.size());
  buffer.upload_enqueued(std::vector<float>(16, 3.0f), 8000);
  buffer.upload_enqueued(big);
  std::vector<float> head(16, -1.0f), all(big.size(), -1.0f);
  buffer.download_enqueued(head, 4);
  queue->wait_enqueued_reads();
  CHECK(head == std::vector<float>(big.begin() + 4, big.begin() + 20));
  buffer.download_enqueued(all);
  queue->wait_enqueued_reads();
  CHECK(all == big);
}

// An enqueued read sees the queue's work before it and none after it (here a launch in the same batch,
// which CUDA records as a graph, and an upload), its bytes land at wait_enqueued_reads(), and a second
// read in flight first completes the first.
TEST_CASE("Enqueued reads see the work before them, not after, and land at the wait", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const char* source = R"(
__kernel void add(__global float* y, float value, uint count) {
  const uint i = get_global_id(0);
  if (i < count) y[i] += value;
}
)";
  const auto program = queue->build("add", compute::kernel_source("dt_prelude.h") + source, {});
  const auto add = program->kernel("add");
  const unsigned count = 512;
  std::vector<float> start(count);
  std::iota(start.begin(), start.end(), 0.0f);
  compute::Buffer<float> ys(*queue, count);
  ys.upload(start);
  std::vector<float> seen(count, -1.0f), part(8, -1.0f);
  {
    compute::LaunchBatch batch(*queue, true);
    queue->launch(*add, compute::NdRange::linear(count, 64), ys, 1.0f, count);
    ys.download_enqueued(seen);
    queue->launch_untimed(*add, compute::NdRange::linear(count, 64), ys, 10.0f, count);
    batch.submit();
  }
  ys.upload_enqueued(std::vector<float>(count, 5.0f));
  queue->wait_enqueued_reads();
  for (unsigned i = 0; i < count; ++i) REQUIRE(seen[i] == start[i] + 1.0f);
  ys.download_enqueued(seen);
  ys.download_enqueued(part, 100);  // completes the first
  CHECK(seen == std::vector<float>(count, 5.0f));
  queue->wait_enqueued_reads();
  CHECK(part == std::vector<float>(8, 5.0f));
  queue->wait_enqueued_reads();                                        // nothing in flight: returns
  CHECK_THROWS_AS(ys.download_enqueued(part, count - 4), InputError);  // past the end: refused
}

TEST_CASE("Queue copies between device buffers", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  std::vector<int> data(256);
  std::iota(data.begin(), data.end(), 7);
  compute::Buffer<int> a(*queue, 256), b(*queue, 256);
  a.upload(data);
  b.upload(std::vector<int>(256, 0));
  queue->copy(a.memory(), 16 * sizeof(int), b.memory(), 32 * sizeof(int), 64 * sizeof(int));
  queue->finish();
  const auto result = b.download();
  for (size_t i = 0; i < 256; ++i) CHECK(result[i] == (i >= 32 && i < 96 ? data[i - 16] : 0));
}

TEST_CASE("A mapped range is overwritten on publish and nothing else changes", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  std::vector<float> data(300);
  std::iota(data.begin(), data.end(), 1.0f);
  compute::Buffer<float> buffer(*queue, data.size());
  buffer.upload(data);
  {
    auto mapped = buffer.overwrite(100, 50);
    REQUIRE(mapped.data().size() == 50);
    for (size_t i = 0; i < 50; ++i) mapped.data()[i] = -static_cast<float>(i);
    // One mapping at a time: a second one is refused while the first is open.
    CHECK_THROWS_AS(buffer.overwrite(0, 10), InputError);
    mapped.publish();
  }
  const std::vector<float> got = buffer.download();
  for (size_t i = 0; i < got.size(); ++i) {
    INFO("element " << i);
    CHECK(got[i] == (i >= 100 && i < 150 ? -static_cast<float>(i - 100) : data[i]));
  }
  CHECK_THROWS_AS(buffer.overwrite(290, 20), InputError);  // beyond the end
  // A mapping dropped without publishing (an exception on the way) is still released.
  { auto dropped = buffer.overwrite(0, 10); }
  auto again = buffer.overwrite(0, 10);
  again.publish();
}
