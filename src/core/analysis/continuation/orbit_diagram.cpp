#include "vibromap/core/analysis/continuation/orbit_diagram.hpp"

#include <string>

#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/system.hpp"

namespace vibromap {

std::string validate(const OrbitDiagramOptions& o) {
  if (o.transient < 0 || o.transient > 100'000'000) return "transient must be in [0, 100000000] periods";
  if (o.keep < 1 || o.keep > 100'000) return "keep must be in [1, 100000] states";
  return {};
}

std::vector<DiagramStep> orbit_diagram(const std::vector<std::pair<Parameters, PointOptions>>& path,
                                       const Eigen::Vector4d& start, const OrbitDiagramOptions& options) {
  std::vector<DiagramStep> steps;
  Eigen::Vector4d x = start;
  for (const auto& [p, o] : path) {
    DiagramStep step;
    const Model model(p);
    const auto integ = make_integrator(model, o.integrator);
    State u = Model::to_internal(x);
    integ->reset(u);
    Observer none;
    const long total = options.transient + options.keep;
    for (long j = 0; j < total; ++j) {
      if (integ->advance_period(u, none) != IntegrationStatus::ok) {
        step.status = SolveStatus::failed;
        step.strobe.clear();
        break;
      }
      if (j >= options.transient) step.strobe.push_back(Model::to_physical(u));
    }
    if (step.status == SolveStatus::ok) x = step.strobe.back();
    else x = start;
    steps.push_back(std::move(step));
  }
  return steps;
}

}  // namespace vibromap
