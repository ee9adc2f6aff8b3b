// Dynamic MPI distribution of a sweep's cells: see sweep_runner.hpp for the design.

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>
#include <type_traits>

#include "mpi_messages.hpp"
#include "progress.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/scene/cell_maker.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/parallel/sweep_runner.hpp"

namespace vibromap {


namespace {

using detail::broadcast_status;
using detail::mpi_check;
using detail::recv_bytes;
using detail::send_bytes;
using Clock = std::chrono::steady_clock;
static_assert(std::is_trivially_copyable_v<CellResult>, "cells travel between ranks as bytes");

constexpr int kTagResult = 1;  // worker -> 0: results of the last chunk, and a request for more
constexpr int kTagWork = 2;    // 0 -> worker: cell indices; none means stop
constexpr double kTargetChunkSeconds = 0.25;  // a chunk should take about this long
constexpr auto kPollPause = std::chrono::microseconds(100);

std::atomic<bool> g_stop_requested{false};
extern "C" void on_stop_signal(int) { g_stop_requested = true; }

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// --- Messages: [u64 count][count x u64 index][count x CellResult] ---------------------------

std::vector<char> pack(const std::vector<std::uint64_t>& index, const std::vector<CellResult>& cells) {
  const std::uint64_t n = index.size();
  std::vector<char> buf(sizeof n + n * sizeof(std::uint64_t) + cells.size() * sizeof(CellResult));
  char* p = buf.data();
  std::memcpy(p, &n, sizeof n);
  if (n > 0) std::memcpy(p + sizeof n, index.data(), n * sizeof(std::uint64_t));
  if (!cells.empty()) std::memcpy(p + sizeof n + n * sizeof(std::uint64_t), cells.data(), cells.size() * sizeof(CellResult));
  return buf;
}

void unpack(const std::vector<char>& buf, std::vector<std::uint64_t>& index, std::vector<CellResult>& cells) {
  std::uint64_t n = 0;
  std::memcpy(&n, buf.data(), sizeof n);
  index.resize(n);
  if (n > 0) std::memcpy(index.data(), buf.data() + sizeof n, n * sizeof(std::uint64_t));
  const std::size_t rest = buf.size() - sizeof n - n * sizeof(std::uint64_t);
  cells.resize(rest / sizeof(CellResult));
  if (!cells.empty()) std::memcpy(cells.data(), buf.data() + sizeof n + n * sizeof(std::uint64_t), rest);
}



// --- Solving ------------------------------------------------------------------------------

CellResult solve_cell(const CellMaker& make_cell, std::size_t flat) {
  try {
    const CellPoint cell = make_cell(flat);
    return summarize(solve_point(cell.params, cell.options));
  } catch (const std::exception&) {  // a cell's trouble is its status, never the run's
    CellResult c;
    c.status = status_code(SolveStatus::failed);
    c.regime = regime_code(RegimeKind::failed);
    return c;
  }
}

std::vector<CellResult> solve_cells(const CellMaker& make_cell, const std::vector<std::uint64_t>& index) {
  std::vector<CellResult> out;
  out.reserve(index.size());
  for (std::uint64_t i : index) out.push_back(solve_cell(make_cell, i));
  return out;
}

void worker_loop(const Scene& scene, const Grid& grid) {
  const CellMaker make_cell(scene, grid);
  std::vector<std::uint64_t> index;
  std::vector<CellResult> cells;
  for (;;) {
    send_bytes(pack(index, cells), 0, kTagResult);
    unpack(recv_bytes(0, kTagWork), index, cells);
    if (index.empty()) return;
    cells = solve_cells(make_cell, index);
  }
}

}  // namespace
}  // namespace vibromap

namespace vibromap {
namespace {

std::string regime_label(const CellResult& c) {
  return Regime{static_cast<RegimeKind>(c.regime), c.n, c.k}.label();
}

// Rank 0's side of a sweep: the queue of cells, the map being filled, checkpoints and
// progress. The coordinator thread serves the other ranks; the calling thread computes.
class Coordinator {
 public:
  Coordinator(const Scene& scene, const SweepRunConfig& config, SweepMap& map, std::vector<std::uint64_t> pending,
              int ranks)
      : scene_(scene), config_(config), map_(map), pending_(std::move(pending)), workers_(ranks - 1),
        progress_(std::cerr, config.progress, isatty(STDERR_FILENO) != 0, scene.sweep->progress_interval,
                  map.grid.size(), done_count()) {
    for (std::size_t i = 0; i < map_.cells.size(); ++i)
      if (map_.done[i]) ++regimes_[regime_label(map_.cells[i])];
  }

