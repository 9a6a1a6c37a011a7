#include "eval/clip_objects.hpp"

#include <algorithm>
#include <depthtrack/sequence.hpp>

#include "io/json_fields.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack {

namespace {

std::vector<ClipObject> ycb_video_objects(const std::filesystem::path& path) {
  const nlohmann::json json = io::JsonField::read_file(path);
  const io::JsonField frames = io::JsonField(json, path.string(), "")["frames"];
  std::vector<ClipObject> objects;
  for (size_t i = 0; i < frames.size(); ++i) {
    const io::JsonField listed = frames[i]["objects"];
    for (size_t j = 0; j < listed.size(); ++j) {
      ClipObject o{listed[j]["name"].string(), listed[j].has("cls_index") ? listed[j]["cls_index"].integer() : -1};
      const auto known = std::find_if(objects.begin(), objects.end(), [&](const auto& k) { return k.name == o.name; });
      if (known == objects.end()) {
        objects.push_back(o);
      } else if (known->label != o.label) {
        listed[j]["cls_index"].fail("differs from object '" + o.name + "''s in an earlier frame");
      }
    }
  }
  return objects;
}

std::vector<ClipObject> bop_objects(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return {};
  const nlohmann::json json = io::JsonField::read_file(path);
  const io::JsonField gt(json, path.string(), "");
  std::vector<int> ids;
  for (const auto& item : json.items()) {
    const io::JsonField instances = gt[item.key()];
    for (size_t j = 0; j < instances.size(); ++j) ids.push_back(instances[j]["obj_id"].integer());
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<ClipObject> objects;
  for (int id : ids) objects.push_back({std::to_string(id), -1});
  return objects;
}

}  // namespace

std::vector<ClipObject> clip_objects(const std::filesystem::path& dir) {
  std::error_code error;
  // load_sequence names a missing folder or an unknown layout; depthtrack's own layout has one object.
  if (!std::filesystem::exists(dir / io::kDepthtrackManifest, error) &&
      std::filesystem::exists(dir / io::kYcbVideoManifest, error))
    return ycb_video_objects(dir / io::kYcbVideoManifest);
  if (!std::filesystem::exists(dir / io::kDepthtrackManifest, error) &&
      std::filesystem::exists(dir / io::kBopManifest, error))
    return bop_objects(dir / "scene_gt.json");
  return {{load_sequence(dir).object, -1}};
}

}  // namespace depthtrack
