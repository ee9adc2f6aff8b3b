#pragma once
// Internal to vibromap::parallel: the one checking helper for MPI calls (MpiSession sets
// MPI_ERRORS_RETURN on MPI_COMM_WORLD, so every return code is meaningful) and the byte-message
// primitives of the farm.

#include <mpi.h>

#include <vector>

namespace vibromap::detail {

// Throws std::runtime_error naming the call and MPI's error string when rc != MPI_SUCCESS.
void mpi_check(int rc, const char* what);

void send_bytes(const std::vector<char>& buf, int dest, int tag);
// Receives the next message with `tag` from `source` (MPI_ANY_SOURCE allowed) into `buf`;
// returns the sender.
int recv_bytes(int source, int tag, std::vector<char>& buf);
// Whether a message with `tag` is waiting (from any rank).
bool message_waiting(int tag);

}  // namespace vibromap::detail
