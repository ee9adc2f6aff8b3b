// The scene of a command that steps one key (`orbit-diagram`, `continue`): see commands.hpp.

#include "commands.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

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

ParamScene2 scene_with_params(const SceneLoader& load, std::vector<std::string> sets, const std::string& param,
                              const std::string& axis, const std::string& param2, const std::string& axis2) {
  const std::string made2 = cat("sweep.", param2, "=", axis2);
  const SceneLoader load2 = [&](std::vector<std::string> s) {
    s.push_back(made2);
    try {
      return load(s);
    } catch (const SceneError& e) {  // name --param2, not the override made of it
      std::string what = e.what();
      if (const auto at = what.find("--set " + made2); at != std::string::npos)
        what.replace(at, made2.size() + 6, "--param2 " + param2);
      throw SceneError(what);
    }
  };
  const ParamScene ps = scene_with_param(load2, std::move(sets), param, axis);
  ParamScene2 out{ps.scene, ps.axis, {}};
  for (const Axis& a : out.scene.sweep->axes)
    if (a.key == param2 || a.name == param2) out.axis2 = a;
  if (out.axis2.key.empty()) throw SceneError(cat("--param2 ", param2, ": not a numeric scene key (see 'vibromap keys')"));
  if (out.axis2.key == out.axis.key) throw SceneError(cat("--param2 ", param2, ": the same key as --param"));
  return out;
}

}  // namespace vibromap::cli
