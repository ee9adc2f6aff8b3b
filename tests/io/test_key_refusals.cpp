// One rule per key, one message: every numeric key given a value it does not allow is refused
// with the same words by each way a value reaches it (a scene file's line, `--set`, a [sweep]
// axis, a command's stepped key as `continue --param` and `orbit-diagram --param` name it, and a
// library caller's own checks), each channel putting only where the value came from in front.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/scene_testing.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/integrate/integrator.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

using test::concat;
using test::error_of;

// A value key k does not allow: below its lower end, above its upper end, or (a key that only
// asks for a finite number) infinity.
double refused_value(Key k) {
  const Bounds& b = k.info().bounds;
  if (std::isfinite(b.lo)) return b.lo - std::max(1.0, std::abs(b.lo));
  if (std::isfinite(b.hi)) return b.hi + std::max(1.0, std::abs(b.hi));
  return std::numeric_limits<double>::infinity();
}

// The value as TOML and --set write it.
std::string toml_value(double v) { return std::isinf(v) ? (v > 0 ? "inf" : "-inf") : shortest(v); }

// The refusal as the key table states it, built from its parts: "[system] m2 = -5: must be > 0 (kg)".
std::string expected_refusal(Key k, double v) {
  const KeyInfo& i = k.info();
  const std::string allowed = i.type == KeyType::integer ? concat({"an integer ", i.bounds.to_string()})
                                                         : i.bounds.to_string();
  const std::string need = std::isfinite(v) ? concat({"must be ", allowed})
                                            : concat({"must be a finite number", i.bounds.to_string() == "finite"
                                                                                     ? ""
                                                                                     : concat({" ", allowed})});
  return concat({"[", i.section, "] ", i.name, " = ", toml_value(v), ": ", need,
                 i.type == KeyType::real ? i.unit_suffix() : ""});
}

// The library's own check of the point with k set to v: validate() of the part of the point the
// key belongs to.
std::string library_refusal(Key k, double v) {
  Parameters p;
  PointOptions o;
  k.set(p, o, v);
  const std::string_view section = k.info().section;
  if (section == "solver") return validate(o.integrator);
  if (section == "analysis") return validate(o.analysis);
  const std::vector<std::string> errors = validate(p);
  return errors.empty() ? std::string() : errors.front();
}

std::string command_refusal(Key k, double v) {
  try {
    command_axis("--param " + k.full_name(), k.full_name(), {v}, AxisScale::lin, false);
  } catch (const SceneError& e) {
    return e.what();
  }
  return {};
}

TEST(KeyRefusals, EveryKeyIsRefusedInTheSameWordsByEveryChannel) {
  int checked = 0;
  for (const Key k : Key::all()) {
    if (!k.info().is_numeric()) continue;
    const KeyInfo& i = k.info();
    const double v = refused_value(k);
    const std::string refusal = expected_refusal(k, v);
    const std::string name = k.full_name(), value = toml_value(v);
    SCOPED_TRACE(name);
    // A scene file's line, and --set.
    EXPECT_EQ(error_of(concat({"[", i.section, "]\n", i.name, " = ", value, "\n"})),
              concat({"jobs/x.toml:2: ", refusal}));
    EXPECT_EQ(error_of("", {concat({name, "=", value})}), concat({"jobs/x.toml: --set ", name, "=", value, ": ", refusal}));
    // A [sweep] axis.
    const std::string axis = concat({"\"", name, "\" = { values = [", value, "] }"});
    EXPECT_EQ(error_of(concat({"[sweep]\n", axis, "\n"})),
              concat({"jobs/x.toml:2: [sweep] ", name, " = { values = [", value, "] }: the axis reaches ", refusal}));
    // A command's stepped key, and the library.
    EXPECT_EQ(command_refusal(k, v), concat({"--param ", name, ": ", refusal}));
    EXPECT_EQ(k.check(v), refusal);
    EXPECT_EQ(library_refusal(k, v), refusal);
    ++checked;
  }
  EXPECT_GE(checked, 40);  // every real and integer key of the table
}

// The numeric options of [census], [optimise] and [sweep] (option_keys()): a scene's line and
// --set are refused in the core's words (check_option), and a value inside the range is read
// back exactly (every option's field holds its whole range: an unsigned census.seed included).
TEST(KeyRefusals, EveryNumericOptionIsReadAndRefusedByItsRow) {
  const std::string base = "[optimise]\nm2 = { min = 100, max = 310 }\n[sweep]\nE1 = { values = [1e9] }\n";
  for (const KeyInfo& i : option_keys()) {
    const std::string name = i.full_name();
    SCOPED_TRACE(name);
    const double bad = std::isfinite(i.bounds.lo) ? i.bounds.lo - 1.0 : -1.0;
    const std::string refusal = check_option(name, bad);
    EXPECT_EQ(refusal, concat({"[", i.section, "] ", i.name, " = ", toml_value(bad), ": must be ",
                               i.type == KeyType::integer ? "an integer " : "", i.bounds.to_string(),
                               i.type == KeyType::real ? i.unit_suffix() : ""}));
    EXPECT_EQ(error_of(base, {concat({name, "=", toml_value(bad)})}),
              concat({"jobs/x.toml: --set ", name, "=", toml_value(bad), ": ", refusal}));
    // Its largest value, or (an open or no upper end) a value inside.
    const Bounds& b = i.bounds;
    const double top = !std::isfinite(b.hi) ? b.lo + 1.0 : b.hi_open ? 0.5 * (b.lo + b.hi) : b.hi;
    EXPECT_NO_THROW(test::parse(base, {concat({name, "=", toml_value(top)})}));
  }
  EXPECT_EQ(test::parse(base, {"census.seed=9000000000000000"}).census->seed, 9'000'000'000'000'000u);
}

// A continuation key is a parameter: a real key of [system], [contact] or [forcing].
TEST(KeyRefusals, ContinueTakesEveryParameterAndNothingElse) {
  int parameters = 0;
  for (const Key k : Key::all()) {
    SCOPED_TRACE(k.full_name());
    const double v = k.stored(Parameters{}, PointOptions{}).value_or(k.is_parameter() ? k.value(Parameters{}) : 1.0);
    if (k.is_parameter()) {
      ++parameters;
      EXPECT_EQ(command_axis("--param", k.info().name, {v}, AxisScale::lin, true).axis.key, k.full_name());
    } else {
      EXPECT_THROW(command_axis("--param", k.full_name(), {v}, AxisScale::lin, true), SceneError);
    }
  }
  EXPECT_EQ(parameters, 24);  // 11 of [system], 9 of [contact], 4 of [forcing]
}

}  // namespace
}  // namespace vibromap
