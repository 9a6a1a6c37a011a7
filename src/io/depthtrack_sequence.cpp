// depthtrack's own sequence layout: sequence.json beside the 16-bit depth PNGs it names.
#include <cmath>
#include <depthtrack/error.hpp>
#include <fstream>

#include "io/json_fields.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack {

namespace {

constexpr const char* kFormat = "depthtrack-sequence";
constexpr int kVersion = 1;

Camera read_camera(const io::JsonField& c) {
  try {
    return Camera::make(c["width"].integer(), c["height"].integer(), c["fx"].number(), c["fy"].number(),
                        c["cx"].number(), c["cy"].number());
  } catch (const InputError& e) {
    throw InputError("'" + c.file() + "': camera: " + e.what());
  }
}

SequenceFrame read_frame(const io::JsonField& f, const std::filesystem::path& dir) {
  SequenceFrame frame;
  frame.name = f["name"].string();
  frame.timestamp = f["timestamp"].number();
  const std::string depth = f["depth"].string();
  if (depth.empty()) f["depth"].fail("is empty");
  frame.depth_path = dir / depth;
  if (f.has("T_cam_obj") && !f["T_cam_obj"].json().is_null()) frame.ground_truth = f["T_cam_obj"].pose();
  return frame;
}

// The manifest stores depth files relative to dir; frames usually hold dir / name.
std::string relative_depth_name(const std::filesystem::path& depth, const std::filesystem::path& dir) {
  if (depth.empty()) throw InputError("cannot write a sequence manifest: a frame has no depth file");
  if (!depth.has_parent_path()) return depth.generic_string();
  const auto relative = std::filesystem::weakly_canonical(std::filesystem::absolute(depth))
                            .lexically_relative(std::filesystem::weakly_canonical(std::filesystem::absolute(dir)));
  if (relative.empty())
    throw InputError("cannot write a sequence manifest: depth file '" + depth.string() +
                     "' cannot be named relative to '" + dir.string() + "'");
  return relative.generic_string();
}

}  // namespace

Sequence io::load_depthtrack_sequence(const std::filesystem::path& dir, const std::string& object) {
  const auto path = dir / kDepthtrackManifest;
  const nlohmann::json json = JsonField::read_file(path);
  const JsonField root(json, path.string(), "");
  if (root["format"].string() != kFormat) root["format"].fail(std::string("must be \"") + kFormat + "\"");
  if (root["version"].integer() != kVersion)
    root["version"].fail("is " + std::to_string(root["version"].integer()) + "; this depthtrack reads version " +
                         std::to_string(kVersion));

  Sequence sequence;
  sequence.format = "depthtrack";
  sequence.camera = read_camera(root["camera"]);
  sequence.metres_per_unit = root["metres_per_unit"].number();
  if (sequence.metres_per_unit <= 0) root["metres_per_unit"].fail("must be positive");
  sequence.object = root.has("object") ? root["object"].string() : "";
  // The manifest carries one object's ground truth; asking for another is a mistake worth reporting.
  if (!object.empty() && !sequence.object.empty() && object != sequence.object)
    throw InputError("'" + path.string() + "' carries the ground truth of object '" + sequence.object + "', not '" +
                     object + "'");

  const JsonField frames = root["frames"];
  if (frames.size() == 0) frames.fail("is empty: the sequence has no frames");
  for (size_t i = 0; i < frames.size(); ++i) {
    sequence.frames.push_back(read_frame(frames[i], dir));
    if (i > 0 && !(sequence.frames[i].timestamp > sequence.frames[i - 1].timestamp))
      frames[i]["timestamp"].fail("must be later than the previous frame's");
  }
  return sequence;
}

void write_sequence_manifest(const std::filesystem::path& dir, const Sequence& sequence) {
  sequence.camera.validate();
  if (!std::isfinite(sequence.metres_per_unit) || sequence.metres_per_unit <= 0)
    throw InputError("cannot write a sequence manifest: metres_per_unit must be finite and positive");
  // ordered_json keeps the fields in the documented order, which makes the file easy to read.
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["version"] = kVersion;
  const Camera& c = sequence.camera;
  json["camera"] = {{"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}};
  json["metres_per_unit"] = sequence.metres_per_unit;
  json["object"] = sequence.object;
  json["frames"] = nlohmann::ordered_json::array();
  for (const SequenceFrame& frame : sequence.frames) {
    if (!std::isfinite(frame.timestamp))
      throw InputError("cannot write a sequence manifest: frame '" + frame.name + "' has a non-finite timestamp");
    nlohmann::ordered_json f;
    f["name"] = frame.name;
    f["timestamp"] = frame.timestamp;
    f["depth"] = relative_depth_name(frame.depth_path, dir);
    if (frame.ground_truth) {
      const Eigen::Matrix4d m = frame.ground_truth->matrix();
      auto& values = f["T_cam_obj"] = nlohmann::ordered_json::array();
      for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 4; ++col) values.push_back(m(r, col));
    }
    json["frames"].push_back(std::move(f));
  }

  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError("cannot create sequence folder '" + dir.string() + "': " + error.message());
  const auto path = dir / io::kDepthtrackManifest;
  std::ofstream out(path);
  out << json.dump(2) << '\n';
  out.close();
  if (!out) throw InputError("cannot write sequence manifest '" + path.string() + "'");
}

}  // namespace depthtrack
