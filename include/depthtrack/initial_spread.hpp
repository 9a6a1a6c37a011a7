#pragma once
/// @file
/// How widely the particles start around a given pose.

#include <numbers>

namespace depthtrack {

/// Spread of the initial particle cloud around a start pose: per-axis standard deviations of the
/// translation and of the rotation (about the mesh's centre, object frame). Tracker::initialize refuses
/// (InputError) a spread that is not finite, negative, beyond max_depth or beyond a full turn. The
/// defaults are those of `depthtrack track --init-spread` and of Tracker.initialize in Python.
struct InitialSpread {
  static constexpr double kDefaultMetres = 0.01, kDefaultDegrees = 5.0;
  double metres = kDefaultMetres;                               ///< translation, metres
  double radians = kDefaultDegrees * std::numbers::pi / 180.0;  ///< rotation, radians
};

}  // namespace depthtrack
