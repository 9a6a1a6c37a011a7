// DepthView: a caller's depth buffer read in place, checked and converted in one pass.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <depthtrack/depth_view.hpp>
#include <depthtrack/error.hpp>
#include <limits>
#include <string>

#include "io/depth_pixel.hpp"

namespace depthtrack {

const char* to_string(DepthEncoding encoding) {
  switch (encoding) {
    case DepthEncoding::Float32Metres:
      return "float32 metres";
    case DepthEncoding::Uint16Units:
      return "uint16 units";
  }
  return "?";
}

DepthView DepthView::metres(const float* data, int width, int height, size_t row_stride_bytes) {
  DepthView view;
  view.data = data;
  view.width = width;
  view.height = height;
  view.encoding = DepthEncoding::Float32Metres;
  view.row_stride = row_stride_bytes != 0 ? row_stride_bytes : static_cast<size_t>(std::max(width, 0)) * sizeof(float);
  return view;
}

DepthView DepthView::units(const uint16_t* data, int width, int height, double metres_per_unit,
                           size_t row_stride_bytes) {
  DepthView view;
  view.data = data;
  view.width = width;
  view.height = height;
  view.encoding = DepthEncoding::Uint16Units;
  view.metres_per_unit = metres_per_unit;
  view.row_stride =
      row_stride_bytes != 0 ? row_stride_bytes : static_cast<size_t>(std::max(width, 0)) * sizeof(uint16_t);
  return view;
}

size_t DepthView::element_size() const {
  return encoding == DepthEncoding::Uint16Units ? sizeof(uint16_t) : sizeof(float);
}

void DepthView::validate() const {
  if (encoding != DepthEncoding::Float32Metres && encoding != DepthEncoding::Uint16Units)
    throw InputError("depth view: unknown encoding " + std::to_string(static_cast<int>(encoding)));
  if (data == nullptr) throw InputError("depth view: the data pointer is null");
  if (width <= 0 || height <= 0 || width > std::numeric_limits<int>::max() / height)
    throw InputError("depth view: size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is invalid (both must be positive)");
  const size_t row_bytes = static_cast<size_t>(width) * element_size();
  if (row_stride < row_bytes)
    throw InputError("depth view: row stride " + std::to_string(row_stride) + " bytes is less than a row of " +
                     std::to_string(width) + " " + to_string(encoding) + " pixels (" + std::to_string(row_bytes) +
                     " bytes)");
  if (row_stride > std::numeric_limits<size_t>::max() / static_cast<size_t>(height))
    throw InputError("depth view: row stride " + std::to_string(row_stride) + " bytes times " + std::to_string(height) +
                     " rows overflows the address space");
  if (encoding == DepthEncoding::Uint16Units && !(std::isfinite(metres_per_unit) && metres_per_unit > 0))
    throw InputError("depth view: metres_per_unit must be finite and positive, got " + std::to_string(metres_per_unit));
}

DepthImage DepthView::sample(int factor, float max_depth) const {
  validate();
  if (factor < 1 || width % factor != 0 || height % factor != 0)
    throw InputError("cannot decimate a " + std::to_string(width) + "x" + std::to_string(height) + " depth view by " +
                     std::to_string(factor) + ": the factor must be positive and divide both width and height");
  DepthImage out(width / factor, height / factor);
  const auto* bytes = static_cast<const unsigned char*>(data);
  const size_t w = static_cast<size_t>(width), f = static_cast<size_t>(factor);
  const bool metres = encoding == DepthEncoding::Float32Metres;
  for (size_t v = 0; v < static_cast<size_t>(height); ++v) {
    const unsigned char* row = bytes + v * row_stride;
    const bool kept_row = v % f == 0;
    if (!metres && !kept_row) continue;  // a uint16 value cannot be invalid: only kept pixels are read
    for (size_t u = 0; u < w; ++u) {
      const bool kept = kept_row && u % f == 0;
      // memcpy: a caller's buffer need not be aligned for the element type (a byte-strided array).
      float z;
      if (metres) {
        std::memcpy(&z, row + u * sizeof(float), sizeof z);
        z = io::metres_pixel(z, u, v);  // every pixel is checked, kept or not
      } else {
        if (!kept) continue;
        uint16_t value;
        std::memcpy(&value, row + u * sizeof(uint16_t), sizeof value);
        z = io::units_pixel(value, metres_per_unit);
      }
      if (kept && z <= max_depth) out.at(static_cast<int>(u / f), static_cast<int>(v / f)) = z;  // else NaN
    }
  }
  return out;
}

}  // namespace depthtrack
