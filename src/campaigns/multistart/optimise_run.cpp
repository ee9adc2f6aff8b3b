// The multistart campaign: see optimise_run.hpp.

#include "vibromap/campaigns/multistart/optimise_run.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "start_codec.hpp"
#include "start_sink.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/output_target.hpp"
#include "vibromap/campaigns/multistart/local_search.hpp"
#include "vibromap/campaigns/sweep/sweep_run.hpp"
#include "vibromap/campaigns/stoppable.hpp"
#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/optimise/point_objective.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/optimise_file.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/trajectory_file.hpp"
#include "vibromap/parallel/campaign.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int kVerifyTrajectoryPeriods = 2;  // periods of the best point's trajectory when the scene keeps none

// The periods of the best point's trajectory, and how many such trajectories verify_best holds
// at once (with the soft check any point may end up first: each keeps its trajectory until then).
int verify_trajectory_periods(const Scene& scene) {
  return std::max(scene.options.analysis.trajectory_periods, kVerifyTrajectoryPeriods);
}
int verify_trajectory_copies(const OptimiseOptions& o) { return o.min_soft_fraction > 0.0 ? std::max(o.best, 1) : 1; }
constexpr double kDistinct = 0.01;  // best points closer than this in every scaled variable are one point

// ---- Output, journal ------------------------------------------------------------------------

// The journal beside the result file: an existing one is an unfinished run's, which --resume
// finishes and --overwrite starts again.
OutputPolicy journal_policy(const OptimiseRunConfig& config) {
  return {.option = "journal", .overwrite = config.overwrite, .resumable = true, .resume = config.resume,
          .exists = "an unfinished run of this output left it"};
}

// Rank 0: the result file (checked and locked, for the whole run: one optimisation per output),
// then, under its lock (so that a second run on the same output is told who holds it, not
// about the first run's journal), the journal and the files written beside it later: a link, a
// device or a folder in their place is refused now, before the seeding map and the journal are
// made (an existing file is replaced).
void check_outputs(const Scene& scene, const OptimiseRunConfig& config, std::optional<OutputTarget>& target) {
  if (!scene.optimise) throw SceneError(scene.path + ": no [optimise] section: nothing to optimise (see 'vibromap keys')");
  target.emplace(config.output,
                 OutputPolicy{.overwrite = config.overwrite, .exists = config.resume ? "the optimisation is complete" : ""});
  check_output(config.journal, journal_policy(config));
  target->check_beside(config.map_output, "seeding map");
  if (config.trajectory.empty()) return;
  target->check_beside(config.trajectory, "trajectory");
  check_trajectory_fits(config.trajectory, "the best point's trajectory", verify_trajectory_periods(scene),
                        scene.options.analysis.trajectory_samples, verify_trajectory_copies(*scene.optimise));
}

// What a journal must match to be resumed: the scene's result-defining values (every
// [optimise] key included) and the seeds, one "key = value" line each.
std::string run_identity(const Scene& scene, const std::vector<Seed>& seeds) {
  std::ostringstream os;
  os.precision(17);
  os << canonical_text(scene, IdentityScope::optimise);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    os << "seed." << i << " =";
    for (const double x : seeds[i].x) os << " " << x;
    os << "\n";
  }
  return os.str();
}

Journal open_journal(const Scene& scene, const OptimiseRunConfig& config, const std::vector<Seed>& seeds) {
  const std::string identity = run_identity(scene, seeds);
  const OutputTarget journal(config.journal, journal_policy(config), OutputLocking::none);  // under the output's lock
  if (!journal.resuming()) return Journal::create(config.journal, identity);
  Journal j = Journal::open(config.journal);
  journal.check_identity(j.identity(), identity, scene.path);
  return j;
}

// ---- Seeds ----------------------------------------------------------------------------------

// The seeding sweep's scene: without [optimise] (what the seeding map records, so that changing
// an [optimise] setting does not make the map "another scene" for --resume), and without
// [census] (a census is the optimiser's check of a point, not something every seeding cell
// needs: it would make the seeding map a census map, tens of times slower).
Scene sweep_scene(const Scene& scene) {
  Scene s = scene;
  s.optimise.reset();
  s.census.reset();
  for (const char* section : {"\n[optimise]\n", "\n[census]\n"}) {
    const auto at = s.text.find(section);
    if (at == std::string::npos) continue;
    const auto next = s.text.find("\n[", at + 1);
    s.text.erase(at, next == std::string::npos ? std::string::npos : next - at);
  }
  return s;
}

// What a seeding map path that exists but is not a regular file is (empty for a regular or
// missing file: a missing one is the I/O error of opening it): HDF5 would block for ever opening
// a FIFO (deaf to the stop signals meanwhile) and read a device's bytes.
std::string_view not_a_regular_file(const std::filesystem::file_status& st) {
  switch (st.type()) {
    case std::filesystem::file_type::regular:
    case std::filesystem::file_type::not_found:
    case std::filesystem::file_type::none: return {};
    case std::filesystem::file_type::directory: return "it is a directory, not a regular file";
    case std::filesystem::file_type::fifo: return "it is a FIFO (named pipe), not a regular file";
    case std::filesystem::file_type::character: return "it is a character device, not a regular file";
    case std::filesystem::file_type::block: return "it is a block device, not a regular file";
    case std::filesystem::file_type::socket: return "it is a socket, not a regular file";
    default: return "it is not a regular file";
  }
}

