// The CUDA Queue itself on a GPU (skipped without one): Philox on the device equals the host's bit
// for bit, work-group memory and barriers work, arguments are checked, and objects may outlive
// the queue that made them. The general [compute] tests cover the rest with DEPTHTRACK_TEST_DEVICE=cuda.
#if defined(DEPTHTRACK_WITH_CUDA)
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <functional>
#include <iostream>
#include <numeric>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/cuda/cuda_backend.hpp"
#include "compute/cuda/cuda_driver_api.hpp"
#include "compute/cuda/cuda_queue.hpp"
#include "compute/kernel_sources.hpp"
#include "philox.h"

using namespace depthtrack;

namespace {
std::unique_ptr<compute::Queue> cuda_queue() {
  if (compute::cuda::devices().empty()) {
    std::cout << "SKIPPED: no CUDA device: " << compute::cuda::unavailable_reason() << "\n";
    return nullptr;
  }
  return compute::cuda::open(0);
}

const char* const kKernels = R"(
__kernel void random_words(__global uint* out, ulong seed, uint frame) {
  const uint i = get_global_id(0);
  const dt_philox4 w = dt_random_words(seed, i, frame, DT_STREAM_MOTION, 3u);
  for (uint k = 0; k < 4u; ++k) out[4u * i + k] = w.v[k];
}
/* One sum per work-group through work-group memory, as the filter's reductions do. */
__kernel void group_sums(__global const float* in, __global float* out) {
  __local float scratch[GROUP];
  const uint l = get_local_id(0);
  scratch[l] = in[get_global_id(0)];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint half = GROUP / 2; half > 0; half /= 2) {
    if (l < half) scratch[l] += scratch[l + half];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0) out[get_group_id(0)] = scratch[0];
}
)";

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("CUDA Philox equals the host's bit for bit", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  auto program = queue->build("gpu_test", compute::kernel_source("philox.h") + kKernels, {"GROUP=128"});
  auto kernel = program->kernel("random_words");
  const size_t n = 4096;
  const std::uint64_t seed = 0x123456789abcdefULL;
  compute::Buffer<std::uint32_t> out(*queue, 4 * n);
  auto event = queue->launch(*kernel, compute::NdRange::linear(n, 256), out, seed, 7u);
  CHECK(event->elapsed_ms() >= 0.0);
  const auto words = out.download();
  for (std::uint32_t i = 0; i < n; ++i) {
    const dt_philox4 expected = dt_random_words(seed, i, 7u, DT_STREAM_MOTION, 3u);
    for (unsigned k = 0; k < 4; ++k) REQUIRE(words[4 * i + k] == expected.v[k]);
  }
}

TEST_CASE("CUDA work-group memory and barriers give group sums", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  auto program = queue->build("gpu_test", compute::kernel_source("philox.h") + kKernels, {"GROUP=128"});
  auto kernel = program->kernel("group_sums");
  std::vector<float> values(128 * 8);
  std::iota(values.begin(), values.end(), 0.0f);
  compute::Buffer<float> in(*queue, values.size()), sums(*queue, 8);
  in.upload(values);
  queue->launch(*kernel, compute::NdRange::linear(values.size(), 128), in, sums);
  const auto got = sums.download();
  for (size_t g = 0; g < 8; ++g)
    CHECK(got[g] == std::accumulate(values.begin() + 128 * g, values.begin() + 128 * (g + 1), 0.0f));
}

TEST_CASE("CUDA kernel arguments are checked before the launch", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  auto program = queue->build("gpu_test", compute::kernel_source("philox.h") + kKernels, {"GROUP=128"});
  auto kernel = program->kernel("random_words");
  compute::Buffer<std::uint32_t> out(*queue, 4 * 64);
  compute::set_arg(*kernel, 0, out);
  kernel->set_arg(2, 1u);
  const std::string missing = error_of([&] { queue->launch(*kernel, compute::NdRange::linear(64, 64)); });
  CHECK(missing.find("argument 1") != std::string::npos);
  // A 4-byte value for the 8-byte seed (the driver reports parameter sizes since CUDA 12.4).
  CHECK_THROWS_AS(kernel->set_arg(1, 5u), InputError);
  CHECK_THROWS_AS(kernel->set_arg(3, 5u), InputError);  // the kernel has three parameters
  kernel->set_arg(1, std::uint64_t{5});
  queue->launch(*kernel, compute::NdRange::linear(64, 64));
  queue->finish();
}

