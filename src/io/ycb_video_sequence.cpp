// A YCB-Video clip: NNNNNN-depth.png per frame and gt.json with intrinsics and per-object poses
// (the *-meta.mat files converted to JSON, see ../shared/data/README.md).
#include <algorithm>
#include <cctype>
#include <depthtrack/error.hpp>

#include "io/json_fields.hpp"
#include "io/png_depth.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack {

namespace {

constexpr double kFrameRate = 30.0;  // YCB-Video was recorded at 30 Hz; gt.json has no timestamps

// 0 .. 999999999 (nine digits, as the names are): differences between frame numbers cannot overflow.
int frame_number(const io::JsonField& f) {
  if (f.json().is_number_integer()) {
    const int n = f.integer();
    if (n < 0 || n > 999'999'999) f.fail("must be a frame number from 0 to 999999999");
    return n;
  }
  const std::string text = f.string();
  if (text.empty() || text.size() > 9 ||
      !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
    f.fail("must be a frame number such as \"000001\"");
  return std::stoi(text);
}

std::string frame_name(const io::JsonField& f) {
  return f.json().is_string() ? f.string() : std::to_string(f.integer());
}

Camera read_camera(const io::JsonField& k, const io::ImageSize& size) {
  if (k.size() != 3 || k[0].size() != 3 || k[1].size() != 3) k.fail("must be a 3x3 matrix");
  try {
    return Camera::make(size.width, size.height, k[0][0].number(), k[1][1].number(), k[0][2].number(),
                        k[1][2].number());
  } catch (const InputError& e) {
    k.fail(std::string("is not a usable camera: ") + e.what());
  }
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Exact name, else the one name that contains `wanted` ("mug" -> "025_mug").
std::string choose_object(const std::vector<std::string>& names, const std::string& wanted, const std::string& file) {
  if (wanted.empty()) {
    if (names.size() <= 1) return names.empty() ? "" : names.front();
    throw InputError("'" + file + "' has " + std::to_string(names.size()) + " objects (" + join(names) +
                     "): choose one with the object option");
  }
  if (std::find(names.begin(), names.end(), wanted) != names.end()) return wanted;
  std::vector<std::string> matches;
  for (const auto& n : names)
    if (n.find(wanted) != std::string::npos) matches.push_back(n);
  if (matches.size() == 1) return matches.front();
  if (matches.empty())
    throw InputError("'" + file + "' has no object '" + wanted + "'; objects present: " + join(names));
  throw InputError("object '" + wanted + "' is ambiguous in '" + file + "': it matches " + join(matches));
}

// NNNNNN-color.png beside NNNNNN-depth.png, when it is there.
std::filesystem::path colour_image_beside(const std::filesystem::path& depth) {
  const std::string name = depth.filename().string(), suffix = "-depth.png";
  if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return {};
  const auto colour = depth.parent_path() / (name.substr(0, name.size() - suffix.size()) + "-color.png");
  std::error_code error;
  return std::filesystem::exists(colour, error) ? colour : std::filesystem::path();
}

}  // namespace

Sequence io::load_ycb_video_sequence(const std::filesystem::path& dir, const std::string& object) {
  const auto path = dir / kYcbVideoManifest;
  const nlohmann::json json = JsonField::read_file(path);
  const JsonField root(json, path.string(), "");
  const JsonField frames = root["frames"];
  if (frames.size() == 0) frames.fail("is empty: the clip has no frames");

  // Every object any frame shows, in order of first appearance.
  std::vector<std::string> names;
  for (size_t i = 0; i < frames.size(); ++i) {
    const JsonField objects = frames[i]["objects"];
    for (size_t j = 0; j < objects.size(); ++j) {
      const std::string name = objects[j]["name"].string();
      // Two poses for one object: which is the truth? (Before, the last silently won.)
      for (size_t k = 0; k < j; ++k)
        if (objects[k]["name"].string() == name) objects[j]["name"].fail("repeats object '" + name + "' of this frame");
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }

  Sequence sequence;
  sequence.format = "ycb-video";
  sequence.object = choose_object(names, object, path.string());
  const JsonField first = frames[0];
  const double factor = first["factor_depth"].number();
  if (factor <= 0) first["factor_depth"].fail("must be positive");
  sequence.metres_per_unit = 1.0 / factor;
  // gt.json does not give the image size: the first depth PNG's header does.
  const io::ImageSize size = io::read_depth_png_size(dir / first["depth"].string());
  sequence.camera = read_camera(first["K"], size);

  const int first_number = frame_number(first["frame"]);
  for (size_t i = 0; i < frames.size(); ++i) {
    const JsonField f = frames[i];
    // One Sequence has one camera and one scale: a clip that changes either is not supported.
    if (f["factor_depth"].number() != factor) f["factor_depth"].fail("differs from the first frame's");
    if (f["K"].json() != first["K"].json()) f["K"].fail("differs from the first frame's");
    SequenceFrame frame;
    frame.name = frame_name(f["frame"]);
    const int number = frame_number(f["frame"]);
    if (i > 0 && number <= frame_number(frames[i - 1]["frame"]))
      f["frame"].fail("must be larger than the previous frame's");
    frame.timestamp = (number - first_number) / kFrameRate;
    frame.depth_path = dir / f["depth"].string();
    frame.colour_path = colour_image_beside(frame.depth_path);
    const JsonField objects = f["objects"];
    for (size_t j = 0; j < objects.size(); ++j)
      if (objects[j]["name"].string() == sequence.object) frame.ground_truth = objects[j]["T_cam_obj"].pose();
    sequence.frames.push_back(std::move(frame));
  }
  return sequence;
}

}  // namespace depthtrack
