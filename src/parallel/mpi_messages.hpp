#pragma once
// Internal to vibromap::parallel: the one checking helper for MPI calls and the byte-message
// primitives the sweep and the optimiser share (MPI_ERRORS_RETURN is set on MPI_COMM_WORLD by
// MpiSession, so every call's return code is meaningful).

#include <vector>

namespace vibromap::detail {

// Throws std::runtime_error naming the call and MPI's error string when rc != MPI_SUCCESS.
void mpi_check(int rc, const char* what);

void send_bytes(const std::vector<char>& buf, int dest, int tag);
// Receives the next message with `tag` from `source` (MPI_ANY_SOURCE allowed); *from gets
// the sender.
std::vector<char> recv_bytes(int source, int tag, int* from = nullptr);
// Rank 0's status reaches every rank (collective); returns it.
int broadcast_status(int status);

}  // namespace vibromap::detail
