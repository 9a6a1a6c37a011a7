// OpenCL nd-ranges turned into CUDA grids, checked before the driver sees them (no GPU needed).
#if defined(DEPTHTRACK_WITH_CUDA)
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_launch.hpp"
#include "compute/cuda/cuda_stream.hpp"

using namespace depthtrack;
namespace cuda = depthtrack::compute::cuda;

namespace {
cuda::LaunchLimits h100_like() {
  cuda::LaunchLimits limits;
  limits.max_threads = 1024;
  limits.max_block[0] = limits.max_block[1] = 1024;
  limits.max_block[2] = 64;
  limits.max_grid[0] = 2147483647;
  limits.max_grid[1] = limits.max_grid[2] = 65535;
  return limits;
}

cuda::LaunchShape shape(const compute::NdRange& range) {
  return cuda::launch_shape(range, h100_like(), "k", "test");
}
}  // namespace

TEST_CASE("A CUDA launch has global/local blocks of local threads", "[cuda]") {
  const auto linear = shape(compute::NdRange::linear(1024, 64));
  CHECK(linear.grid[0] == 16);
  CHECK(linear.block[0] == 64);
  CHECK(linear.grid[1] == 1);
  CHECK(linear.block[2] == 1);
  const auto planar = shape(compute::NdRange{{32, 8, 1}, {16, 4, 1}, 2});
  CHECK(planar.grid[0] == 2);
  CHECK(planar.grid[1] == 2);
  CHECK(planar.block[1] == 4);
  // Sizes past `dimensions` do not count.
  CHECK(shape(compute::NdRange{{8, 0, 0}, {8, 0, 0}, 1}).grid[1] == 1);
}

TEST_CASE("Malformed CUDA launches are input errors, oversized ones backend errors", "[cuda]") {
  CHECK_THROWS_AS(shape(compute::NdRange::linear(100, 64)), InputError);
  CHECK_THROWS_AS(shape(compute::NdRange::linear(100, 0)), InputError);
  CHECK_THROWS_AS(shape(compute::NdRange::linear(0, 4)), InputError);
  CHECK_THROWS_AS(shape(compute::NdRange{{4, 1, 1}, {4, 1, 1}, 4}), InputError);
  CHECK_THROWS_AS(shape(compute::NdRange::linear(4096, 2048)), BackendError);
  CHECK_THROWS_AS(shape(compute::NdRange{{64, 64, 1}, {64, 32, 1}, 2}), BackendError);    // 2048 threads
  CHECK_THROWS_AS(shape(compute::NdRange{{128, 1, 128}, {1, 1, 128}, 3}), BackendError);  // z > 64
  CHECK_THROWS_AS(shape(compute::NdRange{{1, 65536, 1}, {1, 1, 1}, 2}), BackendError);    // grid y
  try {
    shape(compute::NdRange::linear(100, 64));
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("100") != std::string::npos);
    CHECK(std::string(e.what()).find("64") != std::string::npos);
  }
}

// A context's queues take stream priorities in the order they were made, the first the most urgent
// (CUDA: lower numbers, within a range such as [-5, 0]), and share the least urgent once it runs out.
TEST_CASE("A CUDA context's queues take priorities in the order they were made", "[cuda]") {
  CHECK(cuda::ranked_stream_priority(0, 0, -5) == -5);
  CHECK(cuda::ranked_stream_priority(1, 0, -5) == -4);
  CHECK(cuda::ranked_stream_priority(4, 0, -5) == -1);
  CHECK(cuda::ranked_stream_priority(5, 0, -5) == 0);
  CHECK(cuda::ranked_stream_priority(4000000000u, 0, -5) == 0);
  CHECK(cuda::ranked_stream_priority(2, 3, 1) == 3);  // a range of 1 .. 3 (most urgent 1)
  CHECK(cuda::ranked_stream_priority(0, 0, 0) == 0);  // one level: every stream the default
}
#endif
