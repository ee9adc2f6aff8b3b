// Pieces shared by the commands' declarations: see command.hpp.

#include "command.hpp"

namespace vibromap::cli {

const CLI::Validator kOutputName(
    [](const std::string& s) { return s.empty() ? std::string("empty; name the file to write") : std::string(); }, "",
    "OUTPUT");

const CLI::Validator kNumber(
    [](const std::string& s) { return s.empty() ? std::string("an empty value is not a number") : std::string(); },
    "");

void add_scene_options(CLI::App& app, std::string& scene, std::vector<std::string>& sets, const std::string& help) {
  app.add_option("scene", scene, help)->required()->type_name("SCENE");
  app.add_option("-s,--set", sets,
                 "Override one scene key (repeatable): section.key=value, or key=value when only one section has the "
                 "key (as in [sweep])")
      ->allow_extra_args(false)
      ->type_name("SECTION.KEY=VALUE");
}

void add_output_option(CLI::App& app, const std::string& names, std::string& file, const std::string& help,
                       const std::string& type) {
  app.add_option(names, file, help)->check(kOutputName)->type_name(type);
}

void add_resume_options(CLI::App& app, bool& resume, bool& overwrite, const std::string& resume_help,
                        const std::string& overwrite_help) {
  CLI::Option* r = app.add_flag("--resume", resume, resume_help);
  app.add_flag("--overwrite", overwrite, overwrite_help)->excludes(r);
}

void add_format_option(CLI::App& app, std::string& format, const std::string& help) {
  app.add_option("-f,--format", format, help)
      ->check(CLI::IsMember({"table", "json"}))
      ->type_name("table|json")
      ->capture_default_str();
}

bool always_campaign(int, char**) { return true; }

}  // namespace vibromap::cli
