// The scene of a command that steps one key (`orbit-diagram`, `continue`): see commands.hpp.

#include "commands.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

std::string short_number(double x) { return precision_number(x, 12); }

std::string exact_number(double x) { return precision_number(x, 17); }

ParamScene scene_with_param(const SceneLoader& load, std::vector<std::string> sets, const std::string& param,
                            const std::string& axis) {
  sets.push_back(cat("sweep.", param, "=", axis));
  ParamScene out;
  try {
    out.scene = load(sets);
  } catch (const SceneError& e) {  // name the option, not the override made of it
    std::string what = e.what();
    const std::string made = "--set " + sets.back();
    if (const auto at = what.find(made); at != std::string::npos) what.replace(at, made.size(), "--param " + param);
    throw SceneError(what);
  }
  for (const Axis& a : out.scene.sweep->axes)
    if (a.key == param || a.name == param) out.axis = a;
  if (out.axis.key.empty()) throw SceneError(cat("--param ", param, ": not a numeric scene key (see 'vibromap keys')"));
  return out;
}

}  // namespace vibromap::cli
