// The scene of a command that steps keys (`orbit-diagram`, `continue`): see commands.hpp.

#include "commands.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

ParamScene scene_with_param(const SceneLoader& load, const std::vector<std::string>& sets, CommandAxis axis) {
  ParamScene out{load(sets, {axis}), axis.axis};
  return out;
}

ParamScene2 scene_with_params(const SceneLoader& load, const std::vector<std::string>& sets, CommandAxis axis,
                              CommandAxis axis2) {
  const Key k = Key::at(axis.axis.key), k2 = Key::at(axis2.axis.key);
  if (k2 == k || k2.info().name == k.info().partner)
    throw SceneError(cat(axis2.option, ": the same key as ", axis.option, " (", k.full_name(), ")"));
  ParamScene2 out{load(sets, {axis, axis2}), axis.axis, axis2.axis};
  return out;
}

}  // namespace vibromap::cli
