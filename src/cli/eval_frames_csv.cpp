#include "cli/eval_frames_csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <depthtrack/error.hpp>

namespace depthtrack::cli {

namespace fs = std::filesystem;

EvalFramesCsv::EvalFramesCsv(const fs::path& path) : path_(path), partial_(path.string() + ".partial") {
  std::error_code error;
  if (path.empty()) throw InputError("the frames CSV path is empty");
  if (fs::is_directory(path, error)) throw InputError("'" + path.string() + "' is a folder, not a file");
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(folder, error)) throw InputError("output folder '" + folder.string() + "' does not exist");
  listed_ = PartialFile(partial_);
  out_.open(partial_, std::ios::out | std::ios::trunc);
  if (!out_) throw InputError("cannot write '" + partial_.string() + "': " + std::strerror(errno));
  out_ << "object,case,frame,timestamp,adds_mm,confidence,status,within_tolerance,covariance_d2,covariance_dof,within_"
          "95,axis_d2_x,axis_d2_y,axis_d2_z,axis_d2_rx,axis_d2_ry,axis_d2_rz\n";
  out_.precision(9);
}

EvalFramesCsv::~EvalFramesCsv() {
  if (finished_) return;
  out_.close();
  std::error_code ignored;
  fs::remove(partial_, ignored);
}

void EvalFramesCsv::write(const std::string& object, const std::string& case_name, const TrackedFrame& f,
                          double tolerance, const std::optional<CovarianceCheck>& check) {
  out_ << object << "," << case_name << "," << f.name << "," << f.timestamp << ",";
  if (!std::isnan(f.adds)) out_ << f.adds * 1000.0;
  out_ << "," << f.estimate.confidence << "," << to_string(f.estimate.status) << ",";
  if (!std::isnan(f.adds)) out_ << (f.adds <= tolerance ? 1 : 0);
  out_ << ",";
  if (check)
    out_ << check->d2 << "," << check->dof << "," << (check->inside ? 1 : 0);
  else
    out_ << ",,";
  for (int i = 0; i < 6; ++i) {
    out_ << ",";
    if (check && !std::isnan(check->axis_d2[static_cast<size_t>(i)])) out_ << check->axis_d2[static_cast<size_t>(i)];
  }
  out_ << "\n";
  if (!out_) throw Error("failed writing '" + partial_.string() + "' (disk full?)");
}

void EvalFramesCsv::finish() {
  if (finished_) return;
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || out_.fail()) throw Error("failed writing '" + partial_.string() + "': " + std::strerror(errno));
  std::error_code error;
  fs::rename(partial_, path_, error);
  if (error) throw Error("cannot rename '" + partial_.string() + "' to '" + path_.string() + "': " + error.message());
  listed_.release();
  finished_ = true;
}

}  // namespace depthtrack::cli
