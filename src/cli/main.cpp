// The vibromap executable: declares the commands of the registry (registry.cpp), installs the
// stop handlers of a campaign, parses the command line (CLI11) and runs the command parsed.
// Every error ends here as one line on stderr, "vibromap: error: ...", with the exit code of
// parallel/exit_code.hpp.

#include <csignal>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/parallel/exit_code.hpp"
#include "vibromap/parallel/farm.hpp"
#include "vibromap/parallel/mpi_session.hpp"
#include "vibromap/parallel/signals.hpp"

namespace {

using namespace vibromap;

// The longest error line: messages clip the input they echo themselves; this is the backstop.
constexpr std::size_t kMaxErrorLine = 1000;

int report(std::string_view message, ExitCode exit) {
  std::string what = clip(message, kMaxErrorLine);
  for (char& c : what) {
    if (c == '\n' || c == '\r') c = ' ';  // one line, always
  }
  std::cerr << "vibromap: error: " << what << "\n";
  return code(exit);
}

// A stop signal that cancelled a computation outside the farm's items (none does: the campaigns
// open their cancellation scopes around items only, and continue catches its own).
int stopped_outside_a_farm() {
  std::cerr << "vibromap: stopped by " << signal_name(stop_signal()) << "\n";
  return code(ExitCode::stopped);
}

int parse_error(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  const auto subs = app.get_subcommands();
  const std::string help = subs.empty() ? "vibromap --help" : "vibromap " + subs.front()->get_name() + " --help";
  return report(std::string(e.what()) + " (see '" + help + "')", ExitCode::bad_input);
}

// The command named by argv[1]; nullptr when none is (CLI11 then says what is wrong).
const cli::Command* named(const std::vector<cli::Command>& commands, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return nullptr;
  for (const cli::Command& c : commands)
    if (c.app->check_name(argv[1])) return &c;
  return nullptr;
}

// CLI11 reports an unknown command as a missing one; name it instead.
void check_command_name(const std::vector<cli::Command>& commands, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-' || named(commands, argc, argv)) return;
  std::string names;
  for (const cli::Command& c : commands) names += (names.empty() ? "" : ", ") + c.app->get_name();
  throw CLI::ExtrasError("unknown command '" + std::string(argv[1]) + "' (commands: " + names + ")",
                         CLI::ExitCodes::ExtrasError);
}

// Without a launcher (no mpirun, no srun) vibromap is an MPI singleton on one node: Open MPI
// then needs no network transport and no X display probe, which are what can make its start-up
// take seconds (the TCP transport grows with the number of network interfaces; hwloc's GL
// plugin tries displays :0-:9). A value already set in the environment wins. (Under a launcher
// the launcher's environment decides: jobs/demo/run.sh and jobs/cluster/sweep.slurm set it.)
void single_node_mpi_defaults() {
  if (launched_by_mpi()) return;
  ::setenv("OMPI_MCA_pml", "ob1", 0);
  ::setenv("OMPI_MCA_btl", "self,vader", 0);
  ::setenv("HWLOC_COMPONENTS", "-gl,-opencl", 0);
}

// The campaign commands honour SIGINT, SIGTERM and SIGUSR1 from the first instant (a final
// checkpoint, then exit 3): their handlers go in before the command line is parsed.
void prepare_campaign(const std::vector<cli::Command>& commands, int argc, char** argv) {
  const cli::Command* command = named(commands, argc, argv);
  if (!command || !command->campaign || !command->campaign(argc, argv)) return;
  install_stop_handlers();
  single_node_mpi_defaults();
}

int dispatch(int argc, char** argv) {
  CLI::App app{"vibromap: explorer of a two-body vibro-impact system with Hertz contact", "vibromap"};
  app.set_version_flag("--version", std::string("vibromap ") + VIBROMAP_VERSION);
  app.require_subcommand(1);
  const std::vector<cli::Command> commands = cli::declare_commands(app);
  prepare_campaign(commands, argc, argv);
  try {
    check_command_name(commands, argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error(app, e);
  }
  for (const cli::Command& c : commands)
    if (c.app->parsed()) return c.run(std::cout);
  return report("no command was parsed", ExitCode::internal);  // require_subcommand(1) prevents it
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f, a batch system's) must fail a write with EFBIG, which the
  // I/O layer reports as one line, not kill the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return dispatch(argc, argv);
  } catch (const QuietExit& e) {
    return e.code;
  } catch (const Cancelled&) {  // the farm turns these into a stopped run; this is the backstop
    return stopped_outside_a_farm();
  } catch (const ItemStopped&) {
    return stopped_outside_a_farm();
  } catch (const std::exception& e) {
    return report(e.what(), exit_code_of(std::current_exception()));
  } catch (...) {
    return report("unknown error", ExitCode::internal);
  }
}
