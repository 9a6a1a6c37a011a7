#include "io/visp_simulated_sequence.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace depthtrack::io {

namespace {

constexpr int kMaxSide = 16384;  // a header beyond this is corrupt, not a camera

uint32_t little_endian_u32(const unsigned char* b) {
  return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 | static_cast<uint32_t>(b[2]) << 16 |
         static_cast<uint32_t>(b[3]) << 24;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path.string() + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The number in a file name such as Depth_0007.bin or Camera_007.txt; -1 where the name is not that.
int file_number(const std::filesystem::path& path, const std::string& prefix, const std::string& extension) {
  static const std::regex digits("([0-9]{1,9})");
  const std::string name = path.filename().string();
  if (name.size() <= prefix.size() + extension.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      path.extension() != extension)
    return -1;
  const std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
  return std::regex_match(middle, digits) ? std::stoi(middle) : -1;
}

// number -> file, for the files of `dir` named prefix + digits + extension.
std::map<int, std::filesystem::path> numbered_files(const std::filesystem::path& dir, const std::string& prefix,
                                                    const std::string& extension) {
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) throw InputError("'" + dir.string() + "' is not a folder");
  std::map<int, std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    const int n = file_number(entry.path(), prefix, extension);
    if (n >= 0) files[n] = entry.path();
  }
  if (error) throw InputError("cannot list '" + dir.string() + "': " + error.message());
  if (files.empty()) throw InputError("'" + dir.string() + "' holds no " + prefix + "N" + extension + " files");
  return files;
}

std::filesystem::path depth_config(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> found;
  std::error_code error;
  if (std::filesystem::is_directory(dir, error))
    for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
      const std::string name = entry.path().filename().string();
      if (name.size() > 10 && name.compare(name.size() - 10, 10, "_depth.xml") == 0) found.push_back(entry.path());
    }
  if (found.size() != 1)
    throw InputError("'" + dir.string() +
                     "' must hold exactly one *_depth.xml (the depth camera's intrinsics), found " +
                     std::to_string(found.size()));
  return found.front();
}

}  // namespace

DepthImage read_visp_depth(const std::filesystem::path& path, double metres_per_unit, int expected_width,
                           int expected_height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read depth file '" + path.string() + "'");
  std::array<unsigned char, 8> header{};
  if (!in.read(reinterpret_cast<char*>(header.data()), header.size()))
    throw InputError("depth file '" + path.string() + "' is shorter than its 8-byte header");
  const uint32_t height = little_endian_u32(header.data()), width = little_endian_u32(header.data() + 4);
  if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide)
    throw InputError("depth file '" + path.string() + "' has an impossible size " + std::to_string(width) + "x" +
                     std::to_string(height));
  if ((expected_width > 0 && static_cast<int>(width) != expected_width) ||
      (expected_height > 0 && static_cast<int>(height) != expected_height))
    throw InputError("depth file '" + path.string() + "' is " + std::to_string(width) + "x" + std::to_string(height) +
                     ", not " + std::to_string(expected_width) + "x" + std::to_string(expected_height) +
                     " as the sequence's first frame");
  const size_t count = static_cast<size_t>(width) * height;
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error || size != header.size() + 2 * count)
    throw InputError("depth file '" + path.string() + "' holds " + (error ? std::string("?") : std::to_string(size)) +
                     " bytes; a " + std::to_string(width) + "x" + std::to_string(height) + " image needs " +
                     std::to_string(header.size() + 2 * count));
  std::vector<unsigned char> bytes(2 * count);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    throw InputError("cannot read the pixels of depth file '" + path.string() + "'");
  std::vector<uint16_t> units(count);
  for (size_t i = 0; i < count; ++i)
    units[i] = static_cast<uint16_t>(bytes[2 * i] | static_cast<unsigned>(bytes[2 * i + 1]) << 8);
  return DepthImage::from_units(static_cast<int>(width), static_cast<int>(height), units, metres_per_unit);
}

Pose read_visp_pose(const std::filesystem::path& path) {
  std::istringstream text(read_text(path));
  std::array<double, 16> m{};
  for (double& x : m)
    if (!(text >> x) || !std::isfinite(x))
      throw InputError("pose file '" + path.string() + "' must hold a 4x4 matrix of 16 finite numbers");
  std::string rest;
  if (text >> rest) throw InputError("pose file '" + path.string() + "' holds more than 16 numbers");
  if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
    throw InputError("pose file '" + path.string() + "': the last row must be 0 0 0 1");
  try {
    return Pose::from_row_major(m);
  } catch (const InputError& e) {
    throw InputError("pose file '" + path.string() + "': " + e.what());
  }
}

