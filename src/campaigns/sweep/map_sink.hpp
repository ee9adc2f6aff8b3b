#pragma once
// Internal to the sweep campaign: rank 0's sink of cell results, streamed into the map file
// (io/map_file.hpp's MapWriter), with the regime counts for progress lines and the report.

#include <map>
#include <string>

#include "cell_codec.hpp"
#include "refine_plan.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/sweep_output.hpp"

namespace vibromap::detail {

// What the report says of the whole map (the cells it already held on resume included).
struct MapTally {
  int census_k = 0;                     // K of each cell's census (0: no census)
  std::map<std::string, long> regimes;  // regime label -> cells
  std::map<std::string, ClassCost> classes;  // regime kind -> its solved cells and their solve time
  long census_budget_states = 0;        // census: initial states followed to analysis.max_periods
  long soft = 0;                        // cells whose motion is soft (is_soft)
  long impacting = 0;                   // cells with impacts in their motion (k > 0 or T_con > 0)
  long hertz_invalid = 0;               // of those, cells beyond the Hertz limit
  long fragile = 0;                     // cells marked fragile (analysis.fragility)
  long fragility_assessed = 0;          // cells whose fragility was assessed
  void add(const CellResult& c);
};

class MapSink : public ResultSink<CellResult> {
 public:
  // `tally`: that of the cells the map already holds (resume).
  MapSink(const CellCodec& codec, MapWriter writer, MapTally tally, int ranks);

  std::uint64_t items() const override { return writer_.layout().grid.size(); }
  std::uint64_t items_done() const override { return writer_.cells_done(); }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override;
  void store_results(const ItemRange& range, std::vector<CellResult>& results) override;
  void checkpoint() override { writer_.checkpoint(); }
  void finish(bool complete) override;
  std::string note() const override;  // the five most frequent regimes

  const MapTally& tally() const { return tally_; }

 protected:
  MapWriter writer_;
  MapTally tally_;
  int ranks_;
  std::vector<CellSpan> spans_;  // pending's scratch
};

// The sink of an adaptive map (sweep.refine > 0): one farm run per phase (refine_plan.hpp), the
// items the fine grid's points, pending those of the phase the map does not hold yet.
class RefineSink : public MapSink {
 public:
  // `plan` holds the points the map already has (resume).
  RefineSink(const CellCodec& codec, MapWriter writer, MapTally tally, int ranks, RefinePlan plan);

  // Plans `phase` and returns how many of its points remain to solve.
  std::uint64_t begin_phase(int phase);
  std::uint64_t items_pending() const override { return left_; }
  std::uint64_t scope_items() const override { return phase_points_; }  // progress: the phase's points
  std::uint64_t scope_done() const override { return phase_points_ - left_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override;
  void store_results(const ItemRange& range, std::vector<CellResult>& results) override;
  void finish(bool) override { writer_.checkpoint(); }  // a phase's end; close() ends the map
  std::string note() const override;  // the fine grid's points solved and inferred so far, the regimes
  // The fill of the inherited points (every phase done).
  void fill();
  // The last checkpoint, and after a fill the figures; closes.
  void close();
  const RefineFigures& figures() const { return figures_; }
  std::uint64_t filled() const { return filled_; }

 private:
  RefinePlan plan_;
  int phase_ = 0;
  std::uint64_t left_ = 0, filled_ = 0;
  std::uint64_t phase_points_ = 0;  // the phase's points, done or not
  // For progress lines: points solved so far (audited too), and points known to be inherited:
  // decided by the levels begun and solved by none of them.
  std::uint64_t solved_ = 0, inferred_ = 0;
  bool whole_ = false;  // filled: the run went through every phase
  RefineFigures figures_;
};

std::string regime_label(const CellResult& c);

}  // namespace vibromap::detail
