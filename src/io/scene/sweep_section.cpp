// The [sweep] section of a scene: its keys are the axes (any numeric key, each an inline table;
// sweep_axes.cpp names them) and the options order, store, checkpoint_interval and
// progress_interval (refinement: sweep_refine.cpp). They are not point keys (an axis is a table,
// order and store are arrays): read_sweep() reads them, and an axis's values are checked against
// the range of the key's own row.

#include <algorithm>
#include <cmath>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

constexpr int kMaxAxisPoints = 1'000'000;  // per axis: a typo such as n = 1e9 fails, not allocates 8 GB
constexpr double kMaxCells = 1e12;         // far beyond any run; keeps the flat cell index exact

}  // namespace

const std::vector<std::string_view>& sweep_option_keys() {
  static const std::vector<std::string_view> keys = {"order", "store", "checkpoint_interval", "progress_interval",
                                                          "refine", "refine_on", "refine_audit",
                                                          "refine_speckle"};
  return keys;
}

const std::vector<SweepInterval>& sweep_intervals() {
  static const std::vector<SweepInterval> rows = [] {
    const SweepOptions defaults;
    auto interval_row = [&](std::string_view key, double SweepOptions::*f) {
      KeyInfo info = option_key(cat(kSweep, ".", key));  // the key table's row
      info.default_text = float_text(defaults.*f);
      return SweepInterval{std::move(info), f};
    };
    return std::vector<SweepInterval>{interval_row("checkpoint_interval", &SweepOptions::checkpoint_interval),
                                      interval_row("progress_interval", &SweepOptions::progress_interval)};
  }();
  return rows;
}

// The dataset names of the storable quantities, in the quantity table's order (core/quantities.hpp).
const std::vector<std::string>& quantity_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Quantity q : all_quantities()) n.push_back(to_string(q));
    return n;
  }();
  return names;
}

double axis_end(const toml::table& axis, std::string_view field, const std::string& loc) {
  const std::optional<double> x = number_of(*axis.get(field));
  if (!x || !std::isfinite(*x)) fail(cat(loc, ": ", field, " must be a finite number"));
  return *x;
}

AxisScale axis_scale(const toml::table& axis, const std::string& loc) {
  const toml::node* node = axis.get("scale");
  if (node == nullptr) return AxisScale::lin;
  const auto* s = node->as_string();
  if (s != nullptr && (s->get() == "lin" || s->get() == "log")) return parse_axis_scale(s->get());
  std::string msg = cat(loc, ": scale must be one of \"lin\", \"log\"");
  if (s != nullptr) {
    if (const auto hint = closest(s->get(), {"lin", "log"})) msg += cat(" (did you mean \"", *hint, "\"?)");
  }
  fail(msg);
}

