#pragma once
// The work farm: one engine under every campaign (sweep, multistart, and the ones to come).
// It knows nothing of what an item is. A campaign hands it
//   - a solver, run on every rank: item index -> the item's result, appended as bytes;
//   - a sink, on rank 0 only: how many items there are, which are still pending (resume skips
//     what is recorded as done), where results go, and how to make them durable.
// campaign.hpp adds the typed layer (a Result type, its codec, a typed sink) on top.
//
// Distribution. Rank 0 keeps the cursor over the pending items and hands them out in chunks of
// consecutive items; every rank, rank 0 included, computes. A chunk is sized to about
// `chunk_seconds` of work from the running mean item cost and never more than half a rank's
// share of what is left (guided self-scheduling: slow items near the end do not leave ranks
// idle). On rank 0 a coordinator thread answers the other ranks (each request carries the
// results of the previous chunk) while the main thread computes; it is the only thread that
// calls MPI while the farm runs (MPI_THREAD_SERIALIZED). Items are solved independently, so
// results do not depend on the number of ranks or the order.
//
// Checkpoints. Every `checkpoint_interval` seconds the sink's checkpoint() makes what it has
// stored durable; at the end finish() writes the last one. The sink decides how (a streaming
// map flushes new cells, a journal fsyncs), so a checkpoint costs what is new.
//
// Signals (signals.hpp). A stop signal on any rank, at any instant of the run, stops the
// farm: no new chunks, the final checkpoint is written, and the report names the signal (the
// command exits with ExitCode::stopped). An item in flight may be abandoned: a solver that
// polls the stop flag throws ItemStopped, and that item is not stored (a resumed run computes
// it), while the items of its chunk solved before it are. So a run whose one item takes hours
// still stops within moments of the signal.
//
// Errors. A failing sink on rank 0 ends the run on every rank: the other ranks are answered
// with the exit code `exit_code_of` gives and throw QuietExit, rank 0 rethrows the sink's
// exception. An exception escaping a solver on another rank is reported to rank 0, which stops
// every rank (exit code internal) after a final checkpoint of what was stored. No rank is left
// waiting: every worker is answered before run_farm returns or throws.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/wire.hpp"

namespace vibromap {

// Items [begin, end).
struct ItemRange {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
  std::uint64_t size() const { return end - begin; }
};

// Rank 0's side of a campaign. The farm calls it from one thread at a time.
class FarmSink {
 public:
  virtual ~FarmSink() = default;
  virtual std::uint64_t items() const = 0;       // items of the campaign
  virtual std::uint64_t items_done() const = 0;  // recorded as done (by earlier runs, then this one)
  // Items this run is to compute (chunk sizes are a share of it); a sink whose run covers only
  // some of its items (a phase of an adaptive map) says how many.
  virtual std::uint64_t items_pending() const { return items() - items_done(); }
  // Appends to `out` the pending items at or after `from`, ascending, at most `max` of them
  // (max > 0), and returns where the scan stopped: the `from` of the next call. Returns items()
  // when none are left after `out`.
  virtual std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) = 0;
  // Stores the results of `range`, read from `results` in item order.
  virtual void store(const ItemRange& range, ByteReader& results) = 0;
  virtual void checkpoint() = 0;              // makes what was stored durable and done
  virtual void finish(bool complete) = 0;     // the last checkpoint; complete: every item done
  virtual std::string note() const { return {}; }  // appended to progress lines
  // What progress lines count: the items of this run's scope and those of it done before the
  // run started (all items; a sink whose run covers some of them, a phase, says so).
  virtual std::uint64_t scope_items() const { return items(); }
  virtual std::uint64_t scope_done() const { return items_done(); }
};

// FarmSink::pending for a sink that can say of each item whether it is done: appends the items
// of [from, items) with !is_done(i), ascending and merged into ranges, at most `max` of them,
// and returns where the scan stopped.
template <class IsDone>
std::uint64_t scan_pending(std::uint64_t from, std::uint64_t max, std::uint64_t items, IsDone is_done,
                           std::vector<ItemRange>& out) {
  std::uint64_t taken = 0, i = from;
  for (; i < items && taken < max; ++i) {
    if (is_done(i)) continue;
    if (!out.empty() && out.back().end == i) {
      ++out.back().end;
    } else {
      out.push_back({i, i + 1});
    }
    ++taken;
  }
  return i;
}

// Thrown by a solver that abandons its item because a stop signal arrived (stop_flag() is set):
// the item is not stored and the farm stops as for the signal. Not a std::exception, so that a
// campaign's "an item's trouble is its result" handler lets it through.
struct ItemStopped {};

// Appends the result of `item` to `out`. Runs on every rank; must not throw for an item's own
// trouble (a campaign turns that into a result with a status); may throw ItemStopped.
using ItemSolver = std::function<void(std::uint64_t item, ByteWriter& out)>;

// Options of one farm run. The defaults are valid.
struct FarmOptions {
  std::string label = "farm";         // progress lines start with it ("sweep", "optimise"), -
  std::string noun = "items";         // what progress counts ("cells", "starts"), -
  double checkpoint_interval = 60.0;  // time between checkpoints, s (> 0)
  double progress_interval = 10.0;    // time between progress lines when stderr is not a terminal, s
  bool progress = true;               // progress lines on rank 0's stderr
  double chunk_seconds = 0.25;        // work per chunk to aim for, s (> 0)
  std::uint64_t max_chunk = 0;        // most items per chunk; 0: no cap (VIBROMAP_MAX_CHUNK overrides)
  // Chunks are whole multiples of this many items (above max_chunk if need be), so that a run from
  // the first item hands out aligned blocks (a seeded census map's lines), -
  std::uint64_t block = 1;
  std::uint32_t codec_version = 0;    // the campaign's result layout: ranks built apart must agree
  // The exit code the other ranks end with when rank 0's sink throws; empty: ExitCode::io.
  ExitClassifier exit_code_of;
};

// What a farm run did (complete on rank 0; the other ranks fill ranks and items_computed only).
struct FarmReport {
  std::uint64_t items = 0;           // of the campaign
  std::uint64_t items_resumed = 0;   // done before this run
  std::uint64_t items_computed = 0;  // stored by this run (on a worker: computed by it)
  int ranks = 1;
  double wall_s = 0.0;               // the farm's time, s
  int checkpoints = 0;               // periodic checkpoints (the final one excluded)
  double checkpoint_s = 0.0;         // time in periodic checkpoints, s
  double checkpoint_max_s = 0.0;     // the longest checkpoint, the final one included, s
  double final_checkpoint_s = 0.0;   // the final checkpoint, s
  int stop_signal = 0;               // the signal that stopped the run; 0: it ran to the end
  long requests = 0;                 // requests rank 0 served for the other ranks
  double request_s = 0.0;            // rank 0's time serving them, s
  bool complete() const { return stop_signal == 0 && items_resumed + items_computed == items; }
  // Items computed by this run per second of the farm's time (0 when no time passed).
  double items_per_s() const { return wall_s > 0 ? static_cast<double>(items_computed) / wall_s : 0.0; }
};

// Collective: every rank calls it; `sink` is used on rank 0 only (nullptr elsewhere).
FarmReport run_farm(const MpiSession& mpi, const FarmOptions& options, const ItemSolver& solve, FarmSink* sink);

}  // namespace vibromap
