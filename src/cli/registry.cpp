// The registry: every command of the executable, in the order of the help. Adding a command is
// its file (src/cli/<name>_command.cpp, listed in CMakeLists.txt) and its line here.

#include <string>
#include <vector>

#include "command.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/parallel/exit_code.hpp"

namespace vibromap::cli {

Command declare_run(CLI::App& app);
Command declare_sweep(CLI::App& app);
Command declare_accuracy(CLI::App& app);
Command declare_optimise(CLI::App& app);
Command declare_orbit_diagram(CLI::App& app);
Command declare_continue(CLI::App& app);
Command declare_basins(CLI::App& app);
Command declare_restitution(CLI::App& app);
Command declare_keys(CLI::App& app);

namespace {

constexpr DeclareCommand kCommands[] = {
    declare_run,           declare_sweep,    declare_accuracy, declare_optimise,    declare_orbit_diagram,
    declare_continue,      declare_basins,   declare_restitution, declare_keys,
};

constexpr const char* kOutputs =
    "Outputs are written as a new file beside the name given, synced and renamed into place: an\n"
    "existing file is replaced only with --overwrite, and a name that is a symbolic link, a directory,\n"
    "a device or a FIFO is refused (name the link's target itself).\n";

constexpr std::size_t kWidth = 96;  // of the generated lines

// "'vibromap run --help' explains a run, 'vibromap sweep --help' a sweep, ...", one entry per
// command of the registry (none can be left out), wrapped at kWidth columns, never inside a quote.
std::string command_list(const std::vector<Command>& commands) {
  std::vector<std::string> words;
  for (std::size_t i = 0; i < commands.size(); ++i) {
    std::string entry = "'vibromap\x01" + commands[i].app->get_name() + "\x01--help' " +
                        (i == 0 ? "explains " : "") + commands[i].topic + (i + 1 < commands.size() ? "," : ".");
    std::size_t from = 0;
    for (std::size_t at; (at = entry.find(' ', from)) != std::string::npos; from = at + 1)
      words.push_back(entry.substr(from, at - from));
    words.push_back(entry.substr(from));
  }
  std::string text, line;
  for (const std::string& w : words) {
    if (!line.empty() && line.size() + 1 + w.size() > kWidth) text += line + "\n", line.clear();
    line += (line.empty() ? "" : " ") + w;
  }
  text += line;
  for (char& c : text)
    if (c == '\x01') c = ' ';
  return text;
}

}  // namespace

std::vector<Command> declare_commands(CLI::App& app) {
  std::vector<Command> commands;
  for (const DeclareCommand declare : kCommands) commands.push_back(declare(app));
  const std::string list = command_list(commands);
  app.footer(exit_code_summary() + "\n" + kOutputs + list);
  const std::string shared = cat("Exit codes: 'vibromap --help' lists them.\n", kOutputs, list);
  for (const Command& c : commands) c.app->footer(c.footer.empty() ? shared : cat(c.footer, "\n\n", shared));
  return commands;
}

}  // namespace vibromap::cli
