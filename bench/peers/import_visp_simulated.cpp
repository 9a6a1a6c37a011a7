// Converts one of ViSP's simulated depth sequences (Depth/Depth_NNNN.bin, CameraPose/Camera_NNN.txt,
// Config/*_depth.xml; the castle in ../shared/data/sequences/visp-castle-simu) into depthtrack's layout
// (16-bit PNGs + sequence.json), which `depthtrack track`, the tests and the peer runners read.
//
//   depthtrack_import_visp_simulated --in DIR --out DIR [--depth-from-colour "-0.05 0 0"] [--rate 30]
#include <CLI/CLI.hpp>
#include <cstdio>

#include "io/visp_simulated_sequence.hpp"
#include "peer_run.hpp"

using namespace depthtrack;

int main(int argc, char** argv) {
  std::string in, out, offset = "-0.05 0 0";
  io::VispSimulatedImport options;
  CLI::App app("Convert a ViSP simulated depth sequence into depthtrack's sequence layout");
  app.add_option("--in", in, "The ViSP sequence folder (Depth/, CameraPose/, Config/)")->required();
  app.add_option("--out", out, "Folder to write the PNGs and sequence.json into")->required();
  app.add_option("--depth-from-colour", offset,
                 "Translation \"X Y Z\" (metres) from the colour camera, whose poses the files hold, to the depth "
                 "camera's (the castle's: -0.05 0 0)")
      ->capture_default_str();
  app.add_option("--rate", options.rate, "Frames per second (the files carry no timestamps)")->capture_default_str();
  app.add_option("--pixel-centre", options.pixel_centre,
                 "Image coordinate of a pixel's centre in the simulator's renderer (0.5: half-integer centres)")
      ->capture_default_str();
  return peers::run_peer_program(app, argc, argv, "import_visp_simulated", [&] {
    const auto t = cli::parse_numbers(offset, 3, "--depth-from-colour");
    options.depth_from_colour = Pose(Eigen::Vector3d(t[0], t[1], t[2]), Eigen::Quaterniond::Identity());
    const Sequence sequence = io::import_visp_simulated_sequence(in, out, options);
    std::printf("wrote %zu frames (%dx%d, fx %.1f) into %s\n", sequence.frames.size(), sequence.camera.width,
                sequence.camera.height, sequence.camera.fx, out.c_str());
  });
}
