#include "vibromap/campaigns/exit_status.hpp"

#include <new>

#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/io/file_format.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/farm.hpp"

namespace vibromap {

ExitCode exit_code_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const QuietExit& e) {
    return static_cast<ExitCode>(e.code);
  } catch (const Cancelled&) {  // a stop signal ended a computation (core/integrate/cancel.hpp)
    return ExitCode::stopped;
  } catch (const ItemStopped&) {
    return ExitCode::stopped;
  } catch (const SceneError&) {
    return ExitCode::bad_input;
  } catch (const FileVersionError&) {  // a file of another format version (io/file_format.hpp)
    return ExitCode::bad_input;
  } catch (const IoError&) {
    return ExitCode::io;
  } catch (const std::bad_alloc&) {
    return ExitCode::io;
  } catch (...) {
    return ExitCode::internal;
  }
}

int exit_status_of(std::exception_ptr error) { return code(exit_code_of(error)); }

}  // namespace vibromap
