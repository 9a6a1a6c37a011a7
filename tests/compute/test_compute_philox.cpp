// The device's Philox draws equal the host's exactly: one generator in cl/philox.h for every backend.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute_support.hpp"
#include "philox.h"

using namespace depthtrack;

namespace {
const char* const kPhiloxKernel = R"(
__kernel void draws(ulong seed, uint frame, uint stream, uint count, __global uint* words, __global float* normals) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  const dt_philox4 w = dt_random_words(seed, i, frame, stream, 0u);
  for (uint k = 0; k < 4u; ++k) words[4u * i + k] = w.v[k];
  float n[6];
  dt_normals6(seed, i, frame, stream, n);
  for (uint k = 0; k < 6u; ++k) normals[6u * i + k] = n[k];
}
)";
}  // namespace

TEST_CASE("Device Philox words and normals equal the host's", "[compute]") {
  auto queue = test::test_queue();
  if (!queue) return;
  const unsigned count = 1000, frame = 17, stream = DT_STREAM_MOTION;
  const std::uint64_t seed = 0x0123456789ABCDEFull;
  auto program = queue->build("philox", compute::kernel_source("philox.h") + kPhiloxKernel, {});
  auto kernel = program->kernel("draws");
  compute::Buffer<std::uint32_t> words(*queue, 4 * count);
  compute::Buffer<float> normals(*queue, 6 * count);
  queue->launch(*kernel, compute::NdRange::linear(1024, 64), seed, frame, stream, count, words, normals);
  const auto device_words = words.download();
  const auto device_normals = normals.download();

  unsigned word_mismatches = 0, normal_mismatches = 0;
  for (unsigned i = 0; i < count; ++i) {
    const dt_philox4 w = dt_random_words(seed, i, frame, stream, 0u);
    for (unsigned k = 0; k < 4; ++k) word_mismatches += device_words[4 * i + k] != w.v[k];
    float n[6];
    dt_normals6(seed, i, frame, stream, n);
    for (unsigned k = 0; k < 6; ++k) normal_mismatches += std::fabs(device_normals[6 * i + k] - n[k]) > 1e-5f;
  }
  CHECK(word_mismatches == 0);
  CHECK(normal_mismatches == 0);
}
