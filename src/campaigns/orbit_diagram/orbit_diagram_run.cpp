// The orbit-diagram campaign: see orbit_diagram_run.hpp.

#include "vibromap/campaigns/orbit_diagram/orbit_diagram_run.hpp"

#include <algorithm>
#include <memory>
#include <optional>

#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/output_target.hpp"
#include "vibromap/campaigns/stoppable.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/parallel/campaign.hpp"
#include "vibromap/parallel/wire.hpp"
#include "steps_codec.hpp"

namespace vibromap {
namespace {

using detail::Steps;
using detail::StepsCodec;

// Rank 0: both directions in memory; the file when both are in.
class DiagramSink : public ResultSink<Steps> {
 public:
  DiagramSink(const StepsCodec& codec, OrbitDiagramData& data, std::string output)
      : ResultSink<Steps>(codec), data_(data), output_(std::move(output)) {}
  std::uint64_t items() const override { return 2; }
  std::uint64_t items_done() const override { return static_cast<std::uint64_t>(done_[0]) + done_[1]; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override {
    return scan_pending(from, max, 2, [&](std::uint64_t i) { return done_[i]; }, out);
  }
  void store_results(const ItemRange& range, std::vector<Steps>& results) override {
    for (std::uint64_t i = range.begin; i < range.end; ++i) {
      Steps& steps = results[static_cast<std::size_t>(i - range.begin)];
      if (i == 1) std::reverse(steps.begin(), steps.end());  // by axis index
      (i == 0 ? data_.up : data_.down) = std::move(steps);
      done_[i] = true;
    }
  }
  void checkpoint() override {}
  void finish(bool complete) override {
    if (complete && !output_.empty()) write_orbit_diagram(output_, data_);
  }

 private:
  OrbitDiagramData& data_;
  std::string output_;
  bool done_[2] = {false, false};
};

Steps solve_direction(const CellMaker& cells, std::size_t n, const OrbitDiagramOptions& o, std::uint64_t item) {
  std::vector<std::pair<Parameters, PointOptions>> path;
  for (std::size_t k = 0; k < n; ++k) {
    const CellPoint c = cells(item == 0 ? k : n - 1 - k);
    path.emplace_back(c.params, c.options);
  }
  return orbit_diagram(path, path.front().first.initial_state(), o);
}

}  // namespace

OrbitDiagramReport run_orbit_diagram(const MpiSession& mpi, const Scene& scene, const OrbitDiagramConfig& config) {
  OrbitDiagramReport report;
  report.data.axis = config.axis;
  report.data.options = config.options;
  report.data.scene_text = scene.text;
  const StepsCodec codec;
  std::optional<OutputTarget> target;  // rank 0, when the diagram is written to a file
  std::unique_ptr<DiagramSink> sink;
  mpi.agree(
      [&] {
        if (!config.output.empty()) target.emplace(config.output, OutputPolicy{.overwrite = config.overwrite});
        sink = std::make_unique<DiagramSink>(codec, report.data, config.output);
      },
      exit_status_of);
  const Grid grid({config.axis});
  const CellMaker cells(scene, grid);
  Campaign<Steps> campaign;
  campaign.solve =
      stoppable([&](std::uint64_t item) { return solve_direction(cells, grid.size(), config.options, item); });
  campaign.codec = &codec;
  campaign.sink = sink.get();
  FarmOptions o;
  o.label = "orbit-diagram";
  o.noun = "directions";
  o.progress = config.progress;
  o.max_chunk = 1;
  o.exit_code_of = exit_status_of;
  report.farm = run_campaign(mpi, o, campaign);
  return report;
}

}  // namespace vibromap
