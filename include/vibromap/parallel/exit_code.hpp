#pragma once
// The exit codes of every vibromap command: one table, printed by `vibromap --help` and
// tabled in the README. A campaign that a signal stopped exits with `stopped` on every rank;
// a failure on rank 0 ends the other ranks with the same code (QuietExit), so mpirun and a
// batch script see one code whatever rank failed.

#include <string>
#include <string_view>
#include <vector>

namespace vibromap {

enum class ExitCode : int {
  ok = 0,         // done (an unresolved or failed cell, or point, is a result, reported in the output)
  internal = 1,   // an unexpected error, a bug: the message says where
  bad_input = 2,  // bad command line, scene or existing output: the line says what
  stopped = 3,    // stopped by SIGINT, SIGTERM or SIGUSR1 after a final checkpoint: --resume goes on
  io = 4,         // a file could not be read or written, or a resource (disk, memory) ran out
};

constexpr int code(ExitCode e) { return static_cast<int>(e); }
std::string_view to_string(ExitCode e);     // "ok", "internal", "bad_input", "stopped", "io"
std::string_view describe(ExitCode e);      // one line: what the code means
// "Exit codes: 0 done (...), 1 ..., ..." as a paragraph for --help footers.
std::string exit_code_summary();

// Thrown on the ranks other than 0 when rank 0 reports the error that ends the run: the
// process exits with `code` and prints nothing (rank 0 prints the one line).
struct QuietExit {
  int code;
};

}  // namespace vibromap