Camera read_visp_camera(const std::filesystem::path& xml, int width, int height) {
  const std::string text = read_text(xml);
  const auto camera_start = text.find("<camera>"), camera_end = text.find("</camera>");
  if (camera_start == std::string::npos || camera_end == std::string::npos || camera_end < camera_start)
    throw InputError("'" + xml.string() + "' has no <camera> block");
  const std::string block = text.substr(camera_start, camera_end - camera_start);
  auto value = [&](const std::string& tag) {
    const std::regex pattern("<" + tag + ">\\s*([^<]*?)\\s*</" + tag + ">");
    std::smatch match;
    double x = 0;
    if (!std::regex_search(block, match, pattern) || !(std::istringstream(match[1].str()) >> x))
      throw InputError("'" + xml.string() + "': <camera> has no number in <" + tag + ">");
    return x;
  };
  try {
    return Camera::make(width, height, value("px"), value("py"), value("u0"), value("v0"));
  } catch (const InputError& e) {
    throw InputError("'" + xml.string() + "': " + e.what());
  }
}

VispSimulatedImport castle_options() {
  VispSimulatedImport options;
  options.depth_from_colour = Pose(Eigen::Vector3d(-0.05, 0, 0), Eigen::Quaterniond::Identity());
  return options;
}

bool is_visp_simulated_folder(const std::filesystem::path& dir) {
  std::error_code error;
  return std::filesystem::is_directory(dir / "Depth", error) &&
         std::filesystem::is_directory(dir / "CameraPose", error) &&
         std::filesystem::is_directory(dir / "Config", error);
}

Sequence load_visp_simulated_sequence(const std::filesystem::path& in, const VispSimulatedImport& options) {
  if (!(options.rate > 0) || !std::isfinite(options.rate)) throw InputError("the frame rate must be positive");
  if (!std::isfinite(options.pixel_centre)) throw InputError("the pixel centre must be a finite number");
  const auto depths = numbered_files(in / "Depth", "Depth_", ".bin");
  const auto poses = numbered_files(in / "CameraPose", "Camera_", ".txt");
  const DepthImage first = read_visp_depth(depths.begin()->second, options.metres_per_unit);

  Sequence sequence;
  sequence.format = kVispSimulatedFormat;
  const Camera visp = read_visp_camera(depth_config(in / "Config"), first.width(), first.height());
  sequence.camera = Camera::make(visp.width, visp.height, visp.fx, visp.fy, visp.cx - options.pixel_centre,
                                 visp.cy - options.pixel_centre);
  sequence.metres_per_unit = options.metres_per_unit;
  for (const auto& [number, path] : depths) {
    const auto pose = poses.find(number);
    if (pose == poses.end())
      throw InputError("'" + path.string() + "' has no pose: '" + (in / "CameraPose").string() + "' holds no Camera_" +
                       std::to_string(number) + ".txt");
    char name[16];
    std::snprintf(name, sizeof name, "%06d", number);
    SequenceFrame frame;
    frame.name = name;
    frame.timestamp = static_cast<double>(sequence.frames.size()) / options.rate;
    frame.depth_path = path;
    frame.ground_truth = options.depth_from_colour * read_visp_pose(pose->second);
    sequence.frames.push_back(frame);
  }
  return sequence;
}

Sequence import_visp_simulated_sequence(const std::filesystem::path& in, const std::filesystem::path& out,
                                        const VispSimulatedImport& options) {
  Sequence sequence = load_visp_simulated_sequence(in, options);
  // Every file is read and checked before anything is written, so that a bad input leaves an earlier
  // import in `out` whole (its depths are read again below, one at a time, rather than all held).
  for (size_t i = 0; i < sequence.frames.size(); ++i) sequence.load_depth(i);
  const std::vector<SequenceFrame> read = sequence.frames;
  sequence.format = "depthtrack";
  for (SequenceFrame& frame : sequence.frames) frame.depth_path = out / (frame.name + "-depth.png");
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) throw InputError("cannot create sequence folder '" + out.string() + "': " + error.message());
  for (size_t k = 0; k < read.size(); ++k)
    read_visp_depth(read[k].depth_path, options.metres_per_unit)
        .save_png(sequence.frames[k].depth_path, options.metres_per_unit);
  write_sequence_manifest(out, sequence);
  return sequence;
}

}  // namespace depthtrack::io
