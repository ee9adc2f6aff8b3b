#pragma once
// Runs a scene's [sweep] on all MPI ranks and gathers the cells into one HDF5 map.
//
// Work distribution: dynamic. Rank 0 keeps the queue of cells still to compute; every rank,
// rank 0 included, takes cells from it a chunk at a time (guided self-scheduling: chunks
// shrink as the queue empties, so a slow cell near the end does not leave ranks idle). On
// rank 0 a coordinator thread answers the other ranks' requests (each request carries the
// results of the previous chunk) while the main thread computes like any other rank, so N
// ranks compute on N cores. Only the coordinator thread calls MPI while the sweep runs
// (MPI_THREAD_SERIALIZED is enough).
//
// Checkpoints: every checkpoint_interval seconds rank 0 rewrites the map atomically
// (write_map), so a run killed at any moment (kill -9, a cluster's time limit) leaves a map
// that opens, with `done` marking the cells it holds; resume recomputes only the others.
// A cell's result depends only on its parameters, never on the rank or the order, so the
// map does not depend on the number of ranks (except wall_s).
//
// SIGINT/SIGTERM on rank 0: write a checkpoint, stop handing out cells, finish the chunks in
// flight and return with interrupted = true.
//
// Progress: rank 0 reports cells done/total, cells per second, ETA and regime counts, as a
// live line on a terminal or a plain line every progress_interval seconds otherwise.

#include <iosfwd>
#include <map>
#include <string>

#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

struct SweepRunConfig {
  std::string output;   // the map file (HDF5)
  bool resume = false;  // continue an existing map of the same scene
  bool overwrite = false;  // replace an existing map instead of refusing
  bool progress = true; // report progress on rank 0's stderr
};

struct SweepReport {
  std::size_t cells_total = 0;     // cells of the grid
  std::size_t cells_resumed = 0;   // cells already done in the map resumed from
  std::size_t cells_computed = 0;  // cells computed by this run
  int ranks = 1;
  double wall_s = 0.0;             // this run's time, s
  int checkpoints = 0;             // checkpoints written (the final write excluded)
  double checkpoint_s = 0.0;       // time spent writing checkpoints, s
  bool interrupted = false;        // stopped by a signal before the end
  long requests = 0;               // chunk requests rank 0 served for the other ranks
  double request_s = 0.0;          // rank 0's time serving them (receive, store, send), s
  std::map<std::string, long> regimes;  // regime label -> cells, over the whole map
};

// Thrown on ranks other than 0 when rank 0 failed to set up the sweep: rank 0 reports the
// error, the others exit with `code` and print nothing.
struct QuietExit {
  int code;
};

// Collective: every rank calls it with the same scene and config. Throws SceneError when the
// scene has no [sweep] or a resumed map does not belong to the scene, IoError on file errors
// (on rank 0; other ranks are told to stop).
SweepReport run_sweep(const Scene& scene, const SweepRunConfig& config);

// Process-wide MPI set-up for the executable: MPI_Init_thread with MPI_THREAD_SERIALIZED on
// construction, MPI_Finalize on destruction. rank()/size() of MPI_COMM_WORLD.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Ends every rank with this exit code (after a fatal error on one rank).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace vibromap
