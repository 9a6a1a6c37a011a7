// The raw depth stream: a header line with the camera, then per frame a text line and its pixels.
#include "io/raw_depth_stream.hpp"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <depthtrack/error.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "core/timestamp_limits.hpp"

namespace depthtrack {

const char* raw_stream_format() {
  return "depthtrack raw depth stream (all numbers of the text lines in decimal, pixels little-endian, row-major):\n"
         "  once, first:   depthtrack-raw-depth 1 WIDTH HEIGHT FX FY CX CY\\n   (pixels; FX FY CX CY as Camera's)\n"
         "  per frame:     TIMESTAMP f32\\n then WIDTH*HEIGHT float32 metres (0, NaN, +inf = no measurement)\n"
         "            or:  TIMESTAMP u16 METRES_PER_UNIT\\n then WIDTH*HEIGHT uint16 (0 = no measurement)\n"
         "  TIMESTAMP in seconds, each later than the previous; the stream ends at the end of the file after a "
         "frame's last pixel.\n";
}

namespace io {

namespace {

constexpr const char* kMagic = "depthtrack-raw-depth";
constexpr int kVersion = 1;
constexpr size_t kMaxLine = 512;
constexpr int kMaxSide = 16384;  // a header beyond this is corrupt, not a camera

class RawDepthStream final : public FrameSource {
 public:
  RawDepthStream(std::FILE* file, std::string label) : file_(file), label_(std::move(label)) {
    std::string line;
    if (!read_line(line))
      fail("is empty: it has no header line '" + std::string(kMagic) + " 1 WIDTH HEIGHT FX FY CX CY'");
    std::istringstream in(line);
    std::string magic, rest;
    int version = 0, width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    if (!(in >> magic) || magic != kMagic)
      fail("does not start with '" + std::string(kMagic) + "': it is not a raw depth stream (header line '" + line +
           "')");
    if (!(in >> version >> width >> height >> fx >> fy >> cx >> cy) || (in >> rest))
      fail("header line '" + line + "' is not '" + kMagic + " 1 WIDTH HEIGHT FX FY CX CY'");
    if (version != kVersion)
      fail("is version " + std::to_string(version) + "; this depthtrack reads version " + std::to_string(kVersion));
    if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide)
      fail("header: image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
           std::to_string(kMaxSide));
    try {
      camera_ = Camera::make(width, height, fx, fy, cx, cy);
    } catch (const InputError& e) {
      fail(std::string("header: ") + e.what());
    }
  }
  ~RawDepthStream() override {
    if (file_ != stdin) std::fclose(file_);
  }
  RawDepthStream(const RawDepthStream&) = delete;
  RawDepthStream& operator=(const RawDepthStream&) = delete;

  const Camera& camera() const override { return camera_; }

  std::optional<Frame> next() override {
    if (failed_) throw InputError("raw depth stream '" + label_ + "': reading stopped at the frame that failed");
    failed_ = true;  // until the frame is read whole
    std::string line;
    if (!read_line(line)) {
      failed_ = false;
      return std::nullopt;
    }
    Frame frame;
    char name[32];
    std::snprintf(name, sizeof name, "%06zu", count_);
    frame.name = name;
    const std::string where = "frame " + frame.name;
    std::istringstream in(line);
    std::string type, rest;
    if (!(in >> frame.timestamp >> type))
      fail(where + ": line '" + line + "' is not 'TIMESTAMP f32' or 'TIMESTAMP u16 METRES_PER_UNIT'");
    check_time(where, frame.timestamp);
    const size_t pixels = static_cast<size_t>(camera_.width) * static_cast<size_t>(camera_.height);
    if (type == "f32") {
      if (in >> rest) fail(where + ": line '" + line + "' has more than 'TIMESTAMP f32'");
      std::vector<uint32_t> raw(pixels);
      read_pixels(where, raw.data(), pixels * sizeof(uint32_t));
      std::vector<float> metres(pixels);
      for (size_t i = 0; i < pixels; ++i) {
        uint32_t bits = raw[i];
        if constexpr (std::endian::native == std::endian::big)
          bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
        metres[i] = std::bit_cast<float>(bits);
      }
      frame.depth = checked(where, [&] { return DepthImage::from_metres(camera_.width, camera_.height, metres); });
    } else if (type == "u16") {
      double metres_per_unit = 0;
      if (!(in >> metres_per_unit) || (in >> rest))
        fail(where + ": line '" + line + "' is not 'TIMESTAMP u16 METRES_PER_UNIT'");
      std::vector<uint16_t> units(pixels);
      read_pixels(where, units.data(), pixels * sizeof(uint16_t));
      if constexpr (std::endian::native == std::endian::big)
        for (uint16_t& u : units) u = static_cast<uint16_t>((u >> 8) | (u << 8));
      frame.depth =
          checked(where, [&] { return DepthImage::from_units(camera_.width, camera_.height, units, metres_per_unit); });
    } else {
      fail(where + ": pixel type '" + type + "' is neither f32 (float32 metres) nor u16 (uint16 units)");
    }
    previous_ = frame.timestamp;
    ++count_;
    failed_ = false;
    return frame;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError("raw depth stream '" + label_ + "' " + problem);
  }

