#pragma once
// A subcommand of the vibromap executable, as its file declares it: the CLI11 subcommand with
// its options, its footer, and the handler that runs it once the command line is parsed. The
// registry (registry.cpp) lists every command; main.cpp parses, installs the signal handlers,
// dispatches to the one parsed and reports its errors, knowing no command by name.

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace vibromap::cli {

struct Command {
  CLI::App* app = nullptr;  // the subcommand, with its options (declared by the command's file)
  std::string footer;       // its help's own footer (may be empty); the registry adds the lines every
                            // command's help shares
  std::string topic;        // what 'vibromap NAME --help' explains, for the main help ("a run")
  // Whether the command line (argv[1] is the command's name) makes it a campaign on MPI ranks,
  // or a one-process study that a stop signal ends cleanly (continue): its stop handlers then go
  // in before anything else runs. Empty: never.
  std::function<bool(int argc, char** argv)> campaign;
  std::function<int(std::ostream& out)> run;  // the parsed command; returns the exit code
};

using DeclareCommand = Command (*)(CLI::App& app);

// Declares every command of the registry on `app`, in the order of the help, with the footers
// (the main one lists the commands and the exit codes).
std::vector<Command> declare_commands(CLI::App& app);

// ---- pieces shared by the declarations (command.cpp) ----------------------------------

// An output option's value: a file name. An empty one is refused here; the rest (a link, a
// device, a name too long, an existing file without --overwrite) when the command checks it.
extern const CLI::Validator kOutputName;

// CLI11 reads an empty value as 0 for a number option (--e '' was restitution 0); an empty
// number is bad input. Given to every number option.
extern const CLI::Validator kNumber;

// The positional SCENE (with `help`) and -s,--set, the same for every command that reads a scene.
void add_scene_options(CLI::App& app, std::string& scene, std::vector<std::string>& sets, const std::string& help);

// An output file option (`names`, e.g. "-o,--output", with `help`) of type name `type`.
void add_output_option(CLI::App& app, const std::string& names, std::string& file, const std::string& help,
                       const std::string& type = "FILE.h5");

// --resume and --overwrite, which exclude each other.
void add_resume_options(CLI::App& app, bool& resume, bool& overwrite, const std::string& resume_help,
                        const std::string& overwrite_help);

// -f,--format table|json, with `help`.
void add_format_option(CLI::App& app, std::string& format, const std::string& help);

// A campaign predicate for commands that always run on the farm.
bool always_campaign(int argc, char** argv);

}  // namespace vibromap::cli
