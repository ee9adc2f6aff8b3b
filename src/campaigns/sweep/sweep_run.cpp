// The sweep campaign: see sweep_run.hpp.

#include "vibromap/campaigns/sweep/sweep_run.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "cell_codec.hpp"
#include "map_sink.hpp"
#include "vibromap/campaigns/census/census_cell.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/output_target.hpp"
#include "vibromap/campaigns/stoppable.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/core/analysis/point/shooting.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_families.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap {
namespace {

// The map's identity: what a resume must match (every cell-defining value, io/scene/identity.hpp).
std::string map_identity(const Scene& scene) { return canonical_text(scene, IdentityScope::sweep); }

// A note on stderr when resume() wiped damaged chunks (their cells are computed again).
void report_repair(const MapWriter& w) {
  const MapRepair& r = w.repair();
  if (r.chunks == 0) return;
  std::string datasets;
  for (const std::string& d : r.datasets) datasets += (datasets.empty() ? "" : ", ") + d;
  std::cerr << "vibromap: note: " << w.path() << ": " << r.chunks << " damaged chunk" << (r.chunks > 1 ? "s" : "")
            << " (a failed checksum or a chunk missing from its index, in " << datasets << ") wiped; their " << r.cells
            << " cells are computed again\n";
}

// Checks that a map being resumed is this scene's: the same canonical values key by key (the
// error names the keys that differ), the same grid and stored quantities.
void check_same_run(const OutputTarget& target, const MapWriter& w, const MapLayout& wanted, const Scene& scene) {
  const MapLayout& have = w.layout();
  bool same_grid = have.grid.axes().size() == wanted.grid.axes().size() && have.stored == wanted.stored &&
                   have.attractors == wanted.attractors;
  for (std::size_t d = 0; same_grid && d < wanted.grid.axes().size(); ++d)
    same_grid = have.grid.axes()[d].name == wanted.grid.axes()[d].name &&
                have.grid.axes()[d].values == wanted.grid.axes()[d].values;
  target.check_identity(have.identity, wanted.identity, scene.path,
                        same_grid ? "" : "the map's own grid or stored quantities");
}

// analysis.fragility of a map's cells: the scene's, or the largest of an axis over it (0: off).
// A census map leaves it out: its census already lists what the states around rest reach.
double fragility_of(const Scene& scene) {
  double size = scene.options.analysis.fragility;
  for (const Axis& a : scene.sweep->axes)
    if (a.key == "analysis.fragility")
      for (const double v : a.values) size = std::max(size, v);
  return size;
}

// The map's grid: the axes given, or with sweep.refine = L their fine points.
Grid map_grid(const SweepOptions& sweep) {
  if (sweep.refine == 0) return Grid(sweep.axes);
  std::vector<Axis> fine;
  for (const Axis& a : sweep.axes) fine.push_back(refine_axis(a, sweep.refine));
  return Grid(std::move(fine));
}

// Rank 0: the output (checked and locked), and the map to fill (new, or opened for --resume),
// with its regime counts.
std::unique_ptr<detail::MapSink> prepare_sink(const Scene& scene, const SweepRunConfig& config, int ranks,
                                              const detail::CellCodec& codec, std::optional<OutputTarget>& target) {
  if (!scene.sweep) throw SceneError(scene.path + ": no [sweep] section: nothing to sweep (see 'vibromap keys')");
  target.emplace(config.output,
                 OutputPolicy{.overwrite = config.overwrite, .resumable = true, .resume = config.resume});
  const std::size_t attractors = scene.census ? static_cast<std::size_t>(scene.census->max_attractors) : 0;
  MapLayout layout{map_grid(*scene.sweep), scene.sweep->store, scene.text, map_identity(scene), attractors};
  layout.census_shock = scene.census && scene.census->shock;
  const AnalysisOptions& analysis = scene.options.analysis;
  layout.steady = to_string(analysis.steady);
  layout.hertz_limit = analysis.hertz_limit;
  layout.soft_kcon = analysis.soft_kcon;
  if (!scene.census) layout.fragility = fragility_of(scene);
  const SweepOptions& sweep = *scene.sweep;
  std::optional<detail::RefinePlan> plan;
  if (sweep.refine > 0) {
    plan.emplace(sweep.axes, sweep.refine, sweep.refine_on, sweep.refine_audit, sweep.refine_speckle);
    layout.refine_levels = sweep.refine;
    for (const RefineOn& on : sweep.refine_on) {
      if (!layout.refine_on.empty()) layout.refine_on += ' ';
      layout.refine_on += refine_on_text(on);
    }
    layout.refine_audit = sweep.refine_audit;
    layout.refine_speckle = sweep.refine_speckle;
  }
  detail::MapTally tally;
  tally.census_k = scene.census ? scene.census->initial_conditions : 0;
  const auto make = [&](MapWriter w) -> std::unique_ptr<detail::MapSink> {
    if (plan) return std::make_unique<detail::RefineSink>(codec, std::move(w), std::move(tally), ranks, std::move(*plan));
    return std::make_unique<detail::MapSink>(codec, std::move(w), std::move(tally), ranks);
  };
  if (target->resuming()) {
    MapWriter w = target->read([&](const std::string& path) {
      return MapWriter::resume(path, [&](std::uint64_t, const CellResult& c) { tally.add(c); });
    });
    check_same_run(*target, w, layout, scene);
    report_repair(w);
    return make(std::move(w));
  }
  target->check_space(MapWriter::file_bytes(layout), cat("the map of ", std::to_string(layout.grid.size()), " cells"),
                      "store fewer quantities, sweep fewer cells or write elsewhere");
  return make(MapWriter::create(config.output, layout, ranks));
}

// One cell: its point solved from rest, or (with [census]) its census, seeded by `seeds`.
CellResult solve_cell(const CellMaker& cells, const std::optional<CensusOptions>& census, std::uint64_t flat,
                      const std::vector<Eigen::Vector4d>& seeds = {}) {
  try {
    CellPoint point = cells(static_cast<std::size_t>(flat));
    point.options.analysis.trajectory_periods = 0;  // a map keeps no trajectory (run --trajectory does)
    if (census) return solve_census_cell(point.params, point.options, *census, seeds);
    return summarize(solve_point(point.params, point.options));
  } catch (const std::exception&) {  // a cell's trouble is its status, never the run's
    CellResult c;
    c.status = status_code(SolveStatus::failed);
    c.regime = regime_code(RegimeKind::failed);
    return c;
  }
}

// With census.seed_from_neighbour: the cells of a line along the last axis (the farm's block).
std::uint64_t seeded_line(const Scene& scene, const Grid& grid) {
  if (!scene.census || !scene.census->seed_from_neighbour || grid.axes().empty()) return 0;
  return grid.shape().back();
}

FarmOptions farm_options(const Scene& scene, const SweepRunConfig& config, std::uint64_t line) {
  FarmOptions o;
  o.block = std::max<std::uint64_t>(line, 1);
  o.label = "sweep";
  o.noun = "cells";
  o.checkpoint_interval = scene.sweep->checkpoint_interval;
  o.progress_interval = scene.sweep->progress_interval;
  o.progress = config.progress;
  o.exit_code_of = exit_status_of;
  return o;
}

// Adds one phase's farm run to the run's report.
void add_phase(FarmReport& total, const FarmReport& r) {
  total.items_computed += r.items_computed;
  total.ranks = r.ranks;
  total.wall_s += r.wall_s;
  total.checkpoints += r.checkpoints;
  total.checkpoint_s += r.checkpoint_s;
  total.checkpoint_max_s = std::max(total.checkpoint_max_s, r.checkpoint_max_s);
  total.final_checkpoint_s += r.final_checkpoint_s;
  total.stop_signal = r.stop_signal;
  total.requests += r.requests;
  total.request_s += r.request_s;
}

// The phases of an adaptive map, one farm run each (the farm hands out one phase's points and
// returns; every rank learns from rank 0 whether a phase has points and whether it stopped),
// then the fill on rank 0.
FarmReport run_phases(const MpiSession& mpi, const FarmOptions& options, const Campaign<CellResult>& campaign,
                      detail::RefineSink* sink, int levels) {
  const auto t0 = std::chrono::steady_clock::now();
  FarmReport total;
  total.ranks = mpi.size();
  bool first = true;
  for (int phase = 0; phase <= levels + 1; ++phase) {
    int points = 0;
    mpi.agree([&] { points = sink->begin_phase(phase) > 0 ? 1 : 0; }, exit_status_of);
    if (sink && first) {
      total.items = sink->items();
      total.items_resumed = sink->items_done();
      first = false;
    }
    if (mpi.broadcast(points) == 0) continue;
    FarmOptions o = options;
    o.label = phase == 0        ? std::string("sweep coarse")
              : phase <= levels ? cat("sweep level ", std::to_string(phase), "/", std::to_string(levels))
                                : std::string("sweep audit");
    o.noun = "points";
    add_phase(total, run_campaign(mpi, o, campaign));
    total.stop_signal = mpi.broadcast(total.stop_signal);
    if (total.stop_signal != 0) break;
  }
  mpi.agree([&] {
    if (total.stop_signal == 0) sink->fill();
    sink->close();
    total.items_computed += sink->filled();
  }, exit_status_of);
  total.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return total;
}

// Rank 0, a census map whose every cell is done: the family pass over the finished map
// (io/map_families.hpp), each cell's motion scales from its point.
std::optional<FamilyPassReport> label_families(const Scene& scene, const SweepRunConfig& config,
                                               const detail::MapSink& sink, const CellMaker& cells) {
  if (!scene.census || sink.items_done() != sink.items()) return std::nullopt;
  const auto scale_of = [&](std::uint64_t flat) {
    const StateScale scale{Model(cells(static_cast<std::size_t>(flat)).params)};
    return MotionScale{scale.length(), scale.speed()};
  };
  return write_map_families(config.output, scale_of, scene.census->family_distance);
}

}  // namespace

