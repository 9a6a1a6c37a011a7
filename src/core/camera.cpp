#include <cmath>
#include <cstdint>
#include <depthtrack/camera.hpp>
#include <depthtrack/error.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "core/image_limits.hpp"

namespace depthtrack {

Camera Camera::make(int width, int height, double fx, double fy, double cx, double cy) {
  Camera c;
  c.width = width;
  c.height = height;
  c.fx = fx;
  c.fy = fy;
  c.cx = cx;
  c.cy = cy;
  c.validate();
  return c;
}

Camera Camera::from_matrix(int width, int height, const Eigen::Matrix3d& K) {
  auto fail = [&K](const std::string& what) {
    std::ostringstream m;
    m << "camera matrix K " << what << "; K = [" << K.row(0) << "; " << K.row(1) << "; " << K.row(2) << "]";
    throw InputError(m.str());
  };
  if (!K.allFinite()) fail("has a non-finite entry");
  if (K(0, 1) != 0) fail("has skew K[0][1] = " + std::to_string(K(0, 1)) + " (depthtrack's pinhole has none)");
  if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0)
    fail("must be upper triangular with K[1][0] = K[2][0] = K[2][1] = 0");
  if (K(2, 2) != 1) fail("must end in the row 0 0 1, got K[2][2] = " + std::to_string(K(2, 2)));
  return make(width, height, K(0, 0), K(1, 1), K(0, 2), K(1, 2));
}

Eigen::Matrix3d Camera::matrix() const {
  Eigen::Matrix3d K;
  K << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return K;
}

void Camera::validate() const {
  auto fail = [](const std::string& what) { throw InputError("impossible camera intrinsics: " + what); };
  if (width <= 0 || height <= 0)
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) + " must be positive");
  if (width > kMaxImageSide || height > kMaxImageSide ||
      static_cast<int64_t>(width) * static_cast<int64_t>(height) > static_cast<int64_t>(kMaxImagePixels))
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) + " is larger than the " +
         std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) +
         " pixels in all allowed");
  if (!std::isfinite(fx) || fx <= 0) fail("focal length fx = " + std::to_string(fx) + " must be positive");
  if (!std::isfinite(fy) || fy <= 0) fail("focal length fy = " + std::to_string(fy) + " must be positive");
  // A field of view outside (1, 179) degrees is no real lens: a unit mix-up (metres for pixels) or a typo.
  const auto field_of_view = [&](const char* name, double focal, int size, const char* axis) {
    const double degrees = 2 * std::atan(size / (2 * focal)) * 180 / std::numbers::pi;
    if (degrees < kMinFieldOfViewDeg || degrees > kMaxFieldOfViewDeg) {
      std::ostringstream m;
      m << "focal length " << name << " = " << focal << " pixels gives a " << axis << " field of view of " << degrees
        << " degrees over " << size << " pixels (plausible: " << kMinFieldOfViewDeg << " to " << kMaxFieldOfViewDeg
        << ")";
      fail(m.str());
    }
  };
  field_of_view("fx", fx, width, "horizontal");
  field_of_view("fy", fy, height, "vertical");
  if (!std::isfinite(cx) || !std::isfinite(cy)) fail("principal point must be finite");
  // Real lenses put it near the image centre; a point far outside is a unit or field mix-up
  // (millimetres, or fx and cx swapped). Half an image of margin on each side is allowed.
  if (cx < -0.5 * width || cx > 1.5 * width || cy < -0.5 * height || cy > 1.5 * height) {
    std::ostringstream m;
    m << "principal point (" << cx << ", " << cy << ") is far outside the " << width << "x" << height
      << " image (allowed: within half an image of it)";
    fail(m.str());
  }
}

Camera Camera::decimated(int factor) const {
  if (factor < 1) throw InputError("decimation factor " + std::to_string(factor) + " must be at least 1");
  if (width % factor != 0 || height % factor != 0)
    throw InputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is not divisible by the decimation factor " + std::to_string(factor));
  // Pixel u' is pixel factor*u' of the original; with integer pixel centres the image
  // coordinate scales by 1/factor, principal point included (no half-pixel shift).
  return Camera::make(width / factor, height / factor, fx / factor, fy / factor, cx / factor, cy / factor);
}

int Camera::decimation_factor_for(int target_width, int target_height) const {
  if (target_width <= 0 || target_height <= 0)
    throw InputError("working resolution " + std::to_string(target_width) + "x" + std::to_string(target_height) +
                     " must be positive");
  if (width % target_width != 0 || height % target_height != 0 || width / target_width != height / target_height)
    throw InputError("working resolution " + std::to_string(target_width) + "x" + std::to_string(target_height) +
                     " is not the sensor's " + std::to_string(width) + "x" + std::to_string(height) +
                     " divided by one integer factor");
  return width / target_width;
}

}  // namespace depthtrack
