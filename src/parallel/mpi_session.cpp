#include "vibromap/parallel/mpi_session.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "mpi_check.hpp"
#include "vibromap/parallel/exit_code.hpp"

namespace vibromap {

bool launched_by_mpi() { return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr; }

int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  return 0;
}
namespace detail {

void mpi_check(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string("MPI ") + what + " failed: " + std::string(text, static_cast<std::size_t>(len)));
}

void send_bytes(const std::vector<char>& buf, int dest, int tag) {
  mpi_check(MPI_Send(buf.data(), static_cast<int>(buf.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD), "MPI_Send");
}

int recv_bytes(int source, int tag, std::vector<char>& buf) {
  MPI_Status st;
  mpi_check(MPI_Probe(source, tag, MPI_COMM_WORLD, &st), "MPI_Probe");
  int count = 0;
  mpi_check(MPI_Get_count(&st, MPI_BYTE, &count), "MPI_Get_count");
  buf.resize(static_cast<std::size_t>(count));
  mpi_check(MPI_Recv(buf.data(), count, MPI_BYTE, st.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return st.MPI_SOURCE;
}

bool message_waiting(int tag) {
  int flag = 0;
  mpi_check(MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE), "MPI_Iprobe");
  return flag != 0;
}

}  // namespace detail

MpiSession::MpiSession() {
  int provided = 0;
  detail::mpi_check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  if (provided < MPI_THREAD_SERIALIZED)
    throw std::runtime_error("the MPI library does not provide MPI_THREAD_SERIALIZED, which the farm needs");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

int MpiSession::broadcast(int value) const {
  detail::mpi_check(MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return value;
}

void MpiSession::broadcast(std::vector<char>& bytes) const {
  unsigned long long n = bytes.size();
  detail::mpi_check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  bytes.resize(static_cast<std::size_t>(n));
  if (n > 0)
    detail::mpi_check(MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

void MpiSession::agree(const std::function<void()>& step, const ExitClassifier& classify) const {
  if (rank_ != 0) {
    if (const int status = broadcast(0); status != 0) throw QuietExit{status};
    return;
  }
  try {
    step();
  } catch (...) {
    int status = classify ? classify(std::current_exception()) : code(ExitCode::internal);
    if (status == 0) status = code(ExitCode::internal);
    broadcast(status);
    throw;
  }
  broadcast(0);
}

void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace vibromap