SweepReport run_sweep(const MpiSession& mpi, const Scene& scene, const SweepRunConfig& config) {
  const detail::CellCodec codec(scene.census.has_value());
  std::optional<OutputTarget> target;
  std::unique_ptr<detail::MapSink> sink;
  mpi.agree([&] { sink = prepare_sink(scene, config, mpi.size(), codec, target); }, exit_status_of);
  const Grid grid = map_grid(*scene.sweep);
  const CellMaker cells(scene, grid);
  const std::uint64_t line = seeded_line(scene, grid);
  std::optional<SeededCells> seeded;
  if (line > 0)
    seeded.emplace(line, [&](std::uint64_t flat, const std::vector<Eigen::Vector4d>& seeds) {
      return solve_cell(cells, scene.census, flat, seeds);
    });
  Campaign<CellResult> campaign;
  campaign.solve = stoppable([&](std::uint64_t flat) {
    return seeded ? (*seeded)(flat) : solve_cell(cells, scene.census, flat);
  });
  campaign.codec = &codec;
  campaign.sink = sink.get();
  SweepReport report;
  const int levels = scene.sweep->refine;
  if (levels > 0) {
    report.farm = run_phases(mpi, farm_options(scene, config, line), campaign, static_cast<detail::RefineSink*>(sink.get()),
                             levels);
  } else {
    report.farm = run_campaign(mpi, farm_options(scene, config, line), campaign);
  }
  mpi.agree([&] {  // rank 0, which alone knows whether the run was stopped
    if (sink && report.farm.stop_signal == 0) report.totals.families = label_families(scene, config, *sink, cells);
  }, exit_status_of);
  SweepTotals& totals = report.totals;
  totals.refine_levels = levels;
  if (auto* refine = dynamic_cast<detail::RefineSink*>(sink.get())) {
    totals.refine = refine->figures();
    totals.refine_solved_now = report.farm.items_computed - refine->filled();
  }
  if (sink) {
    totals.regimes = sink->tally().regimes;
    totals.classes = sink->tally().classes;
    totals.census_budget_states = sink->tally().census_budget_states;
    totals.soft = sink->tally().soft;
    totals.impacting = sink->tally().impacting;
    totals.hertz_invalid = sink->tally().hertz_invalid;
    totals.fragile = sink->tally().fragile;
    totals.fragility_assessed = sink->tally().fragility_assessed;
  }
  if (scene.census) totals.census_initial_conditions = scene.census->initial_conditions;
  return report;
}

}  // namespace vibromap
