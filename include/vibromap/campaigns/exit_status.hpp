#pragma once
// The one mapping from an error to the process's exit code (parallel/exit_code.hpp), shared by
// the commands (main's one catch) and the farm (the code the other ranks end with when rank 0
// fails): a bad scene or existing output, or a file of another format version, is bad_input, a
// file or resource failure is io, a rank that ends quietly keeps its code, a computation a stop
// signal cancelled is stopped, anything else is internal.

#include <exception>

#include "vibromap/parallel/exit_code.hpp"

namespace vibromap {

ExitCode exit_code_of(std::exception_ptr error);
// As exit_code_of, as the int the farm's FarmOptions::exit_code_of wants.
int exit_status_of(std::exception_ptr error);

}  // namespace vibromap