// Rank 0: the best cells of a map file as seeds, read a chunk at a time (any map size).
std::vector<Seed> seeds_from_map(const Scene& scene, const std::string& path, bool made_here) {
  std::error_code ec;
  if (const std::string_view what = not_a_regular_file(std::filesystem::status(path, ec)); !what.empty())
    throw SceneError(cat(scene.path, ": [optimise] map ", path, ": ", what));
  const MapLayout layout = read_map_layout(path);
  try {
    SeedSelector selector(layout.grid, layout.stored, scene.params, *scene.optimise);
    scan_map(path, [&](std::uint64_t flat, const CellResult& c) { selector.offer(flat, c); });
    return selector.seeds();
  } catch (const std::invalid_argument& e) {
    throw SceneError(cat(scene.path, ": [optimise] seeds from ", path, ": ", e.what(),
                         made_here ? cat("; the seeding map ", path, " is kept for the next run") : std::string()));
  }
}

void broadcast_seeds(const MpiSession& mpi, std::vector<Seed>& seeds) {
  ByteWriter w;
  if (mpi.rank() == 0) {
    w.put(static_cast<std::uint64_t>(seeds.size()));
    for (const Seed& s : seeds) w.put(s.x);
  }
  std::vector<char> bytes = std::move(w.bytes());
  mpi.broadcast(bytes);
  if (mpi.rank() == 0) return;
  ByteReader r(bytes);
  seeds.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
  for (Seed& s : seeds) s.x = r.get_doubles();
}

// Step 1: the seeds on every rank. Returns the seeding sweep's stop signal (0: none).
int make_seeds(const MpiSession& mpi, const Scene& scene, const OptimiseRunConfig& config, OptimiseRun& run,
               std::vector<Seed>& seeds) {
  const OptimiseOptions& o = *scene.optimise;
  const bool sweep_first = o.map.empty() && scene.sweep.has_value();
  if (sweep_first) {
    SweepRunConfig sc;
    sc.output = config.map_output;
    sc.overwrite = config.overwrite;
    sc.resume = !config.overwrite;  // an existing map of this scene is finished or reused
    sc.progress = config.progress;
    run.sweep = run_sweep(mpi, sweep_scene(scene), sc).farm;
    const int stopped = mpi.broadcast(run.sweep.stop_signal);
    if (stopped != 0) return stopped;
  }
  run.report.seeds_from = !o.map.empty() ? o.map : sweep_first ? config.map_output : "scene";
  mpi.agree([&] {
    seeds = !o.map.empty() ? seeds_from_map(scene, o.map, false)
            : sweep_first  ? seeds_from_map(scene, config.map_output, true)
                           : std::vector<Seed>{scene_seed(scene.params, o)};
  }, exit_status_of);
  broadcast_seeds(mpi, seeds);
  return 0;
}

// ---- Best points ------------------------------------------------------------------------------

// The census of a point for min_soft_fraction: the scene's [census], else the defaults.
CensusOptions census_options(const Scene& scene) { return scene.census.value_or(CensusOptions{}); }

// The scene text of a best point: the scene, and the --set overrides that give the point.
std::string point_scene_text(const Scene& scene, const VerifiedPoint& v) {
  std::string text = scene.text;
  text += "\n# best point of vibromap optimise; vibromap run SCENE with:";
  for (const std::string& arg : optimised_overrides(v.params, *scene.optimise)) text += " --set " + arg;
  return text + "\n";
}

// Rank 0: re-solves the best points (and re-checks their soft fraction), puts those that pass
// the check first, and writes the best one's trajectory.
void verify_best(const Scene& scene, const OptimiseRunConfig& config, OptimiseReport& report) {
  const OptimiseOptions& o = *scene.optimise;
  const auto t0 = Clock::now();
  const Box box(o.variables);
  const auto points = best_points(report.starts, box, o.best, std::max(kDistinct, 10.0 * o.local.xtol_rel));
  const int periods = verify_trajectory_periods(scene);
  const bool checked = o.min_soft_fraction > 0.0;  // every point keeps its trajectory (verify_trajectory_copies)
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& [start, evaluation] = points[i];
    const int keep = (i == 0 || checked) && !config.trajectory.empty() ? periods : 0;
    report.best.push_back(verify_point(scene.params, scene.options, o, report.starts[start], evaluation, keep,
                                       census_options(scene)));
  }
  prefer_passing(report.best);
  for (std::size_t i = 1; i < report.best.size(); ++i) report.best[i].integrate.trajectory.clear();
  check_cancel();  // a stop that came as the last re-solve ended: nothing written yet
  if (!report.best.empty() && !report.best.front().integrate.trajectory.empty()) {
    write_trajectory(config.trajectory, report.best.front().integrate, point_scene_text(scene, report.best.front()));
    report.trajectory_file = std::filesystem::path(config.trajectory).filename().string();
  }
  report.verify_wall_s = seconds_since(t0);
}

