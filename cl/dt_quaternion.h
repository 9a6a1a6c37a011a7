/* Unit quaternions in float for the kernels: product, rotation of a vector, exp and log maps. */
#ifndef DT_QUATERNION_H
#define DT_QUATERNION_H
#include "dt_prelude.h"

typedef struct {
  float w, x, y, z;
} dt_quat;

typedef struct {
  float x, y, z;
} dt_vec3;

DT_FN dt_vec3 dt_vec3_make(float x, float y, float z) {
  dt_vec3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}

DT_FN dt_quat dt_quat_mul(dt_quat a, dt_quat b) {
  dt_quat r;
  r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
  r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
  r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
  r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
  return r;
}

DT_FN dt_quat dt_quat_conj(dt_quat q) {
  q.x = -q.x;
  q.y = -q.y;
  q.z = -q.z;
  return q;
}

DT_FN dt_quat dt_quat_normalize(dt_quat q) {
  const float s = 1.0f / sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  q.w *= s;
  q.x *= s;
  q.y *= s;
  q.z *= s;
  return q;
}

/* q v q* for a unit quaternion, via t = 2 (q.xyz x v): v + w t + q.xyz x t. */
DT_FN dt_vec3 dt_quat_rotate(dt_quat q, dt_vec3 v) {
  const float tx = 2.0f * (q.y * v.z - q.z * v.y);
  const float ty = 2.0f * (q.z * v.x - q.x * v.z);
  const float tz = 2.0f * (q.x * v.y - q.y * v.x);
  return dt_vec3_make(v.x + q.w * tx + (q.y * tz - q.z * ty), v.y + q.w * ty + (q.z * tx - q.x * tz),
                      v.z + q.w * tz + (q.x * ty - q.y * tx));
}

/* Rotation by the rotation vector v (axis * angle). */
DT_FN dt_quat dt_quat_exp(dt_vec3 v) {
  const float angle = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  dt_quat q;
  if (angle < 1e-6f) {
    q.w = 1.0f;
    q.x = 0.5f * v.x;
    q.y = 0.5f * v.y;
    q.z = 0.5f * v.z;
    return dt_quat_normalize(q);
  }
  const float s = sin(0.5f * angle) / angle;
  q.w = cos(0.5f * angle);
  q.x = s * v.x;
  q.y = s * v.y;
  q.z = s * v.z;
  return q;
}

/* Rotation vector of q, taking the shorter way round. */
DT_FN dt_vec3 dt_quat_log(dt_quat q) {
  if (q.w < 0.0f) {
    q.w = -q.w;
    q.x = -q.x;
    q.y = -q.y;
    q.z = -q.z;
  }
  const float s = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
  const float scale = s < 1e-6f ? 2.0f : 2.0f * atan2(s, q.w) / s;
  return dt_vec3_make(q.x * scale, q.y * scale, q.z * scale);
}
#endif
