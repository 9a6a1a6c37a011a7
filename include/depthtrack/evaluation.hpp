#pragma once
/// @file
/// Running a tracker over a sequence and scoring it against ground truth.
#include <cmath>
#include <cstdint>
#include <depthtrack/frame_source.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/sequence.hpp>
#include <depthtrack/tracker.hpp>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace depthtrack {

/// One tracked frame of a run: its estimate and, where the truth is known, its errors.
struct TrackedFrame {
  std::string name;                  ///< the frame's name in its source (e.g. "000001")
  double timestamp = 0;              ///< seconds
  Estimate estimate;                 ///< the tracker's output for the frame
  std::optional<Pose> ground_truth;  ///< camera_from_object, when the source knows it
  double translation_error = NAN;    ///< metres, when ground truth is known
  double rotation_error = NAN;       ///< radians
  double adds = NAN;                 ///< ADD-S of the estimate against the truth (metres), when known
  double latency_ms = NAN;           ///< wall time from the decoded depth image handed in to the pose out
};

/// Tracks every frame of source, from the given initial pose, until the source ends; on_frame(i, frame) is
/// called after each frame (progress, printing, writing as frames arrive). Frames with ground truth are
/// scored. InputError for a frame that cannot be read (the source's) or whose depth is not the camera's
/// size, and when no frame had a valid depth pixel.
std::vector<TrackedFrame> track_source(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                       const Pose& initial, const InitialSpread& spread,
                                       const std::function<void(size_t, const TrackedFrame&)>& on_frame = {});

/// As track_source, without an initial pose: the first frame is searched within hint
/// (Tracker::initialize_global), the rest are tracked.
std::vector<TrackedFrame> track_source_global(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                              const InitHint& hint,
                                              const std::function<void(size_t, const TrackedFrame&)>& on_frame = {});

/// Tracks every frame of the sequence (through sequence_source) from the given initial pose; on_frame(i, frame) is
/// called after each frame (progress, printing). Depth images are decoded on a reader thread a few frames ahead, so
/// that decoding overlaps the tracker's work.
std::vector<TrackedFrame> track_sequence(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                         const Pose& initial, const InitialSpread& spread,
                                         const std::function<void(size_t, const TrackedFrame&)>& on_frame = {});

/// Tracks every frame of the sequence without an initial pose: the first frame is searched within
/// hint (Tracker::initialize_global), the rest are tracked.
std::vector<TrackedFrame> track_sequence_global(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                                const InitHint& hint,
                                                const std::function<void(size_t, const TrackedFrame&)>& on_frame = {});

/// pose moved by exactly `metres` in a direction and rotated by exactly `degrees` about an axis
/// through the mesh's centre, both drawn from seed: a reproducible "start from perturbed ground truth".
/// InputError for a non-finite distance, angle or centre.
Pose perturb_pose(const Pose& pose, const Eigen::Vector3d& centre, double metres, double degrees, uint64_t seed);

/// ADD-S: mean over the model's vertices, placed by the estimate, of the distance to the closest
/// vertex placed by the truth (symmetric objects score by shape, not by unobservable rotation).
class AddsMetric {
 public:
  /// Indexes mesh's vertices for the nearest-vertex queries.
  explicit AddsMetric(const Mesh& mesh);
  ~AddsMetric();  ///< Frees the index.
  /// ADD-S of estimate against truth, metres.
  double operator()(const Pose& estimate, const Pose& truth) const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
  std::vector<Eigen::Vector3d> vertices_;
};

/// Order of a quaternion's components in text: w first (Eigen, depthtrack's default) or last (ROS,
/// tf2, SciPy).
enum class QuaternionOrder {
  Wxyz,  ///< qw qx qy qz
  Xyzw,  ///< qx qy qz qw
};

/// One object of a several-object run: its mesh, the sequence loaded with its ground truth (every
/// object's sequence is the same clip) and its start.
struct TrackedObject {
  std::string name;   ///< the object's name in the outputs
  Mesh mesh;          ///< its mesh, metres
  Sequence sequence;  ///< the clip, with this object's ground truth
  Pose initial;       ///< camera_from_object at the first frame
};

/// Tracks several objects through one clip with a MultiTracker on one Device (opened from config.backend):
/// each frame is decoded once and every object updated in turn; mutual_occlusion as MultiTracker's. Returns
/// each object's frames (latency_ms: the whole frame's, all objects); on_frame(i, object, frame) after each.
std::vector<std::vector<TrackedFrame>> track_objects(
    const std::vector<TrackedObject>& objects, const TrackerConfig& config, const InitialSpread& spread,
    bool mutual_occlusion, const std::function<void(size_t, size_t, const TrackedFrame&)>& on_frame = {});

/// CSV with a header and a row per frame: frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess (qx,qy,qz,qw with
/// Xyzw) and, when every frame has ground truth, err_t_mm,err_r_deg,adds_mm; then latency_ms (depth in
/// to pose out), confidence and status (tracking, lost, no-data). Written through TrackingCsvWriter (below).
void write_tracking_csv(const std::filesystem::path& path, const std::vector<TrackedFrame>& frames,
                        QuaternionOrder order = QuaternionOrder::Wxyz);

/// BOP's result CSV (bop_toolkit): scene_id,im_id,obj_id,score,R,t,time per frame, R row-major and
/// t in mm, space-separated; score is the estimate's confidence, time the filter's seconds for
/// the frame. The sequence must be a BOP scene with an obj_id (check_bop_exportable throws
/// InputError otherwise).
void check_bop_exportable(const Sequence& sequence);
/// Writes frames of sequence as BOP's result CSV (above) to path; check_bop_exportable's InputError first,
/// an Error naming the file when it cannot be written.
void write_bop_csv(const std::filesystem::path& path, const Sequence& sequence,
                   const std::vector<TrackedFrame>& frames);

/// The same CSV, row by row while tracking, so that output that cannot lie: the constructor checks
/// the place (an existing folder, path not a folder) before any work; rows go to PATH.partial, which
/// finish() renames to PATH; without finish() (an error, an exception) the partial file is removed
/// and an earlier PATH stays untouched. A device such as /dev/stdout or /dev/full is written directly.
/// Every write and the final flush are checked: a failure is an Error naming the file.
class TrackingCsvWriter {
 public:
  /// object_column: an `object` column first (several objects in one run), named by write's object.
  TrackingCsvWriter(const std::filesystem::path& path, bool with_ground_truth,
                    QuaternionOrder order = QuaternionOrder::Wxyz, bool object_column = false);
  ~TrackingCsvWriter();  ///< Without finish(): removes PATH.partial, PATH stays as it was.
  TrackingCsvWriter(const TrackingCsvWriter&) = delete;             ///< One writer per file: not copied.
  TrackingCsvWriter& operator=(const TrackingCsvWriter&) = delete;  ///< One writer per file: not copied.

  /// Appends frame's row (object: the `object` column's value where the writer has one).
  void write(const TrackedFrame& frame, const std::string& object = "");
  /// Flushes and renames PATH.partial to PATH; an Error naming the file when that fails.
  void finish();

 private:
  struct Stream;
  std::unique_ptr<Stream> stream_;
  std::filesystem::path path_, partial_;
  bool with_ground_truth_;
  QuaternionOrder order_;
  bool object_column_;
};

}  // namespace depthtrack
