// depthtrack synth: write a synthetic depth sequence with ground truth (see synth.hpp for the model).
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/synth.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/mesh_scale_warning.hpp"
#include "cli/progress.hpp"
#include "cli/tracker_options.hpp"

namespace depthtrack::cli {

namespace {

namespace fs = std::filesystem;

// What synth itself writes into a sequence folder.
bool written_by_synth(const fs::path& file) {
  const std::string name = file.filename().string();
  return name == "sequence.json" || (name.rfind("depth_", 0) == 0 && file.extension() == ".png");
}

// --out is replaced as a whole when the run succeeds: it must be new, empty, or an earlier sequence of synth's
// (nothing in it but sequence.json and depth_*.png), so that no other file is ever lost.
void check_replaceable(const fs::path& out) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(out, error);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status)) throw InputError("--out '" + out.string() + "' exists and is not a folder");
  for (const auto& entry : fs::directory_iterator(out, error))
    if (!entry.is_regular_file() || !written_by_synth(entry.path()))
      throw InputError("--out '" + out.string() + "' is not a sequence folder written by synth (it holds '" +
                       entry.path().filename().string() + "'): give a new or empty folder");
  if (error) throw InputError("cannot read --out '" + out.string() + "': " + error.message());
}

// The sequence is written into OUT.partial, then put in OUT's place (an earlier OUT set aside and removed),
// so that a failed or interrupted run leaves an earlier sequence as it was.
class StagedFolder {
 public:
  explicit StagedFolder(const fs::path& out) : out_(out), staging_(out.string() + ".partial") {
    std::error_code error;
    if (fs::exists(fs::symlink_status(staging_, error)))
      throw InputError("'" + staging_.string() + "' is in the way: synth writes the sequence there first; remove it");
    fs::create_directories(staging_, error);
    if (error) throw InputError("cannot create folder '" + staging_.string() + "': " + error.message());
  }
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  ~StagedFolder() {
    std::error_code ignored;
    if (!committed_) fs::remove_all(staging_, ignored);
  }
  const fs::path& path() const { return staging_; }
  void commit() {
    std::error_code error;
    const fs::path previous = out_.string() + ".previous";
    const bool had_earlier = fs::exists(out_, error);
    if (had_earlier) {
      fs::remove_all(previous, error);
      fs::rename(out_, previous, error);
      if (error) throw Error("cannot move the earlier '" + out_.string() + "' aside: " + error.message());
    }
    fs::rename(staging_, out_, error);
    if (error) {
      std::error_code ignored;
      if (had_earlier) fs::rename(previous, out_, ignored);
      throw Error("cannot rename '" + staging_.string() + "' to '" + out_.string() + "': " + error.message());
    }
    committed_ = true;
    if (had_earlier) fs::remove_all(previous, error);
  }

 private:
  fs::path out_, staging_;
  bool committed_ = false;
};

struct SynthOptions {
  std::string out, mesh, resolution = "640x480", sensor = "structured-light";
  double unit_scale = 1.0;
  bool builtin = false;
  int frames = 150;
  double rate = 30.0, occluder = 0.0, background = 1.6;
  std::string hide, reappear_offset;
  std::string seed = std::to_string(SynthConfig{}.seed), object;
};

// "WxH" -> the default 640x480, 525-pixel-focal camera scaled to that size (each axis alike).
Camera camera_for(const std::string& resolution) {
  const auto [width, height] = parse_resolution(resolution);
  const double sx = width / 640.0, sy = height / 480.0;
  return Camera::make(width, height, 525.0 * sx, 525.0 * sy, (width - 1) / 2.0, (height - 1) / 2.0);
}

