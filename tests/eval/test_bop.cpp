// BOP scenes: a converter written here turns the YCB-Video clip into a BOP scene (scene_camera.json,
// scene_gt.json, depth/, rgb/, the mug as a millimetre PLY), which must track exactly as well as the
// clip itself; and --bop-out writes BOP's result CSV.
#include <catch2/catch.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace depthtrack;

namespace {

std::string six_digits(int id) {
  char text[16];
  std::snprintf(text, sizeof text, "%06d", id);
  return text;
}

// Writes the YCB-Video clip as BOP scene `scene`: depth units stay the same (0.1 mm, so depth_scale
// 0.1), poses become cam_R_m2c / cam_t_m2c (mm), obj_id is YCB-Video's cls_index (as in BOP's ycbv).
void write_bop_scene(const std::filesystem::path& clip, const std::filesystem::path& scene) {
  std::filesystem::create_directories(scene / "depth");
  std::filesystem::create_directories(scene / "rgb");
  std::ifstream in(clip / "gt.json");
  const auto gt = nlohmann::json::parse(in);
  nlohmann::json cameras = nlohmann::json::object(), poses = nlohmann::json::object();
  for (const auto& f : gt["frames"]) {
    const int id = std::stoi(f["frame"].get<std::string>());
    const auto& k = f["K"];
    cameras[std::to_string(id)] = {
        {"cam_K", {k[0][0], k[0][1], k[0][2], k[1][0], k[1][1], k[1][2], k[2][0], k[2][1], k[2][2]}},
        {"depth_scale", 1000.0 / f["factor_depth"].get<double>()}};
    nlohmann::json instances = nlohmann::json::array();
    for (const auto& o : f["objects"]) {
      const auto& t = o["T_cam_obj"];
      nlohmann::json r = nlohmann::json::array(), translation = nlohmann::json::array();
      for (int row = 0; row < 3; ++row) {
        for (int c = 0; c < 3; ++c) r.push_back(t[row][c]);
        translation.push_back(1000.0 * t[row][3].get<double>());
      }
      instances.push_back({{"cam_R_m2c", r}, {"cam_t_m2c", translation}, {"obj_id", o["cls_index"]}});
    }
    poses[std::to_string(id)] = instances;
    std::filesystem::copy_file(clip / f["depth"].get<std::string>(), scene / "depth" / (six_digits(id) + ".png"));
    std::filesystem::copy_file(clip / (f["frame"].get<std::string>() + "-color.png"),
                               scene / "rgb" / (six_digits(id) + ".png"));
  }
  std::ofstream(scene / "scene_camera.json") << cameras.dump(1);
  std::ofstream(scene / "scene_gt.json") << std::setprecision(17) << poses.dump(1);
}

// The mesh as an ASCII PLY in millimetres, as BOP ships its models.
void write_ply_mm(const Mesh& mesh, const std::filesystem::path& path) {
  std::ofstream ply(path);
  ply << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  ply.precision(9);
  for (const auto& v : mesh.vertices) ply << 1000.0 * v.x() << " " << 1000.0 * v.y() << " " << 1000.0 * v.z() << "\n";
  for (const auto& t : mesh.triangles) ply << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

std::vector<double> column(const std::filesystem::path& csv, size_t index) {
  std::vector<double> values;
  const auto lines = test::lines_of(csv);
  for (size_t i = 1; i < lines.size(); ++i) values.push_back(std::stod(test::cells_of(lines[i])[index]));
  return values;
}

}  // namespace

TEST_CASE("a BOP scene converted from the YCB-Video clip tracks with the clip's accuracy", "[bop][cli][data]") {
  const auto clip = test::shared_data("sequences/ycbv-0000");
  const auto mug = test::shared_data("meshes/ycb/025_mug.obj");
  if (!clip || !mug) return;
  const auto dir = test::temp_dir("bop_ycbv");
  const auto scene = dir / "000048";
  write_bop_scene(*clip, scene);
  write_ply_mm(Mesh::load(*mug), dir / "obj_000014.ply");

  // The loaded scene matches the clip: camera, scale, frames, ground truth.
  const Sequence original = load_sequence(*clip, "mug"), bop = load_sequence(scene, "14");
  CHECK(bop.format == "bop");
  CHECK(bop.scene_id == 48);
  CHECK(bop.object == "14");
  CHECK(bop.camera.fx == original.camera.fx);
  CHECK(bop.camera.cy == original.camera.cy);
  CHECK(bop.metres_per_unit == Approx(original.metres_per_unit));
  REQUIRE(bop.frames.size() == original.frames.size());
  for (size_t i = 0; i < bop.frames.size(); ++i) {
    CHECK(bop.frames[i].name == original.frames[i].name);
    CHECK(bop.frames[i].timestamp == Approx(original.frames[i].timestamp));
    CHECK(translation_error(*bop.frames[i].ground_truth, *original.frames[i].ground_truth) < 1e-9);
    CHECK(rotation_error(*bop.frames[i].ground_truth, *original.frames[i].ground_truth) < 1e-6);
    CHECK(!bop.frames[i].colour_path.empty());
  }

  // The mesh as given: simplification's collapses can differ between the two files' float roundings.
  const std::string common =
      " --resolution 160x120 --particles 100 --seed 5 --init-from-gt --init-perturb \"0.005 3\" --simplify-error 0";
  const auto [status_a, log_a] = test::run_cli("track --mesh " + mug->string() + " --sequence " + clip->string() +
                                                   " --object mug --out " + (dir / "ycbv.csv").string() + common,
                                               dir / "log_a.txt");
  INFO(log_a);
  REQUIRE(status_a == 0);
  // No --unit-scale: a BOP scene's model is read in millimetres.
  const auto [status_b, log_b] = test::run_cli("track --mesh " + (dir / "obj_000014.ply").string() + " --sequence " +
                                                   scene.string() + " --object 14 --out " + (dir / "bop.csv").string() +
                                                   " --bop-out " + (dir / "results.csv").string() + common,
                                               dir / "log_b.txt");
  INFO(log_b);
  REQUIRE(status_b == 0);
  CHECK(log_b.find("reading the mesh in millimetres") != std::string::npos);
  CHECK(log_b.find("warning") == std::string::npos);

  // Same images, poses and particles: the same errors, frame by frame (the mm PLY differs from the
  // OBJ only by float rounding of the vertices).
  const auto err_a = column(dir / "ycbv.csv", 10), err_b = column(dir / "bop.csv", 10);
  const auto adds_a = column(dir / "ycbv.csv", 12), adds_b = column(dir / "bop.csv", 12);
  // One row per frame of the clip (ycbv-0000 holds 20).
  REQUIRE(err_a.size() == original.frames.size());
  REQUIRE(err_b.size() == original.frames.size());
  const double frames = static_cast<double>(err_a.size());
  double mean_a = 0, mean_b = 0;
  for (size_t i = 0; i < err_a.size(); ++i) {
    CHECK(err_b[i] == Approx(err_a[i]).margin(0.05));
    CHECK(adds_b[i] == Approx(adds_a[i]).margin(0.05));
    mean_a += err_a[i] / frames;
    mean_b += err_b[i] / frames;
  }
  CHECK(mean_a < 10.0);  // and it tracks: the clip's accuracy is a few mm
  CHECK(mean_b == Approx(mean_a).margin(0.02));

  // BOP's results: one row per image, R a rotation, t the CSV's translation in mm.
  const auto rows = test::lines_of(dir / "results.csv");
  REQUIRE(rows.size() == original.frames.size() + 1);  // a header and a row per frame
  CHECK(rows[0] == "scene_id,im_id,obj_id,score,R,t,time");
  const auto poses = test::lines_of(dir / "bop.csv");
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto cells = test::cells_of(rows[i]), pose = test::cells_of(poses[i]);
    REQUIRE(cells.size() == 7);
    CHECK(cells[0] == "48");
    CHECK(cells[1] == std::to_string(std::stoi(bop.frames[i - 1].name)));
    CHECK(cells[2] == "14");
    CHECK(std::stod(cells[3]) > 0);
    CHECK(std::stod(cells[3]) <= 1);
    std::istringstream r_text(cells[4]), t_text(cells[5]);
    Eigen::Matrix3d r;
    for (int k = 0; k < 9; ++k) r_text >> r(k / 3, k % 3);
    CHECK((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6);
    const Eigen::Quaterniond q(std::stod(pose[5]), std::stod(pose[6]), std::stod(pose[7]), std::stod(pose[8]));
    CHECK((r - q.normalized().toRotationMatrix()).norm() < 1e-6);
    for (int k = 0; k < 3; ++k) {
      double t = 0;
      t_text >> t;
      CHECK(t == Approx(1000 * std::stod(pose[2 + static_cast<size_t>(k)])).margin(1e-4));
    }
    CHECK(std::stod(cells[6]) > 0);
  }
}

TEST_CASE("a BOP scene names its objects by obj_id and refuses the others", "[bop][io][errors]") {
  const auto dir = test::temp_dir("bop_errors");
  const auto scene = dir / "000001";
  std::filesystem::create_directories(scene / "depth");
  DepthImage depth(4, 3);
  depth.at(1, 1) = 0.8f;
  depth.save_png(scene / "depth" / "000000.png", 0.0001);
  std::ofstream(scene / "scene_camera.json")
      << R"({"0": {"cam_K": [5, 0, 1.5, 0, 5, 1, 0, 0, 1], "depth_scale": 0.1}})";
  std::ofstream(scene / "scene_gt.json") << R"({"0": [
      {"cam_R_m2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_m2c": [10, 20, 800], "obj_id": 3},
      {"cam_R_m2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_m2c": [0, 0, 900], "obj_id": 7}]})";
  const Sequence seq = load_sequence(scene, "3");
  REQUIRE(seq.frames.size() == 1);
  CHECK(seq.camera.width == 4);
  CHECK(seq.metres_per_unit == Approx(0.0001));
  CHECK(seq.frames[0].ground_truth->translation.isApprox(Eigen::Vector3d(0.01, 0.02, 0.8)));
  CHECK(seq.load_depth(0).at(1, 1) == Approx(0.8f));
  CHECK_THROWS_WITH(load_sequence(scene), Catch::Contains("has 2 objects (obj_id 3, 7)"));
  CHECK_THROWS_WITH(load_sequence(scene, "5"), Catch::Contains("has no obj_id 5; objects present: 3, 7"));
  CHECK_THROWS_WITH(load_sequence(scene, "mug"), Catch::Contains("chosen by their obj_id, a number; got 'mug'"));
  // --bop-out of a sequence that is not BOP: refused before tracking.
  const auto synthetic = test::write_cli_sequence("bop_errors_synthetic", 2);
  const auto [status, output] = test::run_cli("track --mesh " + (synthetic / "object.obj").string() + " --sequence " +
                                                  (synthetic / "seq").string() + " --out " + (dir / "o.csv").string() +
                                                  " --init-from-gt --bop-out " + (dir / "r.csv").string(),
                                              dir / "log.txt");
  CHECK(status == 1);
  CHECK(output.find("BOP results need a BOP scene") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "o.csv"));
}
