#include "mpi_messages.hpp"

#include <mpi.h>

#include <stdexcept>
#include <string>

namespace vibromap::detail {

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

std::vector<char> recv_bytes(int source, int tag, int* from) {
  MPI_Status st;
  mpi_check(MPI_Probe(source, tag, MPI_COMM_WORLD, &st), "MPI_Probe");
  int count = 0;
  mpi_check(MPI_Get_count(&st, MPI_BYTE, &count), "MPI_Get_count");
  std::vector<char> buf(static_cast<std::size_t>(count));
  mpi_check(MPI_Recv(buf.data(), count, MPI_BYTE, st.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  if (from != nullptr) *from = st.MPI_SOURCE;
  return buf;
}

int broadcast_status(int status) {
  mpi_check(MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return status;
}

}  // namespace vibromap::detail
