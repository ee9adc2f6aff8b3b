// The refinement keys of [sweep]: refine (levels), refine_on (what "differs"
// means) and refine_audit (the share of inherited points solved again). Read here, listed by
// `vibromap keys` (docs.cpp) and written into a refined map's identity (identity.cpp).

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene_internal.hpp"
#include "vibromap/core/refine/refine.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {

std::string refine_on_text(const RefineOn& on) {
  if (refine_field_is_class(on.field) || on.rel == 0.0) return to_string(on.field);
  return cat(to_string(on.field), ":", shortest(on.rel));
}

namespace detail {
namespace {

constexpr double kMaxFineCells = 1e12;  // as for a uniform grid: keeps the flat index exact

std::string refine_field_names() {
  std::vector<std::string> names;
  for (const RefineField f : all_refine_fields()) names.push_back(to_string(f));
  return join(views(names), ", ");
}

// "name" or "name:rel" (rel a finite number >= 0, continuous quantities only).
RefineOn parse_refine_on(const std::string& text, const std::string& loc) {
  const std::size_t colon = text.find(':');
  const std::string name = trim(text.substr(0, colon));
  RefineOn on;
  try {
    on.field = parse_refine_field(name);
  } catch (const std::invalid_argument&) {
    std::vector<std::string> names;
    for (const RefineField f : all_refine_fields()) names.push_back(to_string(f));
    std::string msg = cat(loc, ": unknown refine quantity '", clip(name), "'");
    if (const auto hint = closest(name, views(names))) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; allowed: ", refine_field_names(), ", a continuous one optionally as \"name:rel\""));
  }
  if (colon != std::string::npos) {
    const std::string rel = trim(text.substr(colon + 1));
    std::size_t used = 0;
    double x = std::nan("");
    try {
      x = std::stod(rel, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != rel.size() || !std::isfinite(x) || x < 0.0)
      fail(cat(loc, ": '", clip(text), "': the relative threshold after ':' must be a finite number >= 0"));
    on.rel = x;
  }
  if (colon != std::string::npos && refine_field_is_class(on.field))
    fail(cat(loc, ": '", clip(text), "': ", to_string(on.field),
             " is a class, compared exactly: give it without a threshold (only k_con, T_con, F_max, z_ratio, "
             "soft_fraction take one)"));
  if (const std::string err = validate_refine_on(on); !err.empty()) fail(cat(loc, ": ", err));
  return on;
}

// The fine grid the levels make must stay a grid vibromap can index.
void check_fine_size(const SweepOptions& sweep, const std::string& loc) {
  double cells = 1.0;
  for (const Axis& a : sweep.axes) {
    const double n = static_cast<double>(a.values.size());
    cells *= axis_is_refined(a) ? (n - 1.0) * std::ldexp(1.0, sweep.refine) + 1.0 : n;
  }
  if (cells > kMaxFineCells)
    fail(cat(loc, ": ", std::to_string(sweep.refine), " levels make a fine grid of ", shortest(cells),
             " points: at most ", shortest(kMaxFineCells)));
}

// A census's quantities: a map has them only when the scene has [census].
bool census_field(RefineField f) { return f == RefineField::attractors || f == RefineField::soft_fraction; }

// Every map keeps the classes regime, n, k and soft; a storable quantity the plan compares is
// added to sweep.store (read_refine).
bool every_map_keeps(RefineField f) {
  if (f == RefineField::regime || f == RefineField::n || f == RefineField::k || f == RefineField::soft) return true;
  const std::vector<Quantity>& all = all_quantities();
  return std::any_of(all.begin(), all.end(), [&](Quantity q) { return to_string(q) == to_string(f); });
}

// The plan reads each refine quantity from the map (a resume plans from the file): the map
// must keep it.
void check_kept(const std::vector<RefineOn>& list, bool census, const std::string& loc) {
  for (const RefineOn& on : list) {
    const std::string name = to_string(on.field);
    if (census_field(on.field) && !census)
      fail(cat(loc, ": sweep.refine_on names ", name, ", a census quantity, but the scene has no [census] section: add "
               "one (a census map keeps ", name, ") or take ", name, " out of sweep.refine_on"));
    if (!census_field(on.field) && !every_map_keeps(on.field))
      fail(cat(loc, ": sweep.refine_on names ", name, ", which a map does not store: refine on ",
               "regime, n, k, soft or a quantity of sweep.store"));
  }
}

}  // namespace