  void run(SweepReport& report) {
    const auto t0 = Clock::now();
    last_checkpoint_ = t0;
    const CellMaker make_cell(scene_, map_.grid);
    std::thread coordinator([this] { coordinate(); });
    for (auto chunk = take_chunk(); !chunk.empty(); chunk = take_chunk()) store(chunk, solve_cells(make_cell, chunk));
    local_done_ = true;
    coordinator.join();
    if (error_) std::rethrow_exception(error_);
    progress_.finish(done_count(), regimes_);
    report.cells_computed = computed_;
    report.checkpoints = checkpoints_;
    report.checkpoint_s = checkpoint_s_;
    report.interrupted = g_stop_requested;
    report.requests = requests_;
    report.request_s = request_s_;
    report.regimes = regimes_;
    report.wall_s = seconds_since(t0);
  }

 private:
  std::size_t done_count() const { return static_cast<std::size_t>(std::count(map_.done.begin(), map_.done.end(), 1)); }

  // Guided self-scheduling with a time target: about kTargetChunkSeconds of work, never more
  // than half a rank's share of what is left, at least one cell.
  std::vector<std::uint64_t> take_chunk() {
    std::lock_guard lock(mu_);
    if (g_stop_requested || next_ >= pending_.size()) return {};
    const std::size_t left = pending_.size() - next_;
    const std::size_t ranks = static_cast<std::size_t>(workers_) + 1;
    std::size_t n = mean_cell_s_ > 0.0 ? static_cast<std::size_t>(kTargetChunkSeconds / mean_cell_s_) : 1;
    n = std::clamp<std::size_t>(n, 1, std::max<std::size_t>(1, left / (2 * ranks)));
    if (max_chunk_ > 0) n = std::min(n, max_chunk_);
    std::vector<std::uint64_t> chunk(pending_.begin() + static_cast<long>(next_),
                                     pending_.begin() + static_cast<long>(next_ + n));
    next_ += n;
    return chunk;
  }

  void store(const std::vector<std::uint64_t>& index, const std::vector<CellResult>& cells) {
    std::lock_guard lock(mu_);
    for (std::size_t i = 0; i < index.size() && i < cells.size(); ++i) {
      map_.cells[index[i]] = cells[i];
      if (!map_.done[index[i]]) ++computed_;
      map_.done[index[i]] = 1;
      ++regimes_[regime_label(cells[i])];
      // Running mean of a cell's cost, for the chunk size.
      mean_cell_s_ = mean_cell_s_ == 0.0 ? cells[i].wall_s : 0.95 * mean_cell_s_ + 0.05 * cells[i].wall_s;
    }
  }

  void coordinate() {
    try {
      int active = workers_;
      bool stop_seen = false;
      while (active > 0 || !local_done_) {
        if (g_stop_requested && !stop_seen) {
          stop_seen = true;
          checkpoint();
        }
        if (active > 0 && serve_one_request(active)) continue;
        maybe_checkpoint();
        {
          std::lock_guard lock(mu_);
          progress_.update(done_count(), regimes_);
        }
        std::this_thread::sleep_for(kPollPause);
      }
    } catch (...) {
      error_ = std::current_exception();
      g_stop_requested = true;  // the local loop stops; the error is rethrown in run()
    }
  }

