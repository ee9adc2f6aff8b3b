// Brute force for the basins campaign's test (test_basins_mpi.py): reads a file of `vibromap
// basins`, and follows the initial state of each pixel named on the command line with no early
// decision (CensusOptions::early_stop = false: integration at the scene's tolerance to a steady
// state, no capture, recurrence or Newton search), each with a fresh follower. Prints one line a
// pixel: "PIXEL LABEL REGIME SAME", REGIME the brute-force attractor's ("-" when none) and SAME 1
// when it is the file's attractor of that pixel (same_attractor), or both have the same negative
// label. The pixel's state is the file's: its coordinates and fixed_state, read back.
//   basins_brute_force FILE.h5 PIXEL...

#include <cstdlib>
#include <iostream>
#include <string>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/io/basins_file.hpp"
#include "vibromap/io/scene/scene.hpp"

int main(int argc, char** argv) {
  using namespace vibromap;
  if (argc < 3) {
    std::cerr << "usage: basins_brute_force FILE.h5 PIXEL...\n";
    return 2;
  }
  try {
    const BasinsContent c = read_basins_file(argv[1]);
    const Scene scene = parse_scene(c.scene_text, argv[1]);
    CensusOptions census = scene.census.value_or(CensusOptions{});
    census.early_stop = false;
    for (int i = 2; i < argc; ++i) {
      const auto pixel = static_cast<std::uint64_t>(std::stoull(argv[i]));
      const int label = c.labels.at(pixel);
      CensusFollower brute(scene.params, scene.options, census);
      const auto out = brute.follow(c.plane.state(pixel));
      bool same = false;
      std::string regime = "-";
      if (out.label >= 0) {
        const Attractor& a = brute.attractor(static_cast<std::size_t>(out.label));
        regime = a.regime.label();
        same = label >= 0 && same_attractor(scene.params, scene.options, c.attractors.at(static_cast<std::size_t>(label)), a);
      } else {
        same = out.label == label;
      }
      std::cout << pixel << " " << label << " " << regime << " " << (same ? 1 : 0) << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "basins_brute_force: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
