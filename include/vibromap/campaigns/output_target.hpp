#pragma once
// A campaign's output file, from the check before any work to the file resumed: one place for
// what every campaign driver (sweep, basins, optimise, orbit-diagram) does with its output.
//
//   OutputTarget target(config.output, {.overwrite = ..., .resumable = true, .resume = ...});
//   if (target.resuming()) {
//     Content c = target.read([](const std::string& path) { return read_my_file(path); });
//     target.check_identity(c.identity, wanted_identity, scene.path);   // "first differing keys"
//   } else {
//     target.check_space(bytes_of_the_new_file, "the map of 1000 cells", "sweep fewer cells");
//   }
//
// In that order, on rank 0 (inside mpi.agree, so that every rank gets its error's exit code):
// 1. The name, what is there and the exists / --resume / --overwrite rule: check_output
//    (io/output_file.hpp), one wording for every command. A link, a FIFO or a folder in the
//    output's place is refused, and an existing file unless the policy allows to replace or
//    resume it.
// 2. The run lock PATH.lock (io/output_lock.hpp): a second run on an output being written is
//    refused naming the holder. A file beside the output whose rule depends on the run (an
//    optimisation's journal) is checked after this, under the lock.
// 4. For --resume: the existing file read while a stop signal ends the run at once (HDF5 cannot
//    poll the stop flag), and its identity compared with the run's, naming the first differing
//    keys (check_same_run).
// 5. For a new file: the disk space it needs.
//
// A file beside the output (a journal, a seeding map, a trajectory) is checked with
// check_beside(), or with the free function check_output() under a policy of its own.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/io/output_file.hpp"
#include "vibromap/io/output_lock.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {

// Whether an OutputTarget takes the run lock PATH.lock.
enum class OutputLocking { lock, none };

class OutputTarget {
 public:
  // Steps 1 and 2 above. Throws SceneError (exit 2) for a bad name, an output that is not a
  // regular file, one that the policy does not allow to replace or resume, or one another run
  // holds; IoError (exit 4) for a missing directory or a lock file that cannot be made.
  OutputTarget(std::string path, const OutputPolicy& policy, OutputLocking locking = OutputLocking::lock);
  OutputTarget(const OutputTarget&) = delete;
  OutputTarget& operator=(const OutputTarget&) = delete;

  const std::string& path() const { return path_; }
  bool exists() const { return exists_; }                      // the output existed when checked
  bool resuming() const { return exists_ && resume_; }  // --resume, and a file to resume
  // The lock file ("" without a lock): what a stop while reading removes.
  std::string lock_path() const { return lock_ ? lock_->path() : std::string(); }

  // Step 4: `read(path())`, during which a stop signal ends the process at once (exit 3, the
  // lock file removed: parallel/signals.hpp's StopAtOnce).
  template <class Read>
  auto read(Read&& read) const {
    const StopAtOnce reading(lock_path());
    return read(path_);
  }

  // Step 4: throws SceneError unless `recorded` (the file's canonical identity,
  // io/scene/identity.hpp) equals `current` (the run's), naming the first differing keys; when
  // the identities agree, a non-empty `also` (what else differs, e.g. "the grid") is named.
  void check_identity(std::string_view recorded, std::string_view current, std::string_view scene_path,
                      std::string_view also = {}) const;

  // Step 5: throws IoError when the output's file system has less than `bytes` free; the
  // message says `what` needs them ("the map of 1000 cells") and what to do (`remedy`).
  void check_space(std::uint64_t bytes, std::string_view what, std::string_view remedy) const;

  // A file the run writes beside the output later (`option` names it in messages): a link, a
  // device or a folder in its place is refused now; an existing regular file may be replaced.
  void check_beside(const std::string& path, std::string_view option) const;

 private:
  std::string path_;
  bool resume_ = false;
  std::unique_ptr<OutputLock> lock_;
  bool exists_ = false;
};

// Throws SceneError, the one wording of a resume refused for another run's file, unless
// `differences` (canonical_differences' entries, or what else differs) is empty: "FILE:
// --resume: made by another run than SCENE: a, b, c, d and 3 more; use --overwrite to start
// again, or another --output".
void check_same_run(const std::string& file, const std::vector<std::string>& differences, std::string_view scene_path);

}  // namespace vibromap
