#pragma once
// The 2D box of one object's pixels in a label image (8-bit PNG, an object id per pixel, as YCB-Video's
// NNNNNN-label.png): the box a detector would hand the tracker.
#include <array>
#include <filesystem>
#include <optional>

namespace depthtrack {

// {u0, v0, u1, v1}, inclusive pixels; nullopt when no pixel carries id. InputError for an id outside
// 0..255 or a file that cannot be read or decoded.
std::optional<std::array<int, 4>> label_box(const std::filesystem::path& path, int id);

// The label image of a YCB-Video frame: NNNNNN-label.png beside NNNNNN-depth.png; empty when the depth
// image is not named so or the label image is not there.
std::filesystem::path label_image_beside(const std::filesystem::path& depth);

}  // namespace depthtrack
