#pragma once
// The brute-force bifurcation diagram: the motion followed along a path of
// parameter points, the state carried from each point to the next, and the stroboscopic states
// kept after a transient at each. Run up and down the same path, it shows hysteresis: a branch
// that holds beyond a fold in one direction jumps in the other.

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/analysis/point/point_solver.hpp"

namespace vibromap {

struct OrbitDiagramOptions {
  long transient = 300;  // forcing periods integrated at each point before states are kept, >= 0
  int keep = 16;         // stroboscopic states kept at each point, >= 1
};
std::string validate(const OrbitDiagramOptions& o);

struct DiagramStep {
  SolveStatus status = SolveStatus::ok;     // failed: the integration failed at this point (no states kept)
  std::vector<Eigen::Vector4d> strobe;      // `keep` states (x1, x2, v1, v2) at period starts, physical
};

// One step per point of `path`, in order: the first from `start` (physical), each next one from
// the last state of the one before (the first state of the path after a failed step). The
// integration runs at each point's own integrator options; a point's trouble is its status.
std::vector<DiagramStep> orbit_diagram(const std::vector<std::pair<Parameters, PointOptions>>& path,
                                       const Eigen::Vector4d& start, const OrbitDiagramOptions& options);

}  // namespace vibromap
