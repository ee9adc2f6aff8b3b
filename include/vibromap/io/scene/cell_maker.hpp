#pragma once
// The parameter point of one cell of a sweep: the scene's base point with each axis's key set
// to the cell's value, exactly as `--set section.key=value` on the scene would set it
// (Key::set, core/model/keys.hpp).

#include <array>
#include <cstddef>
#include <vector>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

// One cell's parameters and solver options.
struct CellPoint {
  Parameters params;
  PointOptions options;
};

// Builds cells of a grid around a scene's point. Contract: every axis of the grid has a
// key that can be an axis (Axis::key, as make_axis fills it; the constructor throws
// std::invalid_argument otherwise, or for more than kMaxSweepAxes axes). operator()(i) for i
// in [0, grid.size()) equals what load_scene gives with `--set KEY=value` for each axis:
// the keys are applied in key table order, so an [initial] axis fills its state from the cell's
// D, and components of [initial] the scene did not give follow a swept D. Cheap per call: the
// setters are resolved once, and a call does no string work.
class CellMaker {
 public:
  CellMaker(const Scene& base, const Grid& grid);
  CellPoint operator()(std::size_t flat) const;

 private:
  struct Step {
    std::size_t axis;  // index into the grid's axes
    Key key;           // the axis's key
  };
  CellPoint base_;
  Grid grid_;
  std::vector<Step> steps_;        // key table order; [initial] ones last
  std::size_t first_initial_ = 0;  // steps before it set keys other than [initial]
  bool refill_rest_ = false;       // D is swept and the scene gave only part of [initial]
  std::array<bool, 4> initial_given_{};
};

}  // namespace vibromap
