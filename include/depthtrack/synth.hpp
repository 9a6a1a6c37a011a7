#pragma once
/// @file
/// Synthetic depth sequences whose noise is NOT the tracker's own model: a structured-light sensor
/// (disparity quantization, depth-dependent noise, missing pixels at depth discontinuities), a
/// background wall and an optional moving occluder covering a chosen fraction of the object.
#include <cstdint>
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/sequence.hpp>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace depthtrack {

/// What the simulated camera reports: a Kinect-like structured-light sensor (the default), or the
/// scene's exact z-depth with no noise, no quantization and no holes (for measuring precision).
enum class SensorKind {
  StructuredLight,  ///< Kinect-like: disparity noise, quantization, holes at edges
  Ideal,            ///< the exact z-depth
};
/// "structured-light" or "ideal".
const char* to_string(SensorKind kind);
SensorKind sensor_kind_from_string(const std::string& name);  ///< throws InputError

/// A Kinect-like structured-light sensor: depth z = focal * baseline / disparity. An ideal sensor
/// ignores every other field.
struct SensorModel {
  SensorKind kind = SensorKind::StructuredLight;  ///< Ideal: every field below is ignored
  double baseline = 0.075;                        ///< metres
  double disparity_step = 0.125;                  ///< pixels: disparity is quantized to 1/8 px
  double disparity_noise = 0.07;                  ///< pixels, gaussian, before quantization
  double edge_threshold = 0.03;                   ///< metres of depth jump between neighbours that marks an edge
  double edge_dropout = 0.6;                      ///< probability that a pixel at an edge is missing
  double random_dropout = 0.01;                   ///< probability that any pixel is missing
  double min_depth = 0.4, max_depth = 4.5;        ///< outside this range the sensor returns nothing
};

/// Smooth 6-DoF motion: sinusoids about a centre pose.
struct TrajectoryModel {
  Eigen::Vector3d centre = {0.0, 0.0, 0.8};              ///< metres, camera frame, of the mesh's centre
  Eigen::Vector3d amplitude = {0.08, 0.05, 0.08};        ///< metres
  Eigen::Vector3d rotation_amplitude = {0.5, 0.6, 0.4};  ///< radians about the object's axes
  double period = 6.0;                                   ///< seconds of the slowest component
};

/// A synthetic clip: the camera, the sensor, the object's path and what hides it.
struct SynthConfig {
  Camera camera = Camera::make(640, 480, 525.0, 525.0, 319.5, 239.5);  ///< the depth camera
  SensorModel sensor;                                                  ///< how it measures
  TrajectoryModel trajectory;                                          ///< how the object moves
  int frames = 150;                                                    ///< frames in the clip
  double rate = 30.0;                                                  ///< Hz
  double occluder_fraction = 0.0;   ///< share of the object's visible pixels hidden, 0..0.9
  double background_depth = 1.6;    ///< metres: a wall behind the object; <= 0 for none
  double metres_per_unit = 0.0001;  ///< PNG scale written (0.1 mm)
  uint64_t seed = 7;                ///< the sensor noise's and the occluder's random numbers
  std::string object;               ///< the object's name, written as the sequence's "object" (empty: none)
  /// The object is absent (only the wall, and the occluder, are seen) for timestamps in
  /// [hidden_from, hidden_until), seconds; from hidden_until on its path is shifted by
  /// reappear_offset (camera frame, metres): it left the view and came back elsewhere.
  /// hidden_until <= hidden_from: never hidden.
  double hidden_from = 0, hidden_until = 0;
  Eigen::Vector3d reappear_offset = Eigen::Vector3d::Zero();  ///< metres, camera frame
  /// Whether the object is absent at timestamp t (seconds).
  bool hides(double t) const { return hidden_until > hidden_from && t >= hidden_from && t < hidden_until; }
};

/// One synthetic frame and its truth.
struct SynthFrame {
  double timestamp = 0;          ///< seconds
  Pose ground_truth;             ///< camera_from_object
  DepthImage depth;              ///< what the sensor saw, metres
  double occluded_fraction = 0;  ///< measured share of object pixels the occluder hid
  bool hidden = false;           ///< the object was not in the scene (SynthConfig::hidden_from)
};

/// Renders the frames of a synthetic clip of mesh (SynthConfig), each independently of the others.
class Synthesizer {
 public:
  /// InputError for an invalid mesh or configuration.
  Synthesizer(const Mesh& mesh, const SynthConfig& config);
  ~Synthesizer();                       ///< Frees the scene.
  Synthesizer(Synthesizer&&) noexcept;  ///< Moves the scene; the moved-from synthesizer is empty.
  /// Frame `index` (0 to config().frames - 1; its timestamp index / rate seconds), the same on every call.
  SynthFrame frame(int index) const;
  /// camera_from_object at timestamp (seconds) on the configured path.
  Pose ground_truth(double timestamp) const;
  /// The configuration, validated.
  const SynthConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes config.frames frames as 16-bit PNGs plus sequence.json into dir (created); on_frame(i, frame)
/// is called after frame i is written, when given. Returns the manifest written.
Sequence write_synthetic_sequence(const std::filesystem::path& dir, const Mesh& mesh, const SynthConfig& config,
                                  const std::function<void(int, const SynthFrame&)>& on_frame = {});

}  // namespace depthtrack
