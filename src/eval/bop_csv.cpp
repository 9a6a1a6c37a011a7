#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>

namespace depthtrack {

void check_bop_exportable(const Sequence& sequence) {
  if (sequence.format != "bop" || sequence.object.empty())
    throw InputError("BOP results need a BOP scene with a chosen obj_id; this sequence is " + sequence.format +
                     (sequence.object.empty() ? " with no object" : " (object '" + sequence.object + "')"));
}

void write_bop_csv(const std::filesystem::path& path, const Sequence& sequence,
                   const std::vector<TrackedFrame>& frames) {
  check_bop_exportable(sequence);
  std::ofstream out(path);
  if (!out) throw InputError("cannot write '" + path.string() + "'");
  out << "scene_id,im_id,obj_id,score,R,t,time\n";
  out.precision(9);
  for (const TrackedFrame& f : frames) {
    const Eigen::Matrix3d r = f.estimate.pose.rotation.toRotationMatrix();
    const Eigen::Vector3d t = 1000.0 * f.estimate.pose.translation;
    out << sequence.scene_id << "," << std::stoi(f.name) << "," << sequence.object << "," << f.estimate.confidence
        << ",";
    for (int i = 0; i < 9; ++i) out << (i ? " " : "") << r(i / 3, i % 3);
    out << "," << t.x() << " " << t.y() << " " << t.z() << "," << f.estimate.timings.total_ms / 1000.0 << "\n";
  }
  // The last rows sit in the stream's buffer until the close: a full disk shows only then.
  out.close();
  if (out.fail()) throw Error("failed writing '" + path.string() + "' (disk full?)");
}

}  // namespace depthtrack