// Step 3 on rank 0: verify_best, stopped by a stop signal (the re-solves of a robust check can
// take minutes, and mpirun kills the ranks a second after it passes SIGINT or SIGTERM on). A
// stop leaves the journal, which holds every start, and writes nothing: --resume runs no start
// and re-solves. Returns the stop signal (0: verified).
int verify_stoppably(const Scene& scene, const OptimiseRunConfig& config, OptimiseReport& report) {
  try {
    const CancelScope scope(&stop_flag());
    verify_best(scene, config, report);
  } catch (const Cancelled&) {
    return stop_signal();
  }
  return 0;
}

StartRecord run_one(const Scene& scene, const std::vector<Seed>& seeds, const StartSpec& spec, int rank) {
  StartRecord rec{spec, {}, rank};
  try {
    rec.result = run_start(start_parameters(scene.params, spec), scene.options, *scene.optimise,
                           seeds.at(static_cast<std::size_t>(spec.seed)),
                           spec.algorithm, census_options(scene));
  } catch (const std::exception& e) {  // a start's trouble is its result, never the run's
    rec.result.stop = std::string("FAILURE (") + e.what() + ")";
  }
  return rec;
}

FarmOptions farm_options(const OptimiseRunConfig& config) {
  FarmOptions o;
  o.label = "optimise";
  o.noun = "starts";
  o.checkpoint_interval = 10.0;  // a start takes seconds; its journal record is small
  o.progress = config.progress;
  o.progress_interval = 60.0;    // every start also prints its own line
  o.exit_code_of = exit_status_of;
  return o;
}

// Step 2: the starts on the farm. Rank 0 gets every start's record in report.starts.
void run_starts(const MpiSession& mpi, const Scene& scene, const OptimiseRunConfig& config,
                const std::vector<Seed>& seeds, OptimiseRun& run) {
  const std::vector<StartSpec> plan = plan_starts(seeds.size(), scene.optimise->algorithms, scene.optimise->laws);
  const detail::StartCodec codec(plan);
  std::unique_ptr<detail::StartSink> sink;
  mpi.agree([&] {
    sink = std::make_unique<detail::StartSink>(codec, plan, *scene.optimise, open_journal(scene, config, seeds),
                                               config.progress);
  }, exit_status_of);
  if (sink) {
    run.starts_resumed = static_cast<std::size_t>(sink->items_done());
    if (config.progress)
      std::cerr << "optimise: " << plan.size() << " starts (" << seeds.size() << " seeds x "
                << scene.optimise->algorithms.size() << " algorithms"
                << (scene.optimise->laws.empty() ? std::string() : cat(" x ", std::to_string(scene.optimise->laws.size()), " contact laws"))
                << ") on " << mpi.size() << " rank"
                << (mpi.size() > 1 ? "s" : "") << ", seeds from " << run.report.seeds_from
                << (run.starts_resumed ? cat(", ", std::to_string(run.starts_resumed), " done by an earlier run") : "")
                << "\n";
  }
  Campaign<StartRecord> campaign;
  campaign.solve = stoppable(
      [&](std::uint64_t i) { return run_one(scene, seeds, plan.at(static_cast<std::size_t>(i)), mpi.rank()); });
  campaign.codec = &codec;
  campaign.sink = sink.get();
  run.starts = run_campaign(mpi, farm_options(config), campaign);
  if (sink) run.report.starts = sink->records();
}

}  // namespace

OptimiseRun run_optimise(const MpiSession& mpi, const Scene& scene, const OptimiseRunConfig& config) {
  const auto t0 = Clock::now();
  OptimiseRun run;
  run.report.ranks = mpi.size();
  std::optional<OutputTarget> target;  // rank 0, for the whole run
  mpi.agree([&] { check_outputs(scene, config, target); }, exit_status_of);
  std::vector<Seed> seeds;
  if ((run.stop_signal = make_seeds(mpi, scene, config, run, seeds)) != 0) return run;
  run.report.sweep_wall_s = run.sweep.wall_s;
  const auto t_starts = Clock::now();
  run_starts(mpi, scene, config, seeds, run);
  if ((run.stop_signal = mpi.broadcast(run.starts.stop_signal)) != 0 || mpi.rank() != 0) return run;
  OptimiseReport& report = run.report;
  for (const FreeVariable& v : scene.optimise->variables) report.variables.emplace_back(v.name());
  report.measures = PointObjective(scene.params, scene.options, *scene.optimise).measure_names();
  report.seeds = seeds;
  report.optimise_wall_s = seconds_since(t_starts);
  if ((run.stop_signal = verify_stoppably(scene, config, report)) != 0) return run;
  report.wall_s = seconds_since(t0);
  write_optimise_file(config.output, report, *scene.optimise, scene.text);
  std::filesystem::remove(config.journal);
  return run;
}

}  // namespace vibromap
