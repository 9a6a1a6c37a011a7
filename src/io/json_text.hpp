#pragma once
// Internal to the I/O layer: reading JSON text with bounds, so that hostile files give clear errors
// instead of exhausting the stack or memory.
#include <cstddef>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace depthtrack::io {

// Arrays and objects nested deeper than this are refused while parsing: printing or walking a
// deeper value recursively could overflow the stack, and no depthtrack file nests beyond 4.
inline constexpr int max_json_depth = 64;

// The whole of a regular file of at most max_bytes; InputError naming `what` and the path for a
// missing, unreadable, non-regular (a device, a pipe) or larger file.
std::string read_bounded_file(const std::filesystem::path& path, size_t max_bytes, const std::string& what);

// Parses text as JSON (ordered or not); InputError starting with source for invalid JSON or nesting
// deeper than max_json_depth.
template <typename Json>
Json parse_bounded_json(const std::string& text, const std::string& source) {
  const typename Json::parser_callback_t limit = [&source](int depth, typename Json::parse_event_t, Json&) {
    if (depth > max_json_depth)
      throw std::length_error(source + ": nested deeper than " + std::to_string(max_json_depth) + " levels");
    return true;
  };
  try {
    return Json::parse(text, limit);
  } catch (const std::length_error& e) {
    throw InputError(e.what());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": not valid JSON: " + e.what());
  }
}

// At most max_chars of value's compact text, "..." marking a cut: for messages.
template <typename Json>
std::string json_excerpt(const Json& value, size_t max_chars = 60) {
  if (value.is_array() || value.is_object()) {
    if (value.empty()) return value.is_array() ? "[]" : "{}";
    // Never the whole value: it may be megabytes.
    return value.is_array() ? "[...] (" + std::to_string(value.size()) + " elements)"
                            : "{...} (" + std::to_string(value.size()) + " keys)";
  }
  std::string text = value.dump();
  if (text.size() > max_chars) text = text.substr(0, max_chars) + "...";
  return text;
}

}  // namespace depthtrack::io
