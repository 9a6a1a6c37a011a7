#pragma once
// The largest image and the plausible fields of view that Camera::validate and TrackerConfig::validate
// accept: sizes and pixel counts stay far inside int and every image, atlas and stride product.
namespace depthtrack {

inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxImagePixels = 1 << 26;  // e.g. 8192x8192
// A field of view 2 atan(size / 2f), on either axis, outside these is no real lens: a unit mix-up.
inline constexpr double kMinFieldOfViewDeg = 1, kMaxFieldOfViewDeg = 179;

}  // namespace depthtrack