const std::vector<KeyInfo>& sweep_refine_keys() {
  static const std::vector<KeyInfo> rows = [] {
    const SweepOptions defaults;
    KeyInfo refine = option_key("sweep.refine"), audit = option_key("sweep.refine_audit");  // the key table's rows
    refine.default_text = std::to_string(defaults.refine);
    audit.default_text = shortest(defaults.refine_audit);
    return std::vector<KeyInfo>{
        refine, audit,
        {kSweep, "refine_speckle", KeyType::boolean, Bounds::finite(), {}, "-",
         "solve speckled coarse cells whole: where the answer changes twice within 3 coarse cells along every axis "
         "around a cell whose corners differ, that cell and the cells touching it are solved at every fine point "
         "(false: corners alone decide: cheaper, blind to what a cell's agreeing corners hide)",
         {}, defaults.refine_speckle ? "true" : "false", true}};
  }();
  return rows;
}

std::string refine_on_list(const std::vector<RefineOn>& list) {
  std::vector<std::string> names;
  for (const RefineOn& on : list) names.push_back(refine_on_text(on));
  return cat("[", join(views(names), ", ", "\""), "]");
}

std::string refine_on_meaning() {
  return cat("the quantities whose difference between neighbours refines a cell: classes compared exactly (",
             "regime, n, k, soft, hertz_valid, attractors: a census's count), continuous ones (k_con, T_con, F_max, "
             "z_ratio, soft_fraction) as \"name:rel\", differing when |a - b| > rel max(|a|, |b|) (no \":rel\": any "
             "difference); a continuous quantity is stored in the map; attractors and soft_fraction need a [census] section");
}

void read_refine(const toml::table& sec, const Context& ctx, bool census, SweepOptions& sweep) {
  const std::vector<KeyInfo>& keys = sweep_refine_keys();
  if (const toml::node* node = sec.get("refine")) {
    const std::string loc = locate(ctx, keys[0], *node);
    const std::optional<double> x = number_of(*node);
    if (!x || *x != std::trunc(*x) || !keys[0].bounds.contains(*x)) fail(cat(loc, ": must be ", keys[0].allowed()));
    sweep.refine = static_cast<int>(*x);
    check_fine_size(sweep, loc);
  }
  if (const toml::node* node = sec.get("refine_audit"))
    sweep.refine_audit = read_real(keys[1], *node, locate(ctx, keys[1], *node));
  if (const toml::node* node = sec.get("refine_speckle"))
    sweep.refine_speckle = read_boolean(keys[2], *node, locate(ctx, keys[2], *node)) != 0;
  if (const toml::node* node = sec.get("refine_on")) {
    const std::string loc = locate(ctx, kSweep, "refine_on", *node);
    std::vector<RefineOn> list;
    for (const std::string& text : string_list(*node, loc, cat("quantities: ", refine_field_names())))
      list.push_back(parse_refine_on(text, loc));
    if (list.empty()) fail(cat(loc, ": is empty: give at least one quantity (default ", refine_on_list(default_refine_on()), ")"));
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (list[i].field == list[j].field) fail(cat(loc, ": ", to_string(list[i].field), " is listed twice"));
    check_kept(list, census, loc);
    sweep.refine_on = std::move(list);
  }
  if (sweep.refine == 0) return;
  // A continuous quantity the plan compares must be in the map, so that a resume plans alike.
  for (const RefineOn& on : sweep.refine_on) {
    for (const Quantity q : all_quantities()) {
      if (to_string(q) != to_string(on.field)) continue;
      if (std::find(sweep.store.begin(), sweep.store.end(), q) == sweep.store.end()) sweep.store.push_back(q);
    }
  }
}

std::vector<std::string> refine_lines(const SweepOptions& sweep) {
  if (sweep.refine == 0) return {};  // a uniform map's identity is as before
  return {cat("sweep.refine = ", std::to_string(sweep.refine)),
          cat("sweep.refine_on = ", refine_on_list(sweep.refine_on)),
          cat("sweep.refine_audit = ", shortest(sweep.refine_audit)),
          cat("sweep.refine_speckle = ", sweep.refine_speckle ? "true" : "false")};
}

}  // namespace detail
}  // namespace vibromap