  // Answers one waiting request, if any: stores its results and hands out the next chunk.
  bool serve_one_request(int& active) {
    int flag = 0;
    MPI_Status st;
    mpi_check(MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
    if (!flag) return false;
    const auto t0 = Clock::now();
    int from = 0;
    std::vector<std::uint64_t> index;
    std::vector<CellResult> cells;
    unpack(recv_bytes(st.MPI_SOURCE, kTagResult, &from), index, cells);
    store(index, cells);
    const auto chunk = take_chunk();
    send_bytes(pack(chunk, {}), from, kTagWork);
    if (chunk.empty()) --active;
    ++requests_;
    request_s_ += seconds_since(t0);
    return true;
  }

  void maybe_checkpoint() {
    if (seconds_since(last_checkpoint_) >= scene_.sweep->checkpoint_interval) checkpoint();
  }

  void checkpoint() {
    const auto t0 = Clock::now();
    SweepMap copy;
    {
      std::lock_guard lock(mu_);
      copy = map_;
    }
    write_map(config_.output, copy);
    checkpoint_s_ += seconds_since(t0);
    ++checkpoints_;
    last_checkpoint_ = Clock::now();
  }

  const Scene& scene_;
  const SweepRunConfig& config_;
  SweepMap& map_;
  std::vector<std::uint64_t> pending_;
  int workers_;
  detail::ProgressReporter progress_;
  std::mutex mu_;
  std::size_t next_ = 0, computed_ = 0;
  double mean_cell_s_ = 0.0;
  std::map<std::string, long> regimes_;
  std::atomic<bool> local_done_{false};
  std::exception_ptr error_;
  int checkpoints_ = 0;
  double checkpoint_s_ = 0.0;
  long requests_ = 0;        // requests served for the other ranks
  double request_s_ = 0.0;   // coordinator time spent serving them, s
  // Benchmark knob: VIBROMAP_MAX_CHUNK=n caps a chunk at n cells (default: no cap), to
  // measure the coordinator's dispatch rate with one cell per request.
  std::size_t max_chunk_ = [] {
    const char* v = std::getenv("VIBROMAP_MAX_CHUNK");
    return v ? static_cast<std::size_t>(std::strtoul(v, nullptr, 10)) : std::size_t{0};
  }();
  Clock::time_point last_checkpoint_;
};

// Why a map cannot be resumed with this scene: the keys whose values differ (none when the
// run is the same), from the scene the map records, parsed as a scene is.
std::vector<std::string> resume_differences(const SweepMap& map, const Scene& scene, const std::string& output) {
  Scene recorded;
  try {
    recorded = parse_scene(map.scene_text, output);
  } catch (const SceneError& e) {
    throw SceneError(cat(output, ": --resume: the scene the map records does not read: ", e.what()));
  }
  std::vector<std::string> diff =
      canonical_differences(canonical_text(recorded, IdentityScope::sweep), canonical_text(scene, IdentityScope::sweep));
  bool same_grid = map.grid.axes().size() == scene.sweep->axes.size() && map.stored == scene.sweep->store;
  for (std::size_t d = 0; same_grid && d < map.grid.axes().size(); ++d)
    same_grid = map.grid.axes()[d].name == scene.sweep->axes[d].name && map.grid.axes()[d].values == scene.sweep->axes[d].values;
  if (diff.empty() && !same_grid) diff.push_back("the map's own grid or stored quantities");
  return diff;
}

// "a, b, c" of the first few entries, and how many more.
std::string listed(const std::vector<std::string>& items) {
  constexpr std::size_t kShown = 4;
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < kShown; ++i) out += cat(i > 0 ? ", " : "", items[i]);
  if (items.size() > kShown) out += cat(" and ", std::to_string(items.size() - kShown), " more");
  return out;
}

// Rank 0: the map to fill (new, or read back for --resume) and the cells still to compute.
SweepMap prepare_map(const Scene& scene, const SweepRunConfig& config, int ranks) {
  const Grid grid(scene.sweep->axes);
  const bool exists = std::filesystem::exists(config.output);
  if (config.resume && exists) {
    SweepMap map = read_map(config.output);
    if (const auto diff = resume_differences(map, scene, config.output); !diff.empty())
      throw SceneError(cat(config.output, ": --resume: the map was made from a different scene or grid than ",
                           scene.path, ": ", listed(diff), "; use another --output"));
    map.grid = grid;  // the scene's axes: the same values, with their keys, units and meanings
    map.scene_text = scene.text;
    map.ranks = ranks;
    return map;
  }
  if (exists && !config.resume && !config.overwrite)
    throw SceneError(config.output + ": already exists; use --resume to continue it or --overwrite to replace it");
  SweepMap map;
  map.grid = grid;
  map.stored = scene.sweep->store;
  map.cells.assign(grid.size(), CellResult{});
  map.done.assign(grid.size(), 0);
  map.scene_text = scene.text;
  map.ranks = ranks;
  return map;
}


}  // namespace

SweepReport run_sweep(const Scene& scene, const SweepRunConfig& config) {
  if (!scene.sweep) throw SceneError(scene.path + ": no [sweep] section: nothing to sweep (see 'vibromap keys')");
  int rank = 0, size = 1;
  mpi_check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
  mpi_check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
  SweepReport report;
  report.ranks = size;
  if (rank != 0) {
    if (const int code = broadcast_status(0); code != 0) throw QuietExit{code};
    std::signal(SIGUSR1, SIG_IGN);  // rank 0 decides when to stop
    worker_loop(scene, Grid(scene.sweep->axes));
    return report;
  }
  SweepMap map;
  try {
    map = prepare_map(scene, config, size);
  } catch (const SceneError&) {
    broadcast_status(2);
    throw;
  } catch (...) {
    broadcast_status(1);
    throw;
  }
  broadcast_status(0);
  std::vector<std::uint64_t> pending;
  for (std::size_t i = 0; i < map.done.size(); ++i)
    if (!map.done[i]) pending.push_back(i);
  report.cells_total = map.grid.size();
  report.cells_resumed = report.cells_total - pending.size();
  g_stop_requested = false;
  for (int sig : {SIGINT, SIGTERM, SIGUSR1}) std::signal(sig, on_stop_signal);
  Coordinator(scene, config, map, std::move(pending), size).run(report);
  write_map(config.output, map);
  return report;
}

MpiSession::MpiSession() {
  int provided = 0;
  mpi_check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  if (provided < MPI_THREAD_SERIALIZED)
    throw std::runtime_error("the MPI library does not provide MPI_THREAD_SERIALIZED, which the sweep needs");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace vibromap
