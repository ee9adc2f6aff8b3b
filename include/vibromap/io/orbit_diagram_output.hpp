#pragma once
// Output of an orbit diagram (`vibromap orbit-diagram`; OrbitDiagramData, orbit_diagram_file.hpp)
// as JSON, for scripts, or as a table, for people.
//
// JSON: one object with the keys
//   key, output, wall_s, transient, keep,
//   steps: [{param, direction ("up" | "down"), status, strobe_x1: [x1, ...]}, ...]
// in the order the two paths took them (up the key, then down), SI units.
//
// Table: the key's range, what was kept, the time and ranks, the file, and a row per point:
// the range of the kept x1 and the number of distinct x1 values, up and down.

#include <iosfwd>
#include <string>

#include "vibromap/io/orbit_diagram_file.hpp"
#include "vibromap/io/report.hpp"

namespace vibromap {

// `output`: the file written (empty: none).
void write_orbit_diagram_json(std::ostream& out, const FarmFigures& farm, const OrbitDiagramData& data,
                              const std::string& output);
void write_orbit_diagram_table(std::ostream& out, const FarmFigures& farm, const OrbitDiagramData& data,
                               const std::string& output);

}  // namespace vibromap
