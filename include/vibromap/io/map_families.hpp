#pragma once
// The family pass of a census map: every listed attractor of every cell gets a family id
// (core/analysis/census/families.hpp says how attractors are matched and ids fixed), written into
// the map's /family and /family_flags, with the family table /families.
//
// The pass streams the map chunk by chunk in flat order: a first pass matches each cell with its
// earlier neighbours and writes provisional labels, a second rewrites them as family ids. Memory:
// one chunk of the datasets it reads, a slab of the grid (one step along the slowest axis) and
// one entry per provisional label; never the whole map. It depends only on the map's contents,
// so a map made on any number of ranks, or stopped and resumed, gets the same ids; run again, it
// writes the same values.
//
// /families (a group, rewritten by each pass; left out of the attribute checksum, its datasets
// carry Fletcher32): per family f, ids 0..F-1 in order of first node, the datasets
//   id (int32), regimes (strings: the regimes its attractors have, space separated), cells,
//   soft_cells, edge_cells, label_changes (int64), fraction_min, fraction_max (float64),
//   first_cell, last_cell (int64 flat indices), first_attractor (int32),
// and the attributes count (F) and distance (the matching threshold).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vibromap/core/analysis/census/families.hpp"

namespace vibromap {

// A cell's motion scales: L (m) and omega L (m/s), StateScale's (core/analysis/point/shooting.hpp).
struct MotionScale {
  double length = 1.0;
  double speed = 1.0;
};

struct FamilyPassReport {
  std::vector<FamilyRecord> families;  // by id
  std::uint64_t cells = 0;             // cells of the map
  std::uint64_t nodes = 0;             // attractors labelled
  double distance = 0.0;               // the matching threshold, motion scales
  double wall_s = 0.0;                 // the pass's time
};

// A family's regimes as the table and the report print them: "(1,1) no-contact".
std::string family_regimes_text(const FamilyRecord& f);

// Labels the families of the census map at `path` (cells not done match nothing and keep -1).
// scale_of(flat): the motion scales of that cell. Throws FileVersionError / IoError as the map
// readers do (map_file.hpp), IoError naming the path when the map has no census.
FamilyPassReport write_map_families(const std::string& path, const std::function<MotionScale(std::uint64_t)>& scale_of,
                                    double distance);

}  // namespace vibromap