TEST_CASE("CUDA copies, shared memory between queues, and objects outliving their queue", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  auto other = compute::cuda::open(0);  // same device, same primary context
  compute::Buffer<int> a(*queue, 16), b(*other, 16);
  std::vector<int> values(16);
  std::iota(values.begin(), values.end(), 100);
  a.upload(values);
  queue->copy(a.memory(), 4 * sizeof(int), b.memory(), 0, 8 * sizeof(int));
  queue->finish();
  const auto got = b.download();
  CHECK(std::vector<int>(got.begin(), got.begin() + 8) == std::vector<int>(values.begin() + 4, values.begin() + 12));
  // Within one allocation: disjoint ranges copy, overlapping ones are refused.
  queue->copy(a.memory(), 0, a.memory(), 8 * sizeof(int), 8 * sizeof(int));
  CHECK(a.download()[15] == 107);
  CHECK_THROWS_AS(queue->copy(a.memory(), 0, a.memory(), 4 * sizeof(int), 8 * sizeof(int)), InputError);

  auto program = queue->build("gpu_test", compute::kernel_source("philox.h") + kKernels, {"GROUP=128"});
  auto kernel = program->kernel("random_words");
  auto memory = queue->allocate(256);
  program.reset();
  queue.reset();  // the context lives on in the memory, kernel and the other queue
  other->launch(*kernel, compute::NdRange::linear(16, 16), *memory, std::uint64_t{1}, 0u)->wait();
}

// The filters' own queues (Queue::another_queue, one per object of a MultiTracker) get streams of
// falling urgency in the order they were made, where the driver offers more than one priority.
TEST_CASE("A CUDA device's queues get stream priorities in the order they were made", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  const auto& api = compute::cuda::require_driver();
  int least = 0, greatest = 0;
  if (!api.cuStreamGetPriority || !api.cuCtxGetStreamPriorityRange ||
      api.cuCtxGetStreamPriorityRange(&least, &greatest) != CUDA_SUCCESS || greatest >= least) {
    std::cout << "SKIPPED: this driver offers one stream priority\n";
    return;
  }
  auto first = queue->another_queue(), second = queue->another_queue();
  const auto priority = [&](const compute::Queue& q) {
    int p = 0;
    REQUIRE(api.cuStreamGetPriority(dynamic_cast<const compute::cuda::CudaQueue&>(q).stream(), &p) == CUDA_SUCCESS);
    return p;
  };
  INFO("priority range [" << greatest << ", " << least << "]");
  CHECK(priority(*queue) == greatest);
  CHECK(priority(*first) == greatest + 1);
  CHECK(priority(*second) == std::min(greatest + 2, least));
}

TEST_CASE("A CUDA allocation beyond free memory names both sizes", "[cuda]") {
  auto queue = cuda_queue();
  if (!queue) return;
  const size_t too_many = queue->info().global_memory + (size_t{1} << 20);
  const std::string message = error_of([&] { queue->allocate(too_many); });
  CHECK(message.find(std::to_string(too_many)) != std::string::npos);
  CHECK(message.find("free") != std::string::npos);
  CHECK(message.find(queue->info().name) != std::string::npos);
  CHECK_THROWS_AS(queue->allocate(0), BackendError);
}

namespace {
// A CUDA queue with graphs and a kernel adding a value to each element: what the graph tests batch.
// queue stays null (a message says why) where there is no CUDA device or graphs are off.
struct GraphQueue {
  std::unique_ptr<compute::Queue> queue;
  compute::cuda::CudaQueue* cuda = nullptr;
  std::unique_ptr<compute::Program> program;
  std::unique_ptr<compute::Kernel> kernel;
  GraphQueue() {
    auto opened = cuda_queue();
    if (!opened) return;
    cuda = dynamic_cast<compute::cuda::CudaQueue*>(opened.get());
    REQUIRE(cuda);
    if (!cuda->graphs()) {
      std::cout << "SKIPPED: CUDA graphs are off (DEPTHTRACK_CUDA_GRAPHS) or the driver lacks them\n";
      return;
    }
    const char* source = R"(
__kernel void add(__global float* y, float value, uint count) {
  const uint i = get_global_id(0);
  if (i < count) y[i] += value;
}
)";
    program = opened->build("add", compute::kernel_source("dt_prelude.h") + source, {});
    kernel = program->kernel("add");
    queue = std::move(opened);
  }
  // `count` zeros on the queue.
  compute::Buffer<float> zeros(unsigned count) {
    compute::Buffer<float> values(*queue, count);
    values.upload(std::vector<float>(count, 0.0f));
    return values;
  }
  // One batch of two launches of add over `range`: a timed one adding `a` to `first`, then an untimed
  // one adding `b` to `second`.
  void two_launches(compute::Buffer<float>& first, float a, compute::Buffer<float>& second, float b,
                    const compute::NdRange& range) {
    const unsigned count = static_cast<unsigned>(first.size());
    compute::LaunchBatch batch(*queue, true);
    queue->launch(*kernel, range, first, a, count);
    queue->launch_untimed(*kernel, range, second, b, count);
    batch.submit();
  }
};
}  // namespace

