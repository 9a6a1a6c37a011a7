// DepthImage: sensor conventions, PNG and float32 files, decimation, and the errors on bad input.
#include <png.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <fstream>
#include <limits>
#include <vector>

#include "support.hpp"

using Catch::Matchers::Contains;
using depthtrack::DepthImage;
using depthtrack::InputError;
namespace fs = std::filesystem;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// Writes a PNG with raw libpng calls (no depthtrack code). 16-bit samples are given as numbers and
// written big-endian by hand, as the PNG specification stores them.
void write_png_raw(const fs::path& path, int width, int height, int bit_depth, int colour_type,
                   const std::vector<uint16_t>& samples, int interlace = PNG_INTERLACE_NONE) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  REQUIRE(file != nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth, colour_type,
               interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const size_t row_samples = samples.size() / static_cast<size_t>(height);
  const size_t bytes_per_sample = bit_depth == 16 ? 2 : 1;
  std::vector<png_byte> bytes(samples.size() * bytes_per_sample);
  for (size_t i = 0; i < samples.size(); ++i) {
    if (bit_depth == 16) {
      bytes[2 * i] = static_cast<png_byte>(samples[i] >> 8);
      bytes[2 * i + 1] = static_cast<png_byte>(samples[i] & 0xff);
    } else {
      bytes[i] = static_cast<png_byte>(samples[i]);
    }
  }
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (size_t v = 0; v < rows.size(); ++v) rows[v] = bytes.data() + v * row_samples * bytes_per_sample;
  if (interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(png);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
}

struct RawPng {
  int width = 0, height = 0, bit_depth = 0, colour_type = 0;
  std::vector<uint16_t> samples;  // 16-bit grey samples decoded from big-endian by hand
};

// Reads a 16-bit grey PNG with raw libpng calls (no depthtrack code).
RawPng read_png_raw(const fs::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  REQUIRE(file != nullptr);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  png_read_info(png, info);
  RawPng out;
  out.width = static_cast<int>(png_get_image_width(png, info));
  out.height = static_cast<int>(png_get_image_height(png, info));
  out.bit_depth = png_get_bit_depth(png, info);
  out.colour_type = png_get_color_type(png, info);
  REQUIRE(out.bit_depth == 16);
  REQUIRE(out.colour_type == PNG_COLOR_TYPE_GRAY);
  std::vector<png_byte> bytes(static_cast<size_t>(out.width) * static_cast<size_t>(out.height) * 2);
  std::vector<png_bytep> rows(static_cast<size_t>(out.height));
  for (size_t v = 0; v < rows.size(); ++v) rows[v] = bytes.data() + v * static_cast<size_t>(out.width) * 2;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(file);
  for (size_t i = 0; i < bytes.size(); i += 2)
    out.samples.push_back(static_cast<uint16_t>(bytes[i] << 8 | bytes[i + 1]));
  return out;
}

void write_bytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Little-endian float32 bytes, composed by hand so the test does not rely on the host's order.
void write_float32_le(const fs::path& path, const std::vector<float>& values) {
  std::vector<unsigned char> bytes;
  for (float f : values) {
    uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<unsigned char>(bits >> (8 * k)));
  }
  write_bytes(path, bytes);
}

// A 64x48 image with varied values (so the PNG does not compress to a few bytes).
DepthImage noisy_image() {
  std::vector<float> metres(64 * 48);
  uint32_t state = 12345;
  for (auto& z : metres) {
    state = state * 1664525u + 1013904223u;
    z = 0.5f + static_cast<float>(state >> 8) / 16777216.0f;
  }
  return DepthImage::from_metres(64, 48, metres);
}

}  // namespace

TEST_CASE("DepthImage(width, height) has every pixel missing", "[io]") {
  const DepthImage image(4, 3);
  REQUIRE(image.width() == 4);
  REQUIRE(image.height() == 3);
  REQUIRE(image.data().size() == 12);
  for (float z : image.data()) REQUIRE(std::isnan(z));
  REQUIRE(image.valid_count() == 0);
}

