/* Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011):
 * a counter-based generator, so every particle's draws depend only on (seed, frame, particle,
 * stream, draw) and every backend produces the same particles for the same seed.
 * Shared by the device kernels and the reference tracker (see dt_prelude.h). */
#ifndef DT_PHILOX_H
#define DT_PHILOX_H
#include "dt_prelude.h"

/* What a draw is for: keeps the streams of different uses apart. */
#define DT_STREAM_INIT 0u
#define DT_STREAM_MOTION 1u
#define DT_STREAM_RESAMPLE 2u
#define DT_STREAM_SEARCH 3u /* the global search's perturbations */
#define DT_STREAM_RESIZE 4u /* the host filter changing its particle count */

typedef struct {
  dt_u32 v[4];
} dt_philox4;

DT_FN dt_philox4 dt_philox4x32_10(dt_philox4 ctr, dt_u32 k0, dt_u32 k1) {
  for (int round = 0; round < 10; ++round) {
    const dt_u32 lo0 = 0xD2511F53u * ctr.v[0], hi0 = dt_mulhi(0xD2511F53u, ctr.v[0]);
    const dt_u32 lo1 = 0xCD9E8D57u * ctr.v[2], hi1 = dt_mulhi(0xCD9E8D57u, ctr.v[2]);
    dt_philox4 next;
    next.v[0] = hi1 ^ ctr.v[1] ^ k0;
    next.v[1] = lo1;
    next.v[2] = hi0 ^ ctr.v[3] ^ k1;
    next.v[3] = lo0;
    ctr = next;
    k0 += 0x9E3779B9u; /* golden ratio */
    k1 += 0xBB67AE85u; /* sqrt(3) - 1 */
  }
  return ctr;
}

/* Four words for (seed, particle, frame, stream, draw). */
DT_FN dt_philox4 dt_random_words(dt_u64 seed, dt_u32 particle, dt_u32 frame, dt_u32 stream, dt_u32 draw) {
  dt_philox4 ctr;
  ctr.v[0] = particle;
  ctr.v[1] = frame;
  ctr.v[2] = stream;
  ctr.v[3] = draw;
  return dt_philox4x32_10(ctr, DT_CAST(dt_u32, seed), DT_CAST(dt_u32, seed >> 32));
}

/* Uniform in [0, 1) with 24 random bits: exact in float on every backend. */
DT_FN float dt_uniform01(dt_u32 word) { return DT_CAST(float, word >> 8) * (1.0f / 16777216.0f); }
/* Uniform in (0, 1]: safe for a logarithm. */
DT_FN float dt_uniform01_open(dt_u32 word) { return (DT_CAST(float, word >> 8) + 1.0f) * (1.0f / 16777216.0f); }

/* Six standard normals (Box-Muller on two Philox calls), the draws of one particle's 6-DoF step. */
DT_FN void dt_normals6(dt_u64 seed, dt_u32 particle, dt_u32 frame, dt_u32 stream, float out[6]) {
  for (dt_u32 call = 0; call < 2u; ++call) {
    const dt_philox4 w = dt_random_words(seed, particle, frame, stream, call);
    for (dt_u32 pair = 0; pair < 2u; ++pair) {
      const dt_u32 slot = call * 4u + pair * 2u;
      if (slot >= 6u) break;
      const float r = dt_sqrtf(-2.0f * dt_logf(dt_uniform01_open(w.v[pair * 2u])));
      const float turn = 2.0f * dt_uniform01(w.v[pair * 2u + 1u]);
      out[slot] = r * dt_cospif(turn);
      out[slot + 1u] = r * dt_sinpif(turn);
    }
  }
}

#endif
