#pragma once
// The objects a sequence folder carries ground truth for, so that an evaluation can run each in turn
// (load_sequence loads one object's).
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack {

struct ClipObject {
  std::string name;  // what load_sequence's object takes: a YCB-Video name, a BOP obj_id, or "" (depthtrack's own)
  int label = -1;    // YCB-Video: cls_index, the object's pixel value in the label images; -1 elsewhere
};

// In order of first appearance (YCB-Video), ascending obj_id (BOP), or the one object of depthtrack's own
// layout. InputError as load_sequence's for a folder of no known layout or a corrupt manifest.
std::vector<ClipObject> clip_objects(const std::filesystem::path& dir);

}  // namespace depthtrack
