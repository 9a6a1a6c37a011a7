// Synthesizer: one frame = trajectory pose -> rendered object -> wall and occluder -> sensor model.
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <string>
#include <vector>

#include "reference/rasterizer.hpp"
#include "synth/ideal_sensor.hpp"
#include "synth/occluder.hpp"
#include "synth/random.hpp"
#include "synth/structured_light_sensor.hpp"
#include "synth/trajectory.hpp"
#include "synth/validate_config.hpp"

namespace depthtrack {

namespace {
constexpr double kNear = 0.05, kFar = 10.0;  // metres: clip planes of the object's rendering

SynthConfig checked(const Mesh& mesh, const SynthConfig& config) {
  synth::validate_config(config);
  if (mesh.vertices.empty() || mesh.triangles.empty())
    throw InputError("synthetic sequence: the mesh has no triangles to render");
  return config;
}
}  // namespace

struct Synthesizer::Impl {
  SynthConfig config;
  Eigen::Vector3d mesh_centre;
  reference::Rasterizer rasterizer;

  Impl(const Mesh& mesh, const SynthConfig& c)
      : config(checked(mesh, c)), mesh_centre(mesh.centre().cast<double>()), rasterizer(mesh, c.camera, kNear, kFar) {}
};

Synthesizer::Synthesizer(const Mesh& mesh, const SynthConfig& config) : impl_(std::make_unique<Impl>(mesh, config)) {}
Synthesizer::~Synthesizer() = default;
Synthesizer::Synthesizer(Synthesizer&&) noexcept = default;

const SynthConfig& Synthesizer::config() const {
  return impl_->config;
}

Pose Synthesizer::ground_truth(double timestamp) const {
  const SynthConfig& c = impl_->config;
  Pose pose = synth::trajectory_pose(c.trajectory, impl_->mesh_centre, timestamp);
  if (c.hidden_until > c.hidden_from && timestamp >= c.hidden_until) pose.translation += c.reappear_offset;
  return pose;
}

SynthFrame Synthesizer::frame(int index) const {
  const SynthConfig& c = impl_->config;
  if (index < 0 || index >= c.frames)
    throw InputError("synthetic sequence: frame " + std::to_string(index) + " is outside 0.." +
                     std::to_string(c.frames - 1));
  SynthFrame out;
  out.timestamp = index / c.rate;
  out.ground_truth = ground_truth(out.timestamp);

  const size_t pixels = static_cast<size_t>(c.camera.pixel_count());
  std::vector<float> object(pixels, 0.0f);
  out.hidden = c.hides(out.timestamp);
  if (!out.hidden) impl_->rasterizer.render(out.ground_truth, object);
  // The wall: what the camera sees where the object is not; it also hides object parts behind it.
  std::vector<float> scene(object);
  if (c.background_depth > 0) {
    const float wall = static_cast<float>(c.background_depth);
    for (size_t i = 0; i < pixels; ++i)
      if (object[i] <= 0.0f || object[i] > wall) {
        object[i] = 0.0f;
        scene[i] = wall;
      }
  }
  out.occluded_fraction =
      synth::add_occluder(scene, object, c.camera.width, c.camera.height, c.occluder_fraction, out.timestamp);

  if (c.sensor.kind == SensorKind::Ideal) {
    out.depth = DepthImage::from_metres(c.camera.width, c.camera.height, synth::ideal_depth(scene));
    return out;
  }
  std::mt19937_64 rng = synth::frame_rng(c.seed, index);
  out.depth =
      DepthImage::from_metres(c.camera.width, c.camera.height, synth::sense_depth(c.sensor, c.camera, scene, rng));
  return out;
}

}  // namespace depthtrack
