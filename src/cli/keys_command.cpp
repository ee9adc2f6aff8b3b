// `vibromap keys`: every scene key as a table, or as a reference scene.

#include <memory>
#include <ostream>

#include "command.hpp"
#include "vibromap/io/scene/docs.hpp"
#include "vibromap/parallel/exit_code.hpp"

namespace vibromap::cli {
namespace {

int keys_command(bool as_toml, std::ostream& out) {
  if (as_toml) {
    write_reference_scene(out);
  } else {
    write_scene_keys(out);
    out << "\nGive a key in a scene as `key = value` under its [section], or on the command line as\n"
           "`--set section.key=value` (or `--set key=value` when only one section has the key). Keys\n"
           "marked 'or give ...' form a pair: give one of the two.\n";
  }
  return code(ExitCode::ok);
}

}  // namespace

Command declare_keys(CLI::App& app) {
  auto as_toml = std::make_shared<bool>(false);
  CLI::App* keys = app.add_subcommand("keys", "List every scene key: default, unit, allowed values, meaning");
  keys->add_flag("--toml", *as_toml, "Print a reference scene instead (every key with its default)");
  return {.app = keys, .footer = {}, .topic = "the scene keys", .campaign = {},
          .run = [as_toml](std::ostream& out) { return keys_command(*as_toml, out); }};
}

}  // namespace vibromap::cli
