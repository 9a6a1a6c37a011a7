// Every misuse of the compute layer is a clear error, never a crash: one test per kind.
#include <catch2/catch.hpp>
#include <functional>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute_support.hpp"

using namespace depthtrack;

namespace {
std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

const char* const kTwoKernels = R"(
__kernel void alpha(__global float* x) { x[get_global_id(0)] = 1.0f; }
__kernel void beta(__global float* x) { x[get_global_id(0)] = 2.0f; }
)";
}  // namespace

TEST_CASE("An unknown device selector lists the available devices", "[compute]") {
  for (const std::string selector : {"opencl:quantum", "vulkan", "cuda:x"}) {
    CAPTURE(selector);
    REQUIRE_THROWS_AS(compute::open_device(selector), InputError);
    const std::string message = message_of([&] { compute::open_device(selector); });
    CHECK(message.find(selector) != std::string::npos);
    for (const auto& device : compute::list_devices()) {
      CHECK(message.find(device.selector) != std::string::npos);
      CHECK(message.find(device.name) != std::string::npos);
    }
  }
}

TEST_CASE("A kernel with a syntax error reports the build log and the device", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const std::string source = compute::kernel_source("dt_prelude.h") +
                             "__kernel void broken(__global float* x) { x[0] = not_declared_here; }\n";
  REQUIRE_THROWS_AS(queue->build("broken", source, {"FLAVOUR=1"}), BackendError);
  const std::string message = message_of([&] { queue->build("broken", source, {"FLAVOUR=1"}); });
  CHECK(test::contains_nocase(message, "build"));
  CHECK(message.find(queue->info().name) != std::string::npos);
  CHECK(message.find("FLAVOUR=1") != std::string::npos);
  // The compiler's complaint: the word "error" only the log holds, next to the unknown identifier.
  CHECK(test::contains_nocase(message, "error"));
  CHECK(message.find("not_declared_here") != std::string::npos);
}

TEST_CASE("A buffer larger than the device allows is refused clearly", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const size_t too_many = queue->info().max_allocation / sizeof(float) + 1024;
  REQUIRE_THROWS_AS(compute::Buffer<float>(*queue, too_many), BackendError);
  const std::string message = message_of([&] { compute::Buffer<float> b(*queue, too_many); });
  CHECK(message.find(queue->info().name) != std::string::npos);
  // The queue still works afterwards.
  compute::Buffer<float> small(*queue, 4);
  small.upload(std::vector<float>{1, 2, 3, 4});
  CHECK(small.download() == std::vector<float>{1, 2, 3, 4});
}

TEST_CASE("Transfers of the wrong size or past the end are input errors", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  compute::Buffer<float> buffer(*queue, 100);
  const std::vector<float> too_long(101, 0.0f), ten(10, 0.0f);
  CHECK_THROWS_AS(buffer.upload(too_long), InputError);
  CHECK_THROWS_AS(buffer.upload(ten, 95), InputError);
  std::vector<float> out(10);
  CHECK_THROWS_AS(buffer.download(out, 91), InputError);
  CHECK_THROWS_AS(buffer.download(out, static_cast<size_t>(-1)), InputError);
  // The queue itself checks byte ranges too.
  CHECK_THROWS_AS(queue->write(buffer.memory(), 396, ten.data(), 8), InputError);
  CHECK_THROWS_AS(queue->read(buffer.memory(), 401, out.data(), 0), InputError);
  auto other = queue->allocate(16);
  CHECK_THROWS_AS(queue->copy(buffer.memory(), 0, *other, 8, 16), InputError);
}

TEST_CASE("An unknown kernel name lists the program's kernels", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  auto program = queue->build("two", compute::kernel_source("dt_prelude.h") + kTwoKernels, {});
  REQUIRE_THROWS_AS(program->kernel("gamma"), Error);
  const std::string message = message_of([&] { program->kernel("gamma"); });
  CHECK(message.find("gamma") != std::string::npos);
  CHECK(message.find("alpha") != std::string::npos);
  CHECK(message.find("beta") != std::string::npos);
}

TEST_CASE("A global size not divisible by the local size is an input error", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  auto program = queue->build("two", compute::kernel_source("dt_prelude.h") + kTwoKernels, {});
  auto kernel = program->kernel("alpha");
  compute::Buffer<float> x(*queue, 100);
  CHECK_THROWS_AS(queue->launch(*kernel, compute::NdRange::linear(100, 64), x), InputError);
  CHECK_THROWS_AS(queue->launch(*kernel, compute::NdRange::linear(100, 0)), InputError);
  // A valid range still launches afterwards.
  queue->launch(*kernel, compute::NdRange::linear(100, 4));
  queue->finish();
  CHECK(x.download() == std::vector<float>(100, 1.0f));
}
