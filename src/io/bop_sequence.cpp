// A BOP scene (https://bop.felk.cvut.cz/datasets/): scene_camera.json (cam_K, depth_scale per
// image), scene_gt.json (per image a list of cam_R_m2c, cam_t_m2c in mm, obj_id) and
// depth/NNNNNN.png, with rgb/NNNNNN.png beside when present. Objects are chosen by obj_id.
#include <algorithm>
#include <cctype>
#include <depthtrack/error.hpp>

#include "io/json_fields.hpp"
#include "io/png_depth.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack {

namespace {

constexpr double kFrameRate = 30.0;  // BOP gives no timestamps; its video-like scenes are 30 Hz captures

bool all_digits(const std::string& text) {
  return !text.empty() && text.size() <= 9 &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::string six_digits(int id) {
  std::string text = std::to_string(id);
  return std::string(text.size() < 6 ? 6 - text.size() : 0, '0') + text;
}

// The image ids (the keys of scene_camera.json), ascending.
std::vector<int> image_ids(const io::JsonField& cameras) {
  if (!cameras.json().is_object() || cameras.json().empty()) cameras.fail("must map image ids to cameras");
  std::vector<int> ids;
  for (const auto& item : cameras.json().items()) {
    if (!all_digits(item.key())) cameras[item.key()].fail("is not an image id (digits)");
    ids.push_back(std::stoi(item.key()));
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

Camera read_camera(const io::JsonField& k, const io::ImageSize& size) {
  if (k.size() != 9) k.fail("must hold the 9 numbers of a row-major 3x3 matrix");
  try {
    return Camera::make(size.width, size.height, k[0].number(), k[4].number(), k[2].number(), k[5].number());
  } catch (const InputError& e) {
    k.fail(std::string("is not a usable camera: ") + e.what());
  }
}

// cam_R_m2c (row-major) and cam_t_m2c (mm) as camera_from_object in metres.
Pose read_pose(const io::JsonField& instance) {
  const io::JsonField r = instance["cam_R_m2c"], t = instance["cam_t_m2c"];
  if (r.size() != 9) r.fail("must hold 9 numbers (a row-major rotation)");
  if (t.size() != 3) t.fail("must hold 3 numbers (millimetres)");
  std::array<double, 16> m{};
  for (size_t row = 0; row < 3; ++row) {
    for (size_t c = 0; c < 3; ++c) m[row * 4 + c] = r[row * 3 + c].number();
    m[row * 4 + 3] = t[row].number() * 0.001;
  }
  m[15] = 1;
  try {
    return Pose::from_row_major(m);
  } catch (const InputError& e) {
    r.fail(e.what());
  }
}

std::string join(const std::vector<int>& ids) {
  std::string out;
  for (int id : ids) out += (out.empty() ? "" : ", ") + std::to_string(id);
  return out;
}

int choose_object(const std::vector<int>& ids, const std::string& wanted, const std::string& file) {
  if (wanted.empty()) {
    if (ids.size() == 1) return ids.front();
    if (ids.empty()) return -1;
    throw InputError("'" + file + "' has " + std::to_string(ids.size()) + " objects (obj_id " + join(ids) +
                     "): choose one with the object option");
  }
  if (!all_digits(wanted))
    throw InputError("a BOP scene's objects are chosen by their obj_id, a number; got '" + wanted +
                     "' (present: " + join(ids) + ")");
  const int id = std::stoi(wanted);
  if (std::find(ids.begin(), ids.end(), id) == ids.end())
    throw InputError("'" + file + "' has no obj_id " + wanted + "; objects present: " + join(ids));
  return id;
}

}  // namespace

Sequence io::load_bop_sequence(const std::filesystem::path& dir, const std::string& object) {
  const auto camera_path = dir / kBopManifest, gt_path = dir / "scene_gt.json";
  const nlohmann::json camera_json = JsonField::read_file(camera_path);
  const JsonField cameras(camera_json, camera_path.string(), "");
  const std::vector<int> ids = image_ids(cameras);

  std::error_code error;
  const bool has_gt = std::filesystem::exists(gt_path, error);
  const nlohmann::json gt_json = has_gt ? JsonField::read_file(gt_path) : nlohmann::json::object();
  const JsonField gt(gt_json, gt_path.string(), "");
  std::vector<int> objects;  // every obj_id any image shows, ascending
  for (const auto& item : gt_json.items()) {
    const JsonField instances = gt[item.key()];
    for (size_t j = 0; j < instances.size(); ++j) objects.push_back(instances[j]["obj_id"].integer());
  }
  std::sort(objects.begin(), objects.end());
  objects.erase(std::unique(objects.begin(), objects.end()), objects.end());

  Sequence sequence;
  sequence.format = "bop";
  const int obj_id = choose_object(objects, object, gt_path.string());
  sequence.object = obj_id < 0 ? "" : std::to_string(obj_id);
  const std::string scene = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
  sequence.scene_id = all_digits(scene) ? std::stoi(scene) : 0;

  const JsonField first = cameras[std::to_string(ids.front())];
  const double depth_scale = first["depth_scale"].number();  // depth in mm = value * depth_scale
  if (depth_scale <= 0) first["depth_scale"].fail("must be positive");
  sequence.metres_per_unit = depth_scale * 0.001;
  const auto first_depth = dir / "depth" / (six_digits(ids.front()) + ".png");
  sequence.camera = read_camera(first["cam_K"], io::read_depth_png_size(first_depth));

  for (int id : ids) {
    const JsonField c = cameras[std::to_string(id)];
    // One Sequence has one camera and one scale: a scene that changes either is not supported.
    if (c["depth_scale"].number() != depth_scale) c["depth_scale"].fail("differs from the first image's");
    if (c["cam_K"].json() != first["cam_K"].json()) c["cam_K"].fail("differs from the first image's");
    SequenceFrame frame;
    frame.name = six_digits(id);
    frame.timestamp = (id - ids.front()) / kFrameRate;
    frame.depth_path = dir / "depth" / (frame.name + ".png");
    const auto colour = dir / "rgb" / (frame.name + ".png");
    if (std::filesystem::exists(colour, error)) frame.colour_path = colour;
    if (obj_id >= 0 && gt.has(std::to_string(id))) {
      const JsonField instances = gt[std::to_string(id)];
      // The first instance of the object: depthtrack tracks one.
      for (size_t j = 0; j < instances.size() && !frame.ground_truth; ++j)
        if (instances[j]["obj_id"].integer() == obj_id) frame.ground_truth = read_pose(instances[j]);
    }
    sequence.frames.push_back(std::move(frame));
  }
  return sequence;
}

}  // namespace depthtrack
