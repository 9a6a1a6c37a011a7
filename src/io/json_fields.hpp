#pragma once
// Internal to the I/O layer: reading JSON manifests with errors that name the file and the field.
#include <array>
#include <depthtrack/pose.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace depthtrack::io {

// A JSON value together with where it came from ("frames[3].K"), for error messages.
class JsonField {
 public:
  JsonField(const nlohmann::json& value, std::string file, std::string where)
      : value_(value), file_(std::move(file)), where_(std::move(where)) {}

  // Parses path; throws InputError when it cannot be read or is not valid JSON.
  static nlohmann::json read_file(const std::filesystem::path& path);

  bool has(const std::string& key) const { return value_.is_object() && value_.contains(key); }
  JsonField operator[](const std::string& key) const;  // member of an object; missing -> InputError
  JsonField operator[](size_t index) const;            // element of an array
  size_t size() const;                                 // array length; not an array -> InputError

  double number() const;
  int integer() const;
  std::string string() const;
  // A rigid transform given as 16 row-major numbers, flat or as 4 rows of 4; the bottom row
  // must be 0 0 0 1 and the 3x3 block a rotation.
  Pose pose() const;

  const nlohmann::json& json() const { return value_; }
  // "<file>: field 'where' <problem>" as an InputError.
  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& file() const { return file_; }

 private:
  const nlohmann::json& value_;
  std::string file_, where_;
};

}  // namespace depthtrack::io