void run(const SynthOptions& o) {
  const Mesh mesh = o.builtin ? builtin_demo_mesh() : Mesh::load(o.mesh, o.unit_scale);
  if (!o.builtin) warn_if_mesh_scale_unusual(mesh, o.mesh, o.unit_scale);
  SynthConfig config;
  config.camera = camera_for(o.resolution);
  config.frames = o.frames;
  config.rate = o.rate;
  config.occluder_fraction = o.occluder;
  config.background_depth = o.background;
  config.seed = parse_seed(o.seed, "--seed");
  config.object = o.object;
  // <= 0 is SynthConfig's "no wall"; on the command line only 0 says so, a negative depth is a mistake.
  if (!(o.background >= 0))
    throw InputError("--background " + std::to_string(o.background) +
                     " is not a depth: give the wall's distance in metres, or 0 for no wall");
  config.sensor.kind = sensor_kind_from_string(o.sensor);
  if (!o.hide.empty()) {
    const auto v = parse_numbers(o.hide, 2, "--hide");
    if (!(v[1] > v[0])) throw InputError("--hide \"FROM UNTIL\" needs UNTIL > FROM, got '" + o.hide + "'");
    config.hidden_from = v[0];
    config.hidden_until = v[1];
  }
  if (!o.reappear_offset.empty()) {
    if (o.hide.empty()) throw InputError("--reappear-offset needs --hide (it applies from the end of the hidden time)");
    const auto v = parse_numbers(o.reappear_offset, 3, "--reappear-offset");
    config.reappear_offset = Eigen::Vector3d(v[0], v[1], v[2]);
  }

  fs::path out = fs::path(o.out).lexically_normal();
  if (!out.has_filename()) out = out.parent_path();  // "seq/" names seq
  if (out.empty() || out.filename() == "." || out.filename() == "..")
    throw InputError("--out '" + o.out + "' must name a folder by its name (not '.' or '..')");
  check_replaceable(out);
  StagedFolder folder(out);
  ProgressBar bar("synth", config.frames);
  double occluded_sum = 0;
  const Sequence written =
      write_synthetic_sequence(folder.path(), mesh, config, [&](int index, const SynthFrame& frame) {
        occluded_sum += frame.occluded_fraction;
        bar.update(index + 1);
      });
  bar.finish();
  folder.commit();
  std::cout << "wrote " << written.frames.size() << " frames (" << config.camera.width << "x" << config.camera.height
            << ", " << config.rate << " Hz), mean occluded fraction " << occluded_sum / config.frames << ", to "
            << o.out << "\n";
}
}  // namespace

void add_synth_command(CLI::App& app) {
  auto options = std::make_shared<SynthOptions>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Write a synthetic depth sequence (16-bit PNGs + sequence.json with ground-truth poses): the object moves "
      "smoothly in front of a wall, seen by a simulated structured-light sensor (quantized disparity, noise growing "
      "with depth squared, holes at depth edges), optionally behind a bar sweeping across it.");
  cmd->add_option("--out", options->out, "Folder to write the sequence into (created)")->required();
  auto* mesh =
      cmd->add_option("--mesh", options->mesh, "Object mesh file (any format assimp reads)")->check(CLI::ExistingFile);
  cmd->add_option("--unit-scale", options->unit_scale,
                  "Factor turning the mesh's coordinates into metres (0.001 for a mesh in millimetres)")
      ->needs(mesh)
      ->capture_default_str();
  auto* builtin = cmd->add_flag("--builtin", options->builtin, "Use the built-in demo object instead of --mesh");
  mesh->excludes(builtin);
  cmd->add_option("--frames", options->frames, "Number of frames")->capture_default_str();
  cmd->add_option("--rate", options->rate, "Frame rate (Hz); timestamps are frame / rate")->capture_default_str();
  cmd->add_option("--occluder", options->occluder,
                  "Share of the object's pixels a bar in front of it hides (0 = no occluder, at most 0.9)")
      ->capture_default_str();
  cmd->add_option("--sensor", options->sensor,
                  "structured-light (quantized disparity, noise, holes) or ideal (exact z-depth: no noise, no "
                  "quantization beyond the PNG's 0.1 mm, no holes)")
      ->capture_default_str();
  cmd->add_option("--hide", options->hide,
                  "\"FROM UNTIL\" seconds: the object is not in the scene then (only the wall is seen)");
  cmd->add_option("--reappear-offset", options->reappear_offset,
                  "\"DX DY DZ\" metres (camera frame): after --hide the object comes back moved by this");
  cmd->add_option("--seed", options->seed, "Seed of the sensor noise; equal seeds give identical images")
      ->capture_default_str();
  cmd->add_option("--resolution", options->resolution,
                  "Image size WIDTHxHEIGHT; the 640x480 camera with 525 px focal length is scaled to it")
      ->capture_default_str();
  cmd->add_option("--background", options->background, "Depth of the wall behind the object (metres; 0 = none)")
      ->capture_default_str();
  cmd->add_option("--object", options->object,
                  "Name of the object, written into sequence.json (what `track --object` then checks)");
  cmd->callback([options, mesh, builtin]() {
    if (mesh->count() == 0 && builtin->count() == 0)
      throw InputError("synth needs an object: --mesh FILE or --builtin");
    run(*options);
  });
}

}  // namespace depthtrack::cli
