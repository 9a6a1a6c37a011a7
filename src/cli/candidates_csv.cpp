#include "cli/candidates_csv.hpp"

#include <depthtrack/error.hpp>
#include <fstream>

namespace depthtrack::cli {

void write_candidates_csv(const std::filesystem::path& path, const std::vector<SearchCandidate>& candidates,
                          QuaternionOrder order) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write '" + path.string() + "' (--candidates-out)");
  const bool xyzw = order == QuaternionOrder::Xyzw;
  out << "rank,score,confidence,tx,ty,tz," << (xyzw ? "qx,qy,qz,qw" : "qw,qx,qy,qz") << "\n";
  out.precision(9);
  for (size_t i = 0; i < candidates.size(); ++i) {
    const SearchCandidate& c = candidates[i];
    const Eigen::Quaterniond& q = c.pose.rotation;
    out << i + 1 << "," << c.score << "," << c.confidence << "," << c.pose.translation.x() << ","
        << c.pose.translation.y() << "," << c.pose.translation.z() << ",";
    if (xyzw)
      out << q.x() << "," << q.y() << "," << q.z() << "," << q.w() << "\n";
    else
      out << q.w() << "," << q.x() << "," << q.y() << "," << q.z() << "\n";
  }
  out.close();
  if (out.fail()) throw Error("failed writing '" + path.string() + "' (disk full?)");
}

}  // namespace depthtrack::cli