// The general [compute] test checks a batch's results; this one that the graph is built once and
// replayed: the same kernels over the same ranges build nothing new, only changed arguments are set
// again, and another range is a graph of its own.
TEST_CASE("CUDA batches replay one graph, setting only the arguments that changed", "[cuda]") {
  GraphQueue g;
  if (!g.queue) return;
  const unsigned count = 256;
  compute::Buffer<float> ys = g.zeros(count);
  const auto range = compute::NdRange::linear(count, 64);
  const auto frame = [&](float first, float second, const compute::NdRange& r) {
    g.two_launches(ys, first, ys, second, r);
  };
  const compute::cuda::LaunchGraphs& graphs = *g.cuda->graphs();
  frame(1.0f, 2.0f, range);
  CHECK(graphs.graphs_built() == 1);
  CHECK(graphs.nodes_updated() == 0);
  frame(1.0f, 2.0f, range);  // the same arguments: a replay as it is
  CHECK(graphs.graphs_built() == 1);
  CHECK(graphs.nodes_updated() == 0);
  frame(1.0f, 5.0f, range);  // the second launch's value changed: one node set
  CHECK(graphs.graphs_built() == 1);
  CHECK(graphs.nodes_updated() == 1);
  frame(1.0f, 1.0f, compute::NdRange::linear(count, 128));  // another block size: another graph
  CHECK(graphs.graphs_built() == 2);
  const std::vector<float> y = ys.download();
  CHECK(y[0] == 3.0f + 3.0f + 6.0f + 2.0f);
  CHECK(y[count - 1] == 14.0f);
}

// A frame that swaps double buffers alternates between two sets of pointers: each set gets a graph of
// its own, so a replay sets only the arguments that really changed.
TEST_CASE("CUDA batches over swapped buffers keep a graph per buffer and replay it as it is", "[cuda]") {
  GraphQueue g;
  if (!g.queue) return;
  const unsigned count = 64;
  compute::Buffer<float> a = g.zeros(count), b = g.zeros(count);
  const auto range = compute::NdRange::linear(count, 64);
  const auto frame = [&](compute::Buffer<float>& first, compute::Buffer<float>& second, float value) {
    g.two_launches(first, 1.0f, second, value, range);
  };
  const compute::cuda::LaunchGraphs& graphs = *g.cuda->graphs();
  frame(a, b, 1.0f);
  frame(b, a, 1.0f);  // both pointers swapped: a graph of its own
  CHECK(graphs.graphs_built() == 2);
  CHECK(graphs.nodes_updated() == 0);
  for (int i = 0; i < 3; ++i) {
    frame(a, b, 1.0f);
    frame(b, a, 1.0f);
  }
  CHECK(graphs.graphs_built() == 2);
  CHECK(graphs.nodes_updated() == 0);
  frame(a, b, 2.0f);  // a value changed: its node set in the first graph
  CHECK(graphs.graphs_built() == 2);
  CHECK(graphs.nodes_updated() == 1);
  // Each of the first eight frames added 1 to each buffer; the last 1 to a and 2 to b.
  CHECK(a.download()[0] == 8.0f + 1.0f);
  CHECK(b.download()[count - 1] == 8.0f + 2.0f);
}

// A frame's batch handed over in two parts (Queue::flush_batch, so the device starts on the first while
// the host records the rest): each part is a graph of its own, replayed as it is frame after frame.
TEST_CASE("A flushed CUDA batch is handed over in parts, each part replayed frame after frame", "[cuda]") {
  GraphQueue g;
  if (!g.queue) return;
  const unsigned count = 64;
  compute::Buffer<float> ys = g.zeros(count);
  const auto range = compute::NdRange::linear(count, 64);
  for (int frame = 0; frame < 3; ++frame) {
    compute::LaunchBatch batch(*g.queue, true);
    const compute::EventPtr first = g.queue->launch(*g.kernel, range, ys, 1.0f, count);
    batch.flush();
    const compute::EventPtr second = g.queue->launch(*g.kernel, range, ys, 2.0f, count);
    g.queue->launch_untimed(*g.kernel, range, ys, 3.0f, count);
    batch.submit();
    // Each part's timed launch records events of its own: the second part did not take the first's.
    REQUIRE(first != second);
    CHECK(first->elapsed_ms() >= 0);
    CHECK(second->elapsed_since_ms(*first).value_or(0.0) >= first->elapsed_ms());
  }
  CHECK(g.cuda->graphs()->graphs_built() == 2);
  CHECK(g.cuda->graphs()->nodes_updated() == 0);
  CHECK(ys.download() == std::vector<float>(count, 3 * 6.0f));
}

#endif
