#include "tracker/silhouette_shares.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "reference/observation_model.hpp"

namespace depthtrack {

namespace {
struct PlanePoint {
  double u, v, y, sigma;
};

// Root mean square of (y - plane) / sigma for the plane y = a + b u + c v minimizing it (weights
// 1 / sigma^2); pixel coordinates and depths are taken about their means so that the normal equations
// stay well conditioned. A degenerate spread (all pixels on one line) keeps the line's fit.
double plane_rms(const std::vector<PlanePoint>& points) {
  double mu = 0, mv = 0, my = 0;
  for (const PlanePoint& p : points) mu += p.u, mv += p.v, my += p.y;
  const double n = static_cast<double>(points.size());
  mu /= n, mv /= n, my /= n;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const PlanePoint& p : points) {
    const Eigen::Vector3d x(1.0, p.u - mu, p.v - mv);
    const double w = 1.0 / (p.sigma * p.sigma);
    normal += w * x * x.transpose();
    rhs += w * (p.y - my) * x;
  }
  const Eigen::Vector3d plane = normal.completeOrthogonalDecomposition().solve(rhs);
  double squares = 0;
  for (const PlanePoint& p : points) {
    const double r = (p.y - my - plane.dot(Eigen::Vector3d(1.0, p.u - mu, p.v - mv))) / p.sigma;
    squares += r * r;
  }
  return std::sqrt(squares / n);
}
}  // namespace

SilhouetteShares silhouette_shares(const reference::Rasterizer& rasterizer, const ObservationModel& model,
                                   double pixel_sigmas, const Pose& pose, const DepthImage& depth,
                                   std::span<float> scratch) {
  const reference::PixelBox box = rasterizer.render(pose, scratch);
  return silhouette_shares(scratch, box, model, pixel_sigmas, depth);
}

SilhouetteShares silhouette_shares(std::span<const float> scratch, const reference::PixelBox& box,
                                   const ObservationModel& model, double pixel_sigmas, const DepthImage& depth) {
  const int width = depth.width();
  int visible = 0, occluded = 0, contradicted = 0, missing = 0;
  double visible_squares = 0;
  std::vector<PlanePoint> seen;
  for (int v = box.v0; v < box.v1; ++v)
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      const double y_hat = scratch[k];
      if (y_hat <= 0) continue;
      const float y = depth.data()[k];
      if (!DepthImage::is_valid(y)) {
        ++missing;
        continue;
      }
      switch (reference::band_side(model, pixel_sigmas, y, y_hat)) {
        case reference::BandSide::Nearer:
          ++occluded;
          break;
        case reference::BandSide::Behind:
          ++contradicted;
          break;
        case reference::BandSide::Within: {
          ++visible;
          const double sigma = reference::depth_sigma(model, y);
          const double z = (y - y_hat) / sigma;
          visible_squares += z * z;
          seen.push_back({static_cast<double>(u), static_cast<double>(v), static_cast<double>(y), sigma});
        }
      }
    }
  // The outline: each uncovered 4-neighbour of a covered pixel, once per covered neighbour.
  const int height = depth.height();
  int outline = 0, past_edge = 0, nearer = 0;
  for (int v = box.v0; v < box.v1; ++v)
    for (int u = box.u0; u < box.u1; ++u) {
      const double y_hat = scratch[static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u)];
      if (y_hat <= 0) continue;
      const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
      for (int n = 0; n < 4; ++n) {
        const int nu = u + du[n], nv = v + dv[n];
        if (nu < 0 || nv < 0 || nu >= width || nv >= height) continue;
        const size_t k = static_cast<size_t>(nv) * static_cast<size_t>(width) + static_cast<size_t>(nu);
        if (scratch[k] > 0) continue;
        ++outline;
        const float y = depth.data()[k];
        if (!DepthImage::is_valid(y)) {
          ++past_edge;
          continue;
        }
        const reference::BandSide side = reference::band_side(model, pixel_sigmas, y, y_hat);
        past_edge += side == reference::BandSide::Behind;
        nearer += side == reference::BandSide::Nearer;
      }
    }
  SilhouetteShares s;
  if (outline > nearer) s.separated = static_cast<double>(past_edge) / (outline - nearer);
  if (outline > 0) s.outline_nearer = static_cast<double>(nearer) / outline;
  s.outline = outline;
  if (visible > 0) s.visible_rms = std::sqrt(visible_squares / visible);
  s.plane_rms = seen.size() >= kPlanePixels ? plane_rms(seen) : s.visible_rms;
  s.pixels = visible + occluded + contradicted + missing;
  const int measured = visible + occluded + contradicted;
  if (s.pixels > 0) s.missing = static_cast<double>(missing) / s.pixels;
  if (measured > 0) {
    s.visible = static_cast<double>(visible) / measured;
    s.occluded = static_cast<double>(occluded) / measured;
    s.contradicted = static_cast<double>(contradicted) / measured;
  }
  return s;
}

}  // namespace depthtrack