TEST_CASE("from_metres stores NaN, +inf and 0 as missing and keeps the rest", "[io]") {
  const DepthImage image = DepthImage::from_metres(3, 2, {1.25f, kNaN, 0.0f, kInf, 0.5f, 4.0f});
  REQUIRE(image.at(0, 0) == 1.25f);
  REQUIRE(std::isnan(image.at(1, 0)));
  REQUIRE(std::isnan(image.at(2, 0)));
  REQUIRE(std::isnan(image.at(0, 1)));
  REQUIRE(image.at(1, 1) == 0.5f);
  REQUIRE(image.at(2, 1) == 4.0f);
  REQUIRE(image.valid_count() == 3);
}

TEST_CASE("from_metres rejects negative depth, naming the pixel and value", "[io]") {
  REQUIRE_THROWS_AS(DepthImage::from_metres(3, 2, {1, 1, 1, 1, 1, -0.5f}), InputError);
  REQUIRE_THROWS_WITH(DepthImage::from_metres(3, 2, {1, 1, 1, 1, 1, -0.5f}),
                      Contains("(2, 1)") && Contains("-0.5") && Contains("negative"));
  REQUIRE_THROWS_WITH(DepthImage::from_metres(2, 1, {-kInf, 1}), Contains("(0, 0)") && Contains("-inf"));
}

TEST_CASE("from_metres rejects a value count that does not match the size", "[io]") {
  REQUIRE_THROWS_AS(DepthImage::from_metres(3, 2, std::vector<float>(5, 1.0f)), InputError);
  REQUIRE_THROWS_WITH(DepthImage::from_metres(3, 2, std::vector<float>(5, 1.0f)), Contains("6") && Contains("5"));
}

TEST_CASE("from_units applies the scale and treats 0 as missing", "[io]") {
  const DepthImage mm = DepthImage::from_units(2, 2, {0, 1000, 65535, 1}, 0.001);
  REQUIRE(std::isnan(mm.at(0, 0)));
  REQUIRE(mm.at(1, 0) == Approx(1.0).margin(1e-7));
  REQUIRE(mm.at(0, 1) == Approx(65.535).margin(1e-5));
  REQUIRE(mm.at(1, 1) == Approx(0.001).margin(1e-9));
  REQUIRE(mm.valid_count() == 3);
  const DepthImage ycb = DepthImage::from_units(1, 1, {6168}, 1.0 / 10000.0);  // 0.1 mm units
  REQUIRE(ycb.at(0, 0) == Approx(0.6168).margin(1e-7));
  REQUIRE_THROWS_AS(DepthImage::from_units(1, 1, {1}, 0.0), InputError);
  REQUIRE_THROWS_AS(DepthImage::from_units(1, 1, {1}, -0.001), InputError);
  REQUIRE_THROWS_AS(DepthImage::from_units(1, 1, {1}, std::nan("")), InputError);
  REQUIRE_THROWS_AS(DepthImage::from_units(2, 2, {1, 2, 3}, 0.001), InputError);
}

TEST_CASE("load_png reads a 16-bit PNG written by raw libpng, with the exact scale", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_png_raw");
  // 258 = 0x0102: a byte-order mix-up would read 513.
  const std::vector<uint16_t> units = {0, 1, 258, 1000, 12345, 65535};
  for (int interlace : {PNG_INTERLACE_NONE, PNG_INTERLACE_ADAM7}) {
    const auto path = dir / (interlace ? "adam7.png" : "plain.png");
    write_png_raw(path, 3, 2, 16, PNG_COLOR_TYPE_GRAY, units, interlace);
    const DepthImage image = DepthImage::load_png(path, 0.001);
    REQUIRE(image.width() == 3);
    REQUIRE(image.height() == 2);
    REQUIRE(std::isnan(image.at(0, 0)));
    REQUIRE(image.at(1, 0) == Approx(0.001).margin(1e-9));
    REQUIRE(image.at(2, 0) == Approx(0.258).margin(1e-7));
    REQUIRE(image.at(0, 1) == Approx(1.0).margin(1e-7));
    REQUIRE(image.at(1, 1) == Approx(12.345).margin(1e-6));
    REQUIRE(image.at(2, 1) == Approx(65.535).margin(1e-5));
    REQUIRE(image.valid_count() == 5);
  }
}

