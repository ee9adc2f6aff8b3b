#include "vibromap/parallel/exit_code.hpp"

#include <array>

namespace vibromap {
namespace {

struct Row {
  ExitCode code;
  std::string_view name, meaning;
};

constexpr std::array kRows = {
    Row{ExitCode::ok, "ok", "done (an unresolved or failed cell or point is a result, reported in the output)"},
    Row{ExitCode::internal, "internal", "an unexpected error (a bug): the message says where"},
    Row{ExitCode::bad_input, "bad_input", "bad input (command line, scene or existing output): the line says what"},
    Row{ExitCode::stopped, "stopped",
        "stopped by SIGINT, SIGTERM or SIGUSR1 after a final checkpoint: run again with --resume"},
    Row{ExitCode::io, "io", "a file could not be read or written, or a resource (disk, memory) ran out"},
};

const Row& row(ExitCode e) {
  for (const Row& r : kRows)
    if (r.code == e) return r;
  return kRows[1];
}

}  // namespace

std::string_view to_string(ExitCode e) { return row(e).name; }
std::string_view describe(ExitCode e) { return row(e).meaning; }

std::string exit_code_summary() {
  std::string s = "Exit codes:";
  for (const Row& r : kRows) s.append("\n  ").append(std::to_string(code(r.code))).append("  ").append(r.meaning);
  return s;
}

}  // namespace vibromap