  template <typename Make>
  DepthImage checked(const std::string& where, const Make& make) const {
    try {
      return make();
    } catch (const InputError& e) {
      fail(where + ": " + e.what());
    }
  }

  void check_time(const std::string& where, double t) const {
    if (!std::isfinite(t) || std::abs(t) >= kMaxAbsTimestamp)
      fail(where + ": timestamp " + std::to_string(t) + " s is outside the sane range (-1e10, 1e10) s");
    if (!previous_) return;
    if (!(t > *previous_))
      fail(where + ": timestamp " + std::to_string(t) + " s is not later than the previous frame's " +
           std::to_string(*previous_) + " s");
    if (t - *previous_ > kMaxTimeStep)
      fail(where + ": comes " + std::to_string(t - *previous_) + " s after the previous frame, more than a day");
  }

  // One line without its '\n'; false at the end of the stream before any byte of it.
  bool read_line(std::string& line) {
    line.clear();
    for (;;) {
      const int c = std::fgetc(file_);
      if (c == EOF) {
        if (std::ferror(file_)) fail("cannot be read: " + std::string(std::strerror(errno)));
        if (line.empty()) return false;
        fail("ends inside a line: '" + line + "'");
      }
      if (c == '\n') return true;
      if (line.size() >= kMaxLine)
        fail("has a line longer than " + std::to_string(kMaxLine) + " bytes where a header line belongs");
      line.push_back(static_cast<char>(c));
    }
  }

  void read_pixels(const std::string& where, void* data, size_t bytes) {
    const size_t got = std::fread(data, 1, bytes, file_);
    if (got != bytes)
      fail(where + ": the stream ends after " + std::to_string(got) + " of the frame's " + std::to_string(bytes) +
           " bytes of pixels (" + std::to_string(camera_.width) + "x" + std::to_string(camera_.height) + ")");
  }

  std::FILE* file_;
  std::string label_;
  Camera camera_;
  size_t count_ = 0;
  std::optional<double> previous_;
  bool failed_ = false;
};

}  // namespace

std::unique_ptr<FrameSource> raw_depth_stream(std::FILE* file, const std::string& label) {
  if (!file) throw InputError("raw depth stream '" + label + "': no file to read");
  try {
    return std::make_unique<RawDepthStream>(file, label);
  } catch (...) {
    if (file != stdin) std::fclose(file);
    throw;
  }
}

std::unique_ptr<FrameSource> open_raw_depth_stream(const std::string& location, const FrameSourceOptions& options) {
  if (!options.object.empty())
    throw InputError("raw depth stream '" + location + "' carries no ground truth, so no --object '" + options.object +
                     "' to pick");
  if (location.empty()) throw InputError("raw depth stream: give a path or - (stdin) after 'raw:'");
  if (location == "-") return raw_depth_stream(stdin, "stdin");
  std::FILE* file = std::fopen(location.c_str(), "rb");
  if (!file) throw InputError("cannot open raw depth stream '" + location + "': " + std::strerror(errno));
  return raw_depth_stream(file, location);
}

}  // namespace io

}  // namespace depthtrack