TEST_CASE("save_png writes 16-bit grey units that raw libpng and load_png read back", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_png_save");
  const DepthImage image = DepthImage::from_metres(3, 2, {0.5f, kNaN, 1.2344f, 0.0001f, 6.5535f, 2.0f});
  image.save_png(dir / "d.png", 1e-4);
  const RawPng raw = read_png_raw(dir / "d.png");
  REQUIRE(raw.width == 3);
  REQUIRE(raw.height == 2);
  REQUIRE(raw.samples == std::vector<uint16_t>{5000, 0, 12344, 1, 65535, 20000});

  const DepthImage back = DepthImage::load_png(dir / "d.png", 1e-4);
  REQUIRE(std::isnan(back.at(1, 0)));
  for (size_t i : {0u, 2u, 3u, 4u, 5u}) REQUIRE(back.data()[i] == Approx(image.data()[i]).margin(0.5e-4));
}

TEST_CASE("save_png rejects a depth that does not fit 16-bit units", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_png_range");
  REQUIRE_THROWS_WITH(DepthImage::from_metres(2, 1, {1.0f, 70.0f}).save_png(dir / "far.png", 0.001),
                      Contains("(1, 0)") && Contains("65535"));
  // 0.3 mm rounds to 0 mm, which would read back as "missing".
  REQUIRE_THROWS_AS(DepthImage::from_metres(1, 1, {0.0003f}).save_png(dir / "near.png", 0.001), InputError);
  DepthImage negative(1, 1);
  negative.at(0, 0) = -1.0f;
  REQUIRE_THROWS_AS(negative.save_png(dir / "neg.png", 0.001), InputError);
  REQUIRE_THROWS_AS(DepthImage::from_metres(1, 1, {1.0f}).save_png(dir / "scale.png", 0.0), InputError);
}

TEST_CASE("load_float32 reads little-endian metres with the missing conventions", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_float32");
  const std::vector<float> values = {0.75f, kNaN, 0.0f, kInf, 3.5f, 1e-3f};
  write_float32_le(dir / "d.bin", values);
  const DepthImage image = DepthImage::load_float32(dir / "d.bin", 2, 3);
  REQUIRE(image.width() == 2);
  REQUIRE(image.height() == 3);
  REQUIRE(image.at(0, 0) == 0.75f);
  REQUIRE(std::isnan(image.at(1, 0)));
  REQUIRE(std::isnan(image.at(0, 1)));
  REQUIRE(std::isnan(image.at(1, 1)));
  REQUIRE(image.at(0, 2) == 3.5f);
  REQUIRE(image.at(1, 2) == 1e-3f);
  REQUIRE(image.valid_count() == 3);
}

TEST_CASE("decimated keeps pixel (factor u, factor v)", "[io]") {
  std::vector<float> metres(8 * 6);
  for (int v = 0; v < 6; ++v)
    for (int u = 0; u < 8; ++u)
      metres[static_cast<size_t>(v * 8 + u)] = 1.0f + static_cast<float>(u) + 10.0f * static_cast<float>(v);
  const DepthImage image = DepthImage::from_metres(8, 6, metres);
  const DepthImage half = image.decimated(2);
  REQUIRE(half.width() == 4);
  REQUIRE(half.height() == 3);
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 4; ++u)
      REQUIRE(half.at(u, v) == 1.0f + 2.0f * static_cast<float>(u) + 20.0f * static_cast<float>(v));
  REQUIRE(image.decimated(1).data() == image.data());
  REQUIRE_THROWS_WITH(image.decimated(3), Contains("8x6") && Contains("3"));
  REQUIRE_THROWS_AS(image.decimated(0), InputError);
}

