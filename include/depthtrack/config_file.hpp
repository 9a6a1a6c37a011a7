#pragma once
/// @file
/// Every TrackerConfig parameter in a JSON file: nested objects as in TrackerConfig (observation,
/// occlusion, motion, refine, loss, recovery), enums as their strings. A file may give any subset;
/// the rest keep their defaults. Unknown keys and wrong types are InputErrors naming the key's path.
#include <depthtrack/tracker_config.hpp>
#include <filesystem>
#include <string>

namespace depthtrack {

/// All fields, indented, in TrackerConfig's order: what `depthtrack config --dump` prints.
std::string tracker_config_to_json(const TrackerConfig& config);
/// Fields given in text override those of base; the result is validated. source names the text in
/// errors (a file name).
TrackerConfig tracker_config_from_json(const std::string& text, const TrackerConfig& base = {},
                                       const std::string& source = "configuration");
/// tracker_config_from_json of the file at path; InputError naming the file when it cannot be read or parsed.
TrackerConfig load_tracker_config(const std::filesystem::path& path, const TrackerConfig& base = {});
/// Field by field, nested structs included.
bool same_config(const TrackerConfig& a, const TrackerConfig& b);

}  // namespace depthtrack
