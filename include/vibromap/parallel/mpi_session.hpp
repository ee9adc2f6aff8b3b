#pragma once
// The process's MPI session and the few collective steps a campaign needs outside the farm.
// MPI_Init_thread asks for MPI_THREAD_SERIALIZED (the farm's coordinator thread is the only
// one calling MPI while it runs) and MPI_COMM_WORLD returns errors instead of aborting, so every
// call goes through one checking helper that throws. Without mpirun the process is rank 0 of 1.

#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace vibromap {

// Maps the exception that ended a step on rank 0 to the exit code the other ranks end with.
using ExitClassifier = std::function<int(std::exception_ptr)>;

// Whether an MPI launcher (mpirun, mpiexec, srun with PMIx) started the process: Open MPI's or
// PMIx's rank variables are set. Needs no MPI call.
bool launched_by_mpi();
// The rank the launcher gave the process, from the same variables; 0 without a launcher.
int launcher_rank();

class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Rank 0 runs `step` while the others wait. When it throws, rank 0 rethrows and every other
  // rank throws QuietExit{classify(error)}; when it returns, every rank returns.
  void agree(const std::function<void()>& step, const ExitClassifier& classify) const;
  // Rank 0's value reaches every rank (collective); returns it.
  int broadcast(int value) const;
  // Rank 0's bytes reach every rank (collective); `bytes` is resized on the others.
  void broadcast(std::vector<char>& bytes) const;
  // Ends every rank at once with `code` (after an error that leaves the ranks out of step).
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace vibromap
