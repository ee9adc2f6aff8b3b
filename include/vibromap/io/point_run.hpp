#pragma once
// One point as `vibromap run` solves it, and its census as `run --census` takes it in one
// process, shared by the command and the Python module so that their numbers cannot differ: the
// trajectory kept only when it is asked for, the point solved, a point the solver refuses
// reported as the scene's error, and the JSON of the answer.

#include <optional>
#include <string>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

// Forcing periods a run keeps when a trajectory is asked for and the scene's [analysis]
// trajectory_periods is 0.
inline constexpr int kDefaultTrajectoryPeriods = 2;

// The override a run adds to `scene` so that a trajectory is computed only when it is kept
// (`keep`): "analysis.trajectory_periods=N" (kDefaultTrajectoryPeriods when the scene gives 0)
// with `keep`, "analysis.trajectory_periods=0" without; nullopt when the scene already agrees.
// An override rather than a field set, so that Scene::text records it.
std::optional<std::string> trajectory_override(const Scene& scene, bool keep);

// solve_point(scene.params, scene.options); throws SceneError "PATH: message" when the solver
// refuses the point (status invalid_input).
PointSummary solve_scene_point(const Scene& scene);

// write_summary_json of `summary`, as a string (what `vibromap run --format json` prints).
std::string summary_json(const PointSummary& summary);

// The census options of `run --census`: the scene's [census] (or its defaults), keeping each
// initial state's label when `labels` (--labels), with the minimal critical shock when `shock`
// (--shock) or census.shock.
CensusOptions run_census_options(const Scene& scene, bool labels, bool shock);

// census_point(scene.params, scene.options, census) in this process; throws SceneError "PATH:
// message" when the census refuses the point (status invalid_input).
CensusSummary census_scene_point(const Scene& scene, const CensusOptions& census);

// write_census_json of `summary`, as a string (what `vibromap run --census --format json` prints).
std::string census_json(const CensusSummary& summary);

}  // namespace vibromap