namespace {

int axis_count(const toml::node& node, const std::string& loc) {
  const std::optional<double> x = number_of(node);  // a whole float such as 23.0 is accepted
  if (!x || *x != std::trunc(*x) || *x < 1.0 || *x > kMaxAxisPoints) {
    fail(cat(loc, ": n must be an integer in [1, ", std::to_string(kMaxAxisPoints), "]"));
  }
  return static_cast<int>(*x);
}

// The axis's table, with no field but from, to, n, values and scale.
const toml::table& axis_table(std::string_view name, const toml::node& node, const std::string& loc) {
  const toml::table* t = node.as_table();
  if (t == nullptr) fail(cat(loc, ": axis ", name, " must be an inline table ", kAxisForms));
  const std::vector<std::string_view> fields = {"from", "to", "n", "values", "scale"};
  for (auto&& [key, value] : *t) {
    if (std::find(fields.begin(), fields.end(), key.str()) != fields.end()) continue;
    std::string msg = cat(loc, ": unknown field '", clip(key.str()), "' in axis ", name);
    if (const auto hint = closest(key.str(), fields)) msg += cat(" (did you mean '", *hint, "'?)");
    fail(cat(msg, "; an axis is ", kAxisForms));
  }
  return *t;
}

std::vector<double> range_points(std::string_view name, const toml::table& axis, AxisScale scale,
                                 const std::string& loc) {
  for (const std::string_view field : {"from", "to", "n"}) {
    if (!axis.contains(field)) fail(cat(loc, ": axis ", name, " lacks '", field, "': an axis is ", kAxisForms));
  }
  const double from = axis_end(axis, "from", loc), to = axis_end(axis, "to", loc);
  const int n = axis_count(*axis.get("n"), loc);
  if (scale == AxisScale::log && (from <= 0.0 || to <= 0.0)) {
    fail(cat(loc, ": a log axis needs from > 0 and to > 0"));
  }
  if (n > 1 && from == to) fail(cat(loc, ": from = to with n = ", std::to_string(n), " repeats a point"));
  return axis_points(from, to, n, scale);
}

std::vector<double> listed_points(const toml::node& node, const std::string& loc) {
  const toml::array* a = node.as_array();
  if (a == nullptr) fail(cat(loc, ": values must be an array of finite numbers"));
  if (a->empty()) fail(cat(loc, ": values is empty: give at least one point"));
  std::vector<double> v;
  for (const toml::node& e : *a) {
    const std::optional<double> x = number_of(e);  // a non-finite one is the key's to refuse
    if (!x) fail(cat(loc, ": values must be numbers, not ", clipped_text(e)));
    v.push_back(*x);
  }
  if (std::any_of(v.begin(), v.end(), [](double x) { return std::isnan(x); })) return v;  // the key refuses it
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  if (const auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end()) {
    fail(cat(loc, ": values repeat ", shortest(*it), ": give each point once"));
  }
  return v;
}

// The axis over key k (make_axis), its values checked against the key: every point within the
// range the key allows (E1 > 0, ...), and whole for an integer key.
Axis checked_axis(Key k, std::vector<double> values, AxisScale scale, const std::string& loc) {
  for (const double v : values) {
    if (scale == AxisScale::log && v <= 0.0) fail(cat(loc, ": a log axis needs values > 0"));
    if (const std::string r = k.check(v); !r.empty()) fail(cat(loc, ": the axis reaches ", r));
  }
  try {
    return make_axis(k, std::move(values), scale);
  } catch (const std::invalid_argument& e) {
    fail(cat(loc, ": ", e.what()));
  }
}

// A categorical axis (contact.law = { values = ["hertz", "flores"] }): the names as indices
// into the key's choices, which the axis keeps whole so that a map names every index.
Axis read_categorical_axis(Key k, std::string_view name, const toml::table& t, const std::string& loc) {
  const KeyInfo& info = k.info();
  const toml::node* values = t.get("values");
  const toml::array* a = values != nullptr ? values->as_array() : nullptr;
  if (a == nullptr || a->empty() || t.size() != 1)
    fail(cat(loc, ": axis ", name, " is categorical: give it as { values = [\"name\", ...] } with names ",
             info.allowed()));
  std::vector<double> indices;
  for (const toml::node& e : *a) {
    const double index = read_choice(info, e, loc);
    if (std::find(indices.begin(), indices.end(), index) != indices.end())
      fail(cat(loc, ": values repeat ", clipped_text(e), ": give each point once"));
    indices.push_back(index);
  }
  return checked_axis(k, std::move(indices), AxisScale::lin, loc);
}

// One axis over key `k`, named `given` in the scene.
Axis read_axis(Key k, std::string_view given, const toml::node& node, const std::string& loc) {
  const std::string name = clip(given);
  const toml::table& t = axis_table(name, node, loc);
  if (k.is_categorical()) return read_categorical_axis(k, name, t, loc);
  const AxisScale scale = axis_scale(t, loc);
  const toml::node* values = t.get("values");
  if (values != nullptr && (t.contains("from") || t.contains("to") || t.contains("n"))) {
    fail(cat(loc, ": axis ", name, " gives both values and from/to/n: an axis is ", kAxisForms));
  }
  return checked_axis(k, values != nullptr ? listed_points(*values, loc) : range_points(name, t, scale, loc), scale, loc);
}

// The axes the file gives and the command's, in the default order (key_rank); `given` receives
// their names as the scene or the command gives them.
std::vector<Axis> read_axes(const toml::table& sweep, const Context& ctx, std::vector<std::string>& given) {
  struct Given {
    Axis axis;
    std::string name;
  };
  std::vector<Given> all;
  for (const SweepAxisEntry& e : sweep_axis_entries(sweep, ctx))
    all.push_back({read_axis(e.key, e.given, *e.node, locate(ctx, kSweep, e.given, *e.node)), e.given});
  for (const CommandAxis& a : ctx.axes) all.push_back({a.axis, a.axis.name});
  if (all.empty()) {
    fail(cat(where(ctx, sweep), ": [sweep] has no axes: give at least one real or integer key (E1, \"forcing.omega\", "
             "...) as KEY = ", kAxisForms));
  }
  if (all.size() > kMaxSweepAxes) {
    fail(cat(where(ctx, sweep), ": [sweep] has ", std::to_string(all.size()), " axes: at most ",
             std::to_string(kMaxSweepAxes)));
  }
  std::stable_sort(all.begin(), all.end(), [](const Given& a, const Given& b) {
    return key_rank(Key::at(a.axis.key)) < key_rank(Key::at(b.axis.key));
  });
  std::vector<Axis> axes;
  for (Given& g : all) {
    axes.push_back(std::move(g.axis));
    given.push_back(std::move(g.name));
  }
  return axes;
}

// Reorders the axes as `order` lists them, by any of their names: each axis exactly once, but
// for a command's own axes (`continue --param`), which the file's order cannot know of: those
// the order leaves out follow the listed ones.
void apply_order(std::vector<Axis>& axes, const std::vector<std::string>& given, const toml::node& node,
                 const std::string& loc, const std::vector<CommandAxis>& command_axes) {
  const std::vector<std::string_view> names = views(given);
  const std::string axes_text = clip(join(names, ", "), 200);
  std::vector<std::size_t> order;  // indices into axes
  for (const std::string& name : string_list(node, loc, cat("the axes: ", axes_text))) {
    const std::optional<Key> k = Key::find(name);
    const auto it = std::find_if(axes.begin(), axes.end(), [&](const Axis& a) { return k && a.key == k->full_name(); });
    if (it == axes.end()) {
      std::string msg = cat(loc, ": '", clip(name), "' is not an axis of this sweep");
      if (const auto hint = closest(name, names)) msg += cat(" (did you mean '", *hint, "'?)");
      fail(cat(msg, "; axes: ", axes_text));
    }
    const auto index = static_cast<std::size_t>(it - axes.begin());
    if (std::find(order.begin(), order.end(), index) != order.end()) fail(cat(loc, ": axis ", clip(name), " is listed twice"));
    order.push_back(index);
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const bool commands = std::any_of(command_axes.begin(), command_axes.end(),
                                      [&](const CommandAxis& c) { return c.axis.key == axes[i].key; });
    if (commands && std::find(order.begin(), order.end(), i) == order.end()) order.push_back(i);
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (std::find(order.begin(), order.end(), i) == order.end()) {
      fail(cat(loc, ": axis ", clip(given[i]), " is missing: order must list every axis once (", axes_text, ")"));
    }
  }
  std::vector<Axis> ordered;
  for (const std::size_t i : order) ordered.push_back(std::move(axes[i]));
  axes = std::move(ordered);
}

std::vector<Quantity> read_store(const toml::node& node, const std::string& loc) {
  const std::string allowed = join(views(quantity_names()), ", ");
  std::vector<Quantity> store;
  for (const std::string& name : string_list(node, loc, cat("quantities: ", allowed))) {
    const auto& names = quantity_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string msg = cat(loc, ": unknown quantity '", clip(name), "'");
      if (const auto hint = closest(name, views(names))) msg += cat(" (did you mean '", *hint, "'?)");
      fail(cat(msg, "; allowed: ", allowed));
    }
    const Quantity q = parse_quantity(name);
    if (std::find(store.begin(), store.end(), q) != store.end()) fail(cat(loc, ": quantity ", name, " is listed twice"));
    store.push_back(q);
  }
  return store;
}

