// 16-bit greyscale depth PNGs through the classic libpng API.
//
// libpng reports errors through a handler that must not return. Ours records the message and
// longjmps back to the setjmp in the function that made the failing call. Those functions hold only
// trivially destructible locals, so the jump skips no destructor (what C++ requires of longjmp);
// everything that needs cleaning up lives in a PngFile owned by the caller.
#include "io/png_depth.hpp"

#include <png.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <sstream>
#include <vector>

namespace depthtrack {

namespace {

struct PngFile {
  std::FILE* file = nullptr;
  png_structp png = nullptr;
  png_infop info = nullptr;
  bool writing = false;
  std::jmp_buf jump;
  char message[512] = "";

  PngFile() = default;
  PngFile(const PngFile&) = delete;
  PngFile& operator=(const PngFile&) = delete;
  ~PngFile() {
    if (writing)
      png_destroy_write_struct(&png, &info);
    else
      png_destroy_read_struct(&png, &info, nullptr);
    if (file) std::fclose(file);
  }
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* self = static_cast<PngFile*>(png_get_error_ptr(png));
  std::snprintf(self->message, sizeof self->message, "%s", message);
  std::longjmp(self->jump, 1);
}

// Warnings (bad ancillary chunks, sRGB profile quirks) do not affect the depth values: stay quiet.
void on_png_warning(png_structp, png_const_charp) {}

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

[[noreturn]] void throw_libpng(const PngFile& f, const std::filesystem::path& path, const char* doing) {
  throw InputError("depth image " + quoted(path) + " is corrupt or truncated (libpng, " + doing + ": " + f.message +
                   ")");
}

void check_scale(double metres_per_unit) {
  if (!std::isfinite(metres_per_unit) || metres_per_unit <= 0)
    throw InputError("depth scale metres_per_unit must be finite and positive, got " + std::to_string(metres_per_unit));
}

// Opens path, checks the PNG signature and reads the header into f.
void open_for_reading(PngFile& f, const std::filesystem::path& path) {
  f.file = std::fopen(path.c_str(), "rb");
  if (!f.file) throw InputError("cannot open depth image " + quoted(path) + ": " + std::strerror(errno));
  png_byte signature[8] = {};
  const size_t got = std::fread(signature, 1, sizeof signature, f.file);
  if (got != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0)
    throw InputError("depth image " + quoted(path) + " is not a PNG file (bad signature)");
  f.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &f, on_png_error, on_png_warning);
  if (!f.png)
    throw InputError("libpng could not start reading " + quoted(path) + " (out of memory or version mismatch)");
  f.info = png_create_info_struct(f.png);
  if (!f.info) throw InputError("libpng could not start reading " + quoted(path) + " (out of memory)");
}

bool read_header(PngFile& f) {
  if (setjmp(f.jump)) return false;
  png_init_io(f.png, f.file);
  png_set_sig_bytes(f.png, 8);
  png_read_info(f.png, f.info);
  return true;
}

const char* colour_type_name(int colour_type) {
  switch (colour_type) {
    case PNG_COLOR_TYPE_GRAY:
      return "greyscale";
    case PNG_COLOR_TYPE_GRAY_ALPHA:
      return "greyscale+alpha";
    case PNG_COLOR_TYPE_RGB:
      return "RGB";
    case PNG_COLOR_TYPE_RGB_ALPHA:
      return "RGBA";
    case PNG_COLOR_TYPE_PALETTE:
      return "palette";
    default:
      return "unknown";
  }
}

io::ImageSize checked_header(PngFile& f, const std::filesystem::path& path) {
  if (!read_header(f)) throw_libpng(f, path, "reading the header");
  const int bit_depth = png_get_bit_depth(f.png, f.info);
  const int colour_type = png_get_color_type(f.png, f.info);
  if (bit_depth != 16 || colour_type != PNG_COLOR_TYPE_GRAY)
    throw InputError("depth image " + quoted(path) + " has bit depth " + std::to_string(bit_depth) +
                     " and colour type " + colour_type_name(colour_type) +
                     "; a depth image must be a 16-bit single-channel greyscale PNG");
  const png_uint_32 width = png_get_image_width(f.png, f.info), height = png_get_image_height(f.png, f.info);
  // libpng already caps each side at 10^6; a corrupt header could still ask for terabytes. 2^26
  // pixels (8192x8192, 384 MiB decoded) is far beyond any depth sensor.
  if (static_cast<uint64_t>(width) * height > (uint64_t{1} << 26))
    throw InputError("depth image " + quoted(path) + " claims an implausible size of " + std::to_string(width) + "x" +
                     std::to_string(height));
  return {static_cast<int>(width), static_cast<int>(height)};
}

// Decodes all rows (interlaced or not) into rows[], then reads to IEND so a cut-off file is caught.
bool read_pixels(PngFile& f, png_bytep* rows) {
  if (setjmp(f.jump)) return false;
  if constexpr (std::endian::native == std::endian::little) png_set_swap(f.png);  // PNG stores big-endian
  png_set_interlace_handling(f.png);
  png_read_update_info(f.png, f.info);
  png_read_image(f.png, rows);
  png_read_end(f.png, nullptr);
  return true;
}

bool write_pixels(PngFile& f, int width, int height, png_bytep* rows) {
  if (setjmp(f.jump)) return false;
  png_init_io(f.png, f.file);
  png_set_IHDR(f.png, f.info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 16,
               PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(f.png, 1);  // depth noise barely compresses: favour speed
  png_write_info(f.png, f.info);
  if constexpr (std::endian::native == std::endian::little) png_set_swap(f.png);
  png_write_image(f.png, rows);
  png_write_end(f.png, nullptr);
  return true;
}

std::vector<png_bytep> row_pointers(std::vector<uint16_t>& pixels, int width, int height) {
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (size_t v = 0; v < rows.size(); ++v)
    rows[v] = reinterpret_cast<png_bytep>(pixels.data() + v * static_cast<size_t>(width));
  return rows;
}

}  // namespace

io::ImageSize io::read_depth_png_size(const std::filesystem::path& path) {
  PngFile f;
  open_for_reading(f, path);
  return checked_header(f, path);
}

DepthImage io::load_depth_png(const std::filesystem::path& path, double metres_per_unit,
                              const std::optional<ImageSize>& camera_size) {
  check_scale(metres_per_unit);
  PngFile f;
  open_for_reading(f, path);
  const io::ImageSize size = checked_header(f, path);
  if (camera_size && (size.width != camera_size->width || size.height != camera_size->height))
    throw InputError("depth image '" + path.string() + "' is " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + " but the camera is " + std::to_string(camera_size->width) + "x" +
                     std::to_string(camera_size->height));
  std::vector<uint16_t> units(static_cast<size_t>(size.width) * static_cast<size_t>(size.height));
  std::vector<png_bytep> rows = row_pointers(units, size.width, size.height);
  if (!read_pixels(f, rows.data())) throw_libpng(f, path, "reading the pixels");
  return DepthImage::from_units(size.width, size.height, units, metres_per_unit);
}

DepthImage DepthImage::load_png(const std::filesystem::path& path, double metres_per_unit) {
  return io::load_depth_png(path, metres_per_unit, std::nullopt);
}

void DepthImage::save_png(const std::filesystem::path& path, double metres_per_unit) const {
  check_scale(metres_per_unit);
  if (data_.empty()) throw InputError("cannot save an empty depth image to '" + path.string() + "'");
  std::vector<uint16_t> units(data_.size(), 0);
  for (size_t i = 0; i < data_.size(); ++i) {
    if (std::isnan(data_[i])) continue;  // missing is written as 0
    const double value = std::round(static_cast<double>(data_[i]) / metres_per_unit);
    if (!(value >= 1.0 && value <= 65535.0)) {  // also catches +-inf
      std::ostringstream message;
      message << "cannot save depth image '" << path.string() << "': pixel (" << i % static_cast<size_t>(width_) << ", "
              << i / static_cast<size_t>(width_) << ") = " << data_[i] << " m is not 1..65535 units of "
              << metres_per_unit << " m";
      throw InputError(message.str());
    }
    units[i] = static_cast<uint16_t>(value);
  }
  PngFile f;
  f.writing = true;
  f.file = std::fopen(path.c_str(), "wb");
  if (!f.file) throw InputError("cannot create depth image '" + path.string() + "': " + std::strerror(errno));
  f.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &f, on_png_error, on_png_warning);
  if (!f.png) throw InputError("libpng could not start writing '" + path.string() + "'");
  f.info = png_create_info_struct(f.png);
  if (!f.info) throw InputError("libpng could not start writing '" + path.string() + "'");
  std::vector<png_bytep> rows = row_pointers(units, width_, height_);
  if (!write_pixels(f, width_, height_, rows.data()))
    throw InputError("cannot write depth image '" + path.string() + "': libpng: " + f.message);
  // fclose flushes: a full disk shows up here, not in libpng.
  const int closed = std::fclose(f.file);
  f.file = nullptr;
  if (closed != 0) throw InputError("cannot write depth image '" + path.string() + "': " + std::strerror(errno));
}

}  // namespace depthtrack
