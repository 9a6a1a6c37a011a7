/* The per-pixel observation and occlusion model of MODEL.md in float, for the weigh kernel.
 * src/reference/observation_model.cpp is the double-precision statement it is tested against. */
#ifndef DT_MODEL_H
#define DT_MODEL_H
#include "dt_params.h"
#include "dt_prelude.h"

/* The depth noise at observed depth y (reference::depth_sigma). */
DT_FN float dt_depth_sigma(const dt_model m, float y) {
  return m.sigma_constant + m.sigma_quadratic * y * y;
}

/* log(((1 - p) p_vis + p p_occ) / p_bg) for observed y, rendered y_hat; *posterior gets p's Bayes update. */
DT_FN float dt_pixel_log_ratio(const dt_model m, float y, float y_hat, float p, float* posterior) {
  const float sigma = dt_depth_sigma(m, y);
  const float z = (y - y_hat) / sigma;
  const float ls2 = m.lambda * sigma * sigma;
  /* All three densities divided by exp(log_scale), as in the reference: lambda exp(exponent), the
   * background, overflows in float for depths beyond ~150 m. */
  const float exponent = m.lambda * (0.5f * ls2 - y);
  const float log_scale = fmax(0.0f, exponent);
  const float scale = exp(-log_scale);
  const float background_part = m.keep * m.lambda * exp(exponent - log_scale);
  const float in_front = erfc(-(y_hat - y + ls2) / (1.4142135624f * sigma)) / (-2.0f * expm1(-m.lambda * y_hat));
  const float visible = (m.tail_density + m.keep * exp(-0.5f * z * z) / (2.5066282746f * sigma)) * scale;
  const float occluded = m.tail_density * scale + background_part * in_front;
  const float background = m.tail_density * scale + background_part;
  const float mixture = (1.0f - p) * visible + p * occluded;
  *posterior = p * occluded / mixture;
  return log(mixture / background);
}

/* Occlusion probability dt seconds later: p_inf + c^dt (p - p_inf). */
DT_FN float dt_propagate_occlusion(const dt_model m, float p, float dt) {
  return m.p_inf + exp(dt * m.log_c) * (p - m.p_inf);
}
#endif
