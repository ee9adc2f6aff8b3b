#include "vibromap/io/point_run.hpp"

#include <sstream>

#include "vibromap/io/census_output.hpp"
#include "vibromap/io/summary_output.hpp"

namespace vibromap {
namespace {

// `summary`, unless its status says the solver refused the point: then SceneError "PATH: message".
template <class Summary>
Summary accepted(const Scene& scene, Summary summary) {
  if (summary.status == SolveStatus::invalid_input) throw SceneError(scene.path + ": " + summary.message);
  return summary;
}

template <class Summary>
std::string json_text(void (*write)(std::ostream&, const Summary&), const Summary& summary) {
  std::ostringstream os;
  write(os, summary);
  return os.str();
}

}  // namespace

std::optional<std::string> trajectory_override(const Scene& scene, bool keep) {
  const int periods = scene.options.analysis.trajectory_periods;
  if (keep && periods == 0) return "analysis.trajectory_periods=" + std::to_string(kDefaultTrajectoryPeriods);
  if (!keep && periods != 0) return std::string("analysis.trajectory_periods=0");
  return std::nullopt;
}

PointSummary solve_scene_point(const Scene& scene) {
  return accepted(scene, solve_point(scene.params, scene.options));
}

std::string summary_json(const PointSummary& summary) { return json_text(&write_summary_json, summary); }

CensusOptions run_census_options(const Scene& scene, bool labels, bool shock) {
  CensusOptions census = scene.census.value_or(CensusOptions{});
  census.labels = labels;
  census.shock = census.shock || shock;
  return census;
}

CensusSummary census_scene_point(const Scene& scene, const CensusOptions& census) {
  return accepted(scene, census_point(scene.params, scene.options, census));
}

std::string census_json(const CensusSummary& summary) { return json_text(&write_census_json, summary); }

}  // namespace vibromap
