// The sweep campaign: see sweep_run.hpp.

#include "vibromap/campaigns/sweep/sweep_run.hpp"

#include <filesystem>
#include <memory>

#include "cell_codec.hpp"
#include "map_sink.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap {
namespace {

// The scene text without the run-control keys that may change between a run and its resume.
std::string cell_defining_text(const std::string& text) {
  std::string out, line;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    line = text.substr(pos, end - pos);
    const auto first = line.find_first_not_of(" \t");
    const std::string_view body = first == std::string::npos ? std::string_view{} : std::string_view(line).substr(first);
    if (!body.starts_with("checkpoint_interval") && !body.starts_with("progress_interval") && !body.starts_with("#"))
      out += line + '\n';
    pos = end + 1;
  }
  return out;
}

// Rank 0: the map to fill (new, or read back for --resume).
SweepMap prepare_map(const Scene& scene, const SweepRunConfig& config, int ranks) {
  const Grid grid(scene.sweep->axes);
  const bool exists = std::filesystem::exists(config.output);
  if (config.resume && exists) {
    SweepMap map = read_map(config.output);
    bool same = map.grid.axes().size() == grid.axes().size() && map.stored == scene.sweep->store &&
                cell_defining_text(map.scene_text) == cell_defining_text(scene.text);
    for (std::size_t d = 0; same && d < grid.axes().size(); ++d)
      same = map.grid.axes()[d].name == grid.axes()[d].name && map.grid.axes()[d].values == grid.axes()[d].values;
    if (!same)
      throw SceneError(cat(config.output, ": --resume: the map was made from a different scene or grid than ",
                           scene.path, " (compare its 'scene' attribute); use another --output"));
    map.scene_text = scene.text;
    map.ranks = ranks;
    return map;
  }
  if (exists && !config.resume && !config.overwrite)
    throw SceneError(cat(config.output, ": already exists; use --resume to continue it or --overwrite to replace it"));
  SweepMap map;
  map.grid = grid;
  map.stored = scene.sweep->store;
  map.cells.assign(grid.size(), CellResult{});
  map.done.assign(grid.size(), 0);
  map.scene_text = scene.text;
  map.ranks = ranks;
  write_map(config.output, map);  // the output is known to be writable before any cell is computed
  return map;
}

CellResult solve_cell(const Scene& scene, const Grid& grid, std::uint64_t flat) {
  try {
    return summarize(solve_point(grid.cell(scene.params, static_cast<std::size_t>(flat)), scene.options));
  } catch (const std::exception&) {  // a cell's trouble is its status, never the run's
    CellResult c;
    c.status = status_code(SolveStatus::failed);
    c.regime = regime_code(RegimeKind::failed);
    return c;
  }
}

FarmOptions farm_options(const Scene& scene, const SweepRunConfig& config) {
  FarmOptions o;
  o.label = "sweep";
  o.noun = "cells";
  o.checkpoint_interval = scene.sweep->checkpoint_interval;
  o.progress_interval = scene.sweep->progress_interval;
  o.progress = config.progress;
  o.exit_code_of = exit_status_of;
  return o;
}

}  // namespace

SweepReport run_sweep(const MpiSession& mpi, const Scene& scene, const SweepRunConfig& config) {
  const detail::CellCodec codec;
  std::unique_ptr<detail::MapSink> sink;
  mpi.agree([&] {
    if (!scene.sweep) throw SceneError(scene.path + ": no [sweep] section: nothing to sweep (see 'vibromap keys')");
    sink = std::make_unique<detail::MapSink>(codec, config.output, prepare_map(scene, config, mpi.size()));
  }, exit_status_of);
  const Grid grid(scene.sweep->axes);
  Campaign<CellResult> campaign;
  campaign.solve = [&](std::uint64_t flat) { return solve_cell(scene, grid, flat); };
  campaign.codec = &codec;
  campaign.sink = sink.get();
  SweepReport report;
  report.farm = run_campaign(mpi, farm_options(scene, config), campaign);
  if (sink) report.regimes = sink->regimes();
  return report;
}

}  // namespace vibromap
