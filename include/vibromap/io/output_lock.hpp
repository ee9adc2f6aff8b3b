#pragma once
// An exclusive lock on an output file for the length of a run, so that two runs never write one
// map (or one optimisation) at once. The lock is the file PATH.lock beside the output, held
// with flock(2): the kernel releases it when the holder ends, however it ends (kill -9 included),
// so a stale lock file never blocks the next run. It records the holder (pid, host, start time)
// for the message a second run gets. The lock file is removed when the holder releases it.
//
// Creating the lock file is also the first write into the output's directory: a missing or
// read-only directory is reported before anything is computed. On a file system that does not
// support locks (some NFS or Lustre mounts), the run goes on unlocked with a note on stderr.

#include <string>

namespace vibromap {

class OutputLock {
 public:
  // Takes the lock on `output` (the file PATH.lock). Throws SceneError naming the holder when
  // another run holds it, IoError when the lock file cannot be made.
  explicit OutputLock(const std::string& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  const std::string& path() const { return path_; }
  bool held() const { return fd_ >= 0; }  // false where the file system has no locks

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace vibromap
