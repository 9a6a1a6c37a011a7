// TrackerConfig <-> JSON, generated from the one field list (core/tracker_config_fields.hpp).
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "core/tracker_config_fields.hpp"
#include "io/json_text.hpp"

namespace depthtrack {

namespace {

using Json = nlohmann::ordered_json;
// Far above any real file (every field is about 2 KiB), far below what would exhaust memory.
constexpr size_t max_config_bytes = size_t{16} << 20;
namespace fields = config_fields;

template <typename T>
Json to_json_value(const T& value) {
  if constexpr (fields::Struct<T>) {
    Json object = Json::object();
    fields::for_each_field<T>([&](const auto& f) { object[f.name] = to_json_value(value.*f.member); });
    return object;
  } else if constexpr (fields::NamedEnum<T>) {
    return to_string(value);
  } else {
    return value;
  }
}

// What a JSON value is, for messages.
std::string kind_of(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number_integer()) return "an integer";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

[[noreturn]] void wrong_type(const std::string& source, const std::string& path, const char* wanted, const Json& j) {
  throw InputError(source + ": '" + path + "' must be " + wanted + ", got " + kind_of(j) + " " + io::json_excerpt(j));
}

template <typename T>
void from_json_value(const Json& j, T& value, const std::string& path, const std::string& source) {
  if constexpr (fields::Struct<T>) {
    if (!j.is_object()) wrong_type(source, path, "an object", j);
    const std::string prefix = path.empty() ? "" : path + ".";
    for (const auto& entry : j.items()) {
      // Named copies, not structured bindings: clang 14 cannot capture those in the lambda below.
      const std::string& key = entry.key();
      const Json& item = entry.value();
      bool known = false;
      fields::for_each_field<T>([&](const auto& f) {
        if (key != f.name) return;
        known = true;
        from_json_value(item, value.*f.member, prefix + key, source);
      });
      if (!known) throw InputError(source + ": unknown key '" + prefix + key + "'");
    }
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) wrong_type(source, path, "true or false", j);
    value = j.get<bool>();
  } else if constexpr (std::is_same_v<T, double>) {
    if (!j.is_number()) wrong_type(source, path, "a number", j);
    value = j.get<double>();
  } else if constexpr (std::is_same_v<T, int>) {
    if (!j.is_number_integer() || j.get<int64_t>() < std::numeric_limits<int>::min() ||
        j.get<int64_t>() > std::numeric_limits<int>::max())
      wrong_type(source, path, "an integer", j);
    value = j.get<int>();
  } else if constexpr (std::is_same_v<T, uint64_t>) {
    if (!j.is_number_unsigned()) wrong_type(source, path, "a non-negative integer", j);
    value = j.get<uint64_t>();
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!j.is_string()) wrong_type(source, path, "a string", j);
    value = j.get<std::string>();
  } else if constexpr (fields::NamedEnum<T>) {
    if (!j.is_string())
      wrong_type(source, path, (std::string("a string (") + fields::named_choices(&value) + ")").c_str(), j);
    try {
      fields::parse_named(j.get<std::string>(), value);
    } catch (const InputError& e) {
      throw InputError(source + ": '" + path + "': " + e.what());
    }
  } else {
    static_assert(!sizeof(T), "a TrackerConfig field of a type the JSON file cannot hold");
  }
}

}  // namespace

std::string tracker_config_to_json(const TrackerConfig& config) {
  return to_json_value(config).dump(2) + "\n";
}

TrackerConfig tracker_config_from_json(const std::string& text, const TrackerConfig& base, const std::string& source) {
  const Json j = io::parse_bounded_json<Json>(text, source);
  TrackerConfig config = base;
  from_json_value(j, config, "", source);
  try {
    config.validate();
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  return config;
}

TrackerConfig load_tracker_config(const std::filesystem::path& path, const TrackerConfig& base) {
  const std::string text = io::read_bounded_file(path, max_config_bytes, "configuration file");
  return tracker_config_from_json(text, base, "configuration file '" + path.string() + "'");
}

bool same_config(const TrackerConfig& a, const TrackerConfig& b) {
  return fields::equal(a, b);
}

}  // namespace depthtrack
