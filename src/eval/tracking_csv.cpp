#include <algorithm>
#include <cerrno>
#include <cstring>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <numbers>

#include "core/partial_files.hpp"

namespace depthtrack {

namespace fs = std::filesystem;

struct TrackingCsvWriter::Stream {
  std::ofstream out;
  PartialFile listed;  // removed if the run is interrupted
};

namespace {

std::string quoted(const fs::path& path) {
  return "'" + path.string() + "'";
}

// Where the rows go while tracking: PATH.partial beside PATH, or PATH itself for a device.
fs::path checked_partial_path(const fs::path& path) {
  std::error_code error;
  if (path.empty()) throw InputError("the output path is empty");
  const fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) throw InputError("output " + quoted(path) + " is a folder, not a file");
  if (fs::exists(status) && !fs::is_regular_file(status)) return path;  // /dev/stdout, /dev/full, a pipe
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, error)) throw InputError("output folder " + quoted(folder) + " does not exist");
  return fs::path(path.string() + ".partial");
}

}  // namespace

TrackingCsvWriter::TrackingCsvWriter(const fs::path& path, bool with_ground_truth, QuaternionOrder order,
                                     bool object_column)
    : stream_(std::make_unique<Stream>()),
      path_(path),
      partial_(checked_partial_path(path)),
      with_ground_truth_(with_ground_truth),
      order_(order),
      object_column_(object_column) {
  if (partial_ != path_) stream_->listed = PartialFile(partial_);
  stream_->out.open(partial_, std::ios::out | std::ios::trunc);
  if (!stream_->out)
    throw InputError("cannot write " + quoted(partial_) + ": " + std::strerror(errno) + " (check the folder of --out)");
  const bool xyzw = order_ == QuaternionOrder::Xyzw;
  stream_->out << (object_column_ ? "object," : "") << "frame,timestamp,tx,ty,tz,"
               << (xyzw ? "qx,qy,qz,qw" : "qw,qx,qy,qz") << ",ess"
               << (with_ground_truth_ ? ",err_t_mm,err_r_deg,adds_mm" : "") << ",latency_ms,confidence,status\n";
  stream_->out.precision(9);
  if (!stream_->out) throw Error("failed writing " + quoted(partial_));
}

TrackingCsvWriter::~TrackingCsvWriter() {
  if (!stream_) return;  // finished
  stream_->out.close();
  std::error_code ignored;
  if (partial_ != path_) fs::remove(partial_, ignored);
}

void TrackingCsvWriter::write(const TrackedFrame& f, const std::string& object) {
  if (!stream_) throw Error("TrackingCsvWriter::write after finish()");
  std::ofstream& out = stream_->out;
  if (object_column_) out << object << ",";
  const Pose& p = f.estimate.pose;
  out << f.name << "," << f.timestamp << "," << p.translation.x() << "," << p.translation.y() << ","
      << p.translation.z() << ",";
  const Eigen::Quaterniond& q = p.rotation;
  if (order_ == QuaternionOrder::Xyzw)
    out << q.x() << "," << q.y() << "," << q.z() << "," << q.w();
  else
    out << q.w() << "," << q.x() << "," << q.y() << "," << q.z();
  out << "," << f.estimate.effective_sample_size;
  if (with_ground_truth_)
    out << "," << f.translation_error * 1000.0 << "," << f.rotation_error * 180.0 / std::numbers::pi << ","
        << f.adds * 1000.0;
  out << "," << f.latency_ms << "," << f.estimate.confidence << "," << to_string(f.estimate.status) << "\n";
  if (!out) throw Error("failed writing " + quoted(partial_) + " (disk full?)");
}

void TrackingCsvWriter::finish() {
  if (!stream_) return;
  stream_->out.flush();
  const bool flushed = static_cast<bool>(stream_->out);
  stream_->out.close();
  if (!flushed || stream_->out.fail()) {
    const int code = errno;
    throw Error("failed writing " + quoted(partial_) + ": " + std::strerror(code));  // the destructor removes it
  }
  if (partial_ != path_) {
    std::error_code error;
    fs::rename(partial_, path_, error);
    if (error) throw Error("cannot rename " + quoted(partial_) + " to " + quoted(path_) + ": " + error.message());
  }
  stream_.reset();  // and with it the partial file's listing
}

void write_tracking_csv(const fs::path& path, const std::vector<TrackedFrame>& frames, QuaternionOrder order) {
  const bool truth = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                    [](const TrackedFrame& f) { return f.ground_truth.has_value(); });
  TrackingCsvWriter writer(path, truth, order);
  for (const auto& f : frames) writer.write(f);
  writer.finish();
}

}  // namespace depthtrack
