#pragma once
// The orbit-diagram campaign: the scene's motion followed along one key's values,
// up and down, each direction an item of the farm (so the two run on two ranks at once).
//   plan   two items: 0 sweeps the axis upwards, 1 downwards
//   solve  core/analysis/continuation/orbit_diagram.hpp along the path, from the scene's initial state at
//          the path's first point, each point built as `--set KEY=value` would (CellMaker)
//   codec  the steps of one direction
//   sink   rank 0 keeps both and writes the file (io/orbit_diagram_file.hpp) when both are done
// No checkpoint or resume: a run is two items; a stopped run writes nothing.

#include <string>

#include "vibromap/core/grid.hpp"
#include "vibromap/io/orbit_diagram_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

struct OrbitDiagramConfig {
  Axis axis;                    // the key and its values (increasing), as the scene reader made it
  OrbitDiagramOptions options;
  std::string output;           // HDF5 file; empty: none
  bool overwrite = false;       // replace an existing file
  bool progress = true;
};

struct OrbitDiagramReport {
  FarmReport farm;
  OrbitDiagramData data;        // rank 0, when complete
};

// Collective. Throws SceneError for an existing output without overwrite, IoError when it
// cannot be written (rank 0; QuietExit elsewhere).
OrbitDiagramReport run_orbit_diagram(const MpiSession& mpi, const Scene& scene, const OrbitDiagramConfig& config);

}  // namespace vibromap