// ---- Bad input files: each must be an InputError that says what is wrong and where. ----

TEST_CASE("load_png of a missing file names it", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_png_missing") / "nothing.png";
  REQUIRE_THROWS_AS(DepthImage::load_png(path, 0.001), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_png(path, 0.001),
                      Contains("cannot open depth image") && Contains("nothing.png") && Contains("No such file"));
}

TEST_CASE("load_png of a file that is not a PNG says so", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_png_text") / "depth.png";
  write_bytes(path, {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'});
  REQUIRE_THROWS_WITH(DepthImage::load_png(path, 0.001), Contains("depth.png") && Contains("not a PNG"));
}

TEST_CASE("load_png of random bytes after a valid signature reports corruption", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_png_corrupt") / "corrupt.png";
  std::vector<unsigned char> bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  uint32_t state = 99;
  for (int i = 0; i < 500; ++i) {
    state = state * 1664525u + 1013904223u;
    bytes.push_back(static_cast<unsigned char>(state >> 24));
  }
  write_bytes(path, bytes);
  REQUIRE_THROWS_AS(DepthImage::load_png(path, 0.001), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_png(path, 0.001), Contains("corrupt.png") && Contains("corrupt"));
}

TEST_CASE("load_png of a file cut in half reports truncation", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_png_truncated");
  noisy_image().save_png(dir / "full.png", 1e-4);
  auto bytes = read_bytes(dir / "full.png");
  REQUIRE(bytes.size() > 1000);
  bytes.resize(bytes.size() / 2);
  write_bytes(dir / "half.png", bytes);
  REQUIRE_THROWS_AS(DepthImage::load_png(dir / "half.png", 1e-4), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_png(dir / "half.png", 1e-4), Contains("half.png") && Contains("truncated"));
}

TEST_CASE("load_png of an 8-bit colour PNG names its bit depth and colour type", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_png_8bit") / "colour.png";
  write_png_raw(path, 2, 2, 8, PNG_COLOR_TYPE_RGB, std::vector<uint16_t>(12, 200));
  REQUIRE_THROWS_AS(DepthImage::load_png(path, 0.001), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_png(path, 0.001),
                      Contains("colour.png") && Contains("bit depth 8") && Contains("RGB") && Contains("16-bit"));
}

TEST_CASE("load_png of an 8-bit greyscale PNG is refused too", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_png_8bit_grey") / "grey8.png";
  write_png_raw(path, 2, 2, 8, PNG_COLOR_TYPE_GRAY, {1, 2, 3, 4});
  REQUIRE_THROWS_WITH(DepthImage::load_png(path, 0.001), Contains("bit depth 8") && Contains("colour type greyscale"));
}

TEST_CASE("load_float32 of a file with the wrong size names both sizes", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_float32_size") / "d.bin";
  write_float32_le(path, std::vector<float>(11, 1.0f));  // 44 bytes; 4x3 needs 48
  REQUIRE_THROWS_AS(DepthImage::load_float32(path, 4, 3), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_float32(path, 4, 3), Contains("d.bin") && Contains("44") && Contains("48"));
}

TEST_CASE("load_float32 rejects a negative depth, naming the pixel", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_float32_negative") / "d.bin";
  write_float32_le(path, {1.0f, 1.0f, -2.0f, 1.0f});
  REQUIRE_THROWS_AS(DepthImage::load_float32(path, 2, 2), InputError);
  REQUIRE_THROWS_WITH(DepthImage::load_float32(path, 2, 2), Contains("d.bin") && Contains("(0, 1)") && Contains("-2"));
}

TEST_CASE("load_float32 of a missing file names it", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_float32_missing") / "none.bin";
  REQUIRE_THROWS_WITH(DepthImage::load_float32(path, 2, 2), Contains("none.bin"));
}
