// Philox4x32-10 against the published known-answer vectors (Random123, kat_vectors).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "philox.h"

TEST_CASE("Philox4x32-10 known answers", "[random]") {
  struct Kat {
    dt_u32 ctr[4], key[2], out[4];
  };
  const Kat kats[] = {
      {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
      {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
       {0xffffffff, 0xffffffff},
       {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
      {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
       {0xa4093822, 0x299f31d0},
       {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
  };
  for (const Kat& k : kats) {
    dt_philox4 ctr;
    for (int i = 0; i < 4; ++i) ctr.v[i] = k.ctr[i];
    const dt_philox4 out = dt_philox4x32_10(ctr, k.key[0], k.key[1]);
    for (int i = 0; i < 4; ++i) CHECK(out.v[i] == k.out[i]);
  }
}

TEST_CASE("uniforms and normals have the right range and moments", "[random]") {
  CHECK(dt_uniform01(0u) == 0.0f);
  CHECK(dt_uniform01(0xffffffffu) < 1.0f);
  CHECK(dt_uniform01_open(0u) > 0.0f);
  CHECK(dt_uniform01_open(0xffffffffu) == 1.0f);
  double sum = 0, sum_sq = 0;
  const int particles = 20000;
  for (int i = 0; i < particles; ++i) {
    float n[6];
    dt_normals6(42, static_cast<dt_u32>(i), 3, DT_STREAM_MOTION, n);
    for (float x : n) {
      sum += x;
      sum_sq += x * x;
    }
  }
  const double count = 6.0 * particles;
  CHECK(std::abs(sum / count) < 0.02);
  CHECK(sum_sq / count == Approx(1.0).margin(0.02));
}

TEST_CASE("draws depend on every part of the key", "[random]") {
  float base[6], other[6];
  dt_normals6(1, 5, 7, DT_STREAM_MOTION, base);
  for (int change = 0; change < 4; ++change) {
    dt_normals6(change == 0 ? 2 : 1, change == 1 ? 6 : 5, change == 2 ? 8 : 7,
                change == 3 ? DT_STREAM_INIT : DT_STREAM_MOTION, other);
    CHECK(other[0] != base[0]);
  }
  dt_normals6(1, 5, 7, DT_STREAM_MOTION, other);
  for (int i = 0; i < 6; ++i) CHECK(other[i] == base[i]);
}
