#pragma once
/// Depth sequences on disk: depthtrack's own layout (what `depthtrack synth` writes; 16-bit PNG or .f32 depth),
/// the YCB-Video clip layout (NNNNNN-depth.png + gt.json), a BOP scene (scene_camera.json, scene_gt.json,
/// depth/NNNNNN.png) and ViSP's simulated sequences (Depth/, CameraPose/, Config/). Streams: frame_source.hpp.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/pose.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace depthtrack {

/// One frame of a folder sequence: where its depth lies, when it was taken and, where known, the truth.
struct SequenceFrame {
  std::string name;                   ///< e.g. "000001"
  double timestamp = 0;               ///< seconds
  std::filesystem::path depth_path;   ///< its depth image (16-bit PNG, float32 *.f32, ViSP .bin)
  std::filesystem::path colour_path;  ///< a colour image registered to the depth, when the sequence has one
  std::optional<Pose> ground_truth;   ///< camera_from_object of the selected object, when known
};

/// A folder sequence as load_sequence reads it: the camera, the depth scale and the frames.
struct Sequence {
  std::string format;                 ///< "depthtrack", "ycb-video", "bop" or "visp-simulated"
  std::string object;                 ///< the object whose ground truth the frames carry ("" if none; BOP: its obj_id)
  int scene_id = 0;                   ///< BOP: the scene folder's number
  Camera camera;                      ///< intrinsics of the depth images
  double metres_per_unit = 0.001;     ///< 16-bit PNG value -> metres
  std::vector<SequenceFrame> frames;  ///< in time order

  /// Loads frame i's depth image (16-bit PNG, float32 metres named *.f32, or ViSP's .bin) and checks its size.
  DepthImage load_depth(size_t i) const;
};

/// Reads any of the layouts from dir (detected from its files). object picks the ground truth of one
/// object in a multi-object clip (YCB-Video: a name; BOP: the obj_id); it may be omitted when the
/// clip has only one.
/// Throws InputError for a missing folder, unknown layout, corrupt manifest or unknown object
/// (the message lists the objects present). ViSP's: the castle's depth camera offset (5 cm along -x), 30 Hz.
Sequence load_sequence(const std::filesystem::path& dir, const std::string& object = "");

/// depthtrack's own layout: dir/sequence.json (camera, scale, frames with timestamps and optional
/// ground truth, row-major 4x4) beside the depth files it names: 16-bit PNGs, or float32 metres named *.f32.
void write_sequence_manifest(const std::filesystem::path& dir, const Sequence& sequence);

}  // namespace depthtrack
