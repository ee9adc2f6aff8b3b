#pragma once
// The orbit-diagram file: the stroboscopic states kept at each point of a path
// through one scene key, up and down. One HDF5 file, written whole (tmp + rename):
//   /<name>        1-D float64 coordinate: the key's values in increasing order (a dimension
//                  scale named after the key within its section, with units, long_name, key)
//   /direction     1-D int8 coordinate (up, down) = (1, -1)
//   /sample        1-D int32 coordinate 0..keep-1
//   /x1, /x2, /v1, /v2   (direction, <name>, sample) float64: the states kept at each point
//                  (m, m/s), NaN where the integration failed
//   /status        (direction, <name>) int8: 0 ok, 2 failed
// Root attributes: title, Conventions, vibromap_version, scene, key, transient, keep, version
// (kOrbitDiagramFormat's, io/file_format.hpp), attribute_checksum (the CRC-32 of every
// attribute, written last: src/io/attribute_seal.hpp).

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation/orbit_diagram.hpp"
#include "vibromap/core/grid.hpp"

namespace vibromap {

struct OrbitDiagramData {
  Axis axis;                        // the key and its values, increasing
  OrbitDiagramOptions options;
  std::vector<DiagramStep> up;      // by axis index, swept upwards
  std::vector<DiagramStep> down;    // by axis index (swept downwards)
  std::string scene_text;
};

// Throws IoError naming the path; leaves no file behind on failure.
void write_orbit_diagram(const std::string& path, const OrbitDiagramData& data);

}  // namespace vibromap
