#include "io/json_fields.hpp"

#include <cmath>
#include <depthtrack/error.hpp>

#include "io/json_text.hpp"

namespace depthtrack::io {

nlohmann::json JsonField::read_file(const std::filesystem::path& path) {
  // A manifest of a long sequence (a pose per frame) stays far below this.
  constexpr size_t max_bytes = size_t{1} << 30;
  const std::string text = read_bounded_file(path, max_bytes, "file");
  std::string source = path.string();  // quoted, built in place (GCC 12 warns falsely on "'" + s + "'")
  source.insert(source.begin(), '\'');
  source.push_back('\'');
  return parse_bounded_json<nlohmann::json>(text, source);
}

void JsonField::fail(const std::string& problem) const {
  throw InputError("'" + file_ + "': field '" + where_ + "' " + problem);
}

JsonField JsonField::operator[](const std::string& key) const {
  const std::string child = where_.empty() ? key : where_ + "." + key;
  if (!value_.is_object()) fail("must be an object");
  const auto it = value_.find(key);
  if (it == value_.end()) throw InputError("'" + file_ + "': field '" + child + "' is missing");
  return {*it, file_, child};
}

JsonField JsonField::operator[](size_t index) const {
  if (!value_.is_array() || index >= value_.size()) fail("has no element " + std::to_string(index));
  return {value_[index], file_, where_ + "[" + std::to_string(index) + "]"};
}

size_t JsonField::size() const {
  if (!value_.is_array()) fail("must be an array");
  return value_.size();
}

double JsonField::number() const {
  if (!value_.is_number()) fail("must be a number");
  const double x = value_.get<double>();
  if (!std::isfinite(x)) fail("must be finite");
  return x;
}

int JsonField::integer() const {
  if (!value_.is_number_integer()) fail("must be an integer");
  if (value_.is_number_unsigned() && value_.get<uint64_t>() > 2147483647u) fail("is out of range");
  const auto x = value_.get<int64_t>();
  if (x < -2147483647 || x > 2147483647) fail("is out of range");
  return static_cast<int>(x);
}

std::string JsonField::string() const {
  if (!value_.is_string()) fail("must be a string");
  return value_.get<std::string>();
}

Pose JsonField::pose() const {
  std::array<double, 16> m{};
  const bool nested = value_.is_array() && value_.size() == 4 && value_[0].is_array();
  if (nested) {
    for (size_t r = 0; r < 4; ++r) {
      const JsonField row = (*this)[r];
      if (row.size() != 4) row.fail("must have 4 numbers");
      for (size_t c = 0; c < 4; ++c) m[r * 4 + c] = row[c].number();
    }
  } else {
    if (!value_.is_array() || value_.size() != 16) fail("must be 16 numbers (row-major 4x4) or 4 rows of 4");
    for (size_t i = 0; i < 16; ++i) m[i] = (*this)[i].number();
  }
  if (std::abs(m[12]) > 1e-6 || std::abs(m[13]) > 1e-6 || std::abs(m[14]) > 1e-6 || std::abs(m[15] - 1) > 1e-6)
    fail("is not a rigid transform: its bottom row must be 0 0 0 1");
  try {
    return Pose::from_row_major(m);
  } catch (const InputError& e) {
    fail(std::string("is not a rigid transform: ") + e.what());
  }
}

}  // namespace depthtrack::io
