#pragma once
// Internal to the I/O layer: one reader per sequence layout; load_sequence picks between them.
#include <depthtrack/sequence.hpp>
#include <filesystem>
#include <string>

namespace depthtrack::io {

inline constexpr const char* kDepthtrackManifest = "sequence.json";
inline constexpr const char* kYcbVideoManifest = "gt.json";
inline constexpr const char* kBopManifest = "scene_camera.json";

Sequence load_depthtrack_sequence(const std::filesystem::path& dir, const std::string& object);
Sequence load_ycb_video_sequence(const std::filesystem::path& dir, const std::string& object);
Sequence load_bop_sequence(const std::filesystem::path& dir, const std::string& object);

}  // namespace depthtrack::io