void check_grid_size(const std::vector<Axis>& axes, const Context& ctx) {
  double cells = 1.0;
  for (const Axis& a : axes) cells *= static_cast<double>(a.values.size());
  if (cells > kMaxCells) {
    fail(cat(ctx.path, ": [sweep] the grid has ", shortest(cells), " cells: at most ", shortest(kMaxCells)));
  }
}

}  // namespace

std::optional<SweepOptions> read_sweep(const toml::table& table, const Context& ctx) {
  static const toml::table kNone;
  const toml::table* sec = table.get_as<toml::table>(kSweep);
  if (sec == nullptr && ctx.axes.empty()) return std::nullopt;
  if (sec == nullptr) sec = &kNone;  // the command's axes only
  SweepOptions sweep;
  std::vector<std::string> given;
  sweep.axes = read_axes(*sec, ctx, given);
  if (const toml::node* node = sec->get("order")) apply_order(sweep.axes, given, *node, locate(ctx, kSweep, "order", *node), ctx.axes);
  if (const toml::node* node = sec->get("store")) sweep.store = read_store(*node, locate(ctx, kSweep, "store", *node));
  // Every map says where the Hertz law holds: its pictures mark the cells where it does not.
  if (std::find(sweep.store.begin(), sweep.store.end(), Quantity::hertz_valid) == sweep.store.end())
    sweep.store.push_back(Quantity::hertz_valid);
  for (const SweepInterval& row : sweep_intervals()) {
    if (const toml::node* node = sec->get(row.info.name)) sweep.*row.field = read_real(row.info, *node, locate(ctx, row.info, *node));
  }
  check_grid_size(sweep.axes, ctx);
  read_refine(*sec, ctx, table.get_as<toml::table>(kCensus) != nullptr, sweep);
  return sweep;
}

}  // namespace vibromap::detail
