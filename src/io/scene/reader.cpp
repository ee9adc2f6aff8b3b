#include "vibromap/io/scene/scene.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/cell_maker.hpp"

// Reading a scene: parse the TOML, apply the overrides, check the structure (sections and
// keys), read and check each key's value, then the [sweep] and [optimise] sections, and
// write the Scene's text.

namespace vibromap {
namespace detail {

[[noreturn]] void fail(const std::string& message) { throw SceneError(message); }

std::string where(const Context& ctx, const toml::node& node) {
  const auto line = node.source().begin.line;
  return line > 0 ? ctx.path + ":" + std::to_string(line) : ctx.path;
}

std::string value_text(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return vibromap::value_text(f->get());
  return clipped_text(node);
}

std::string origin(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node) {
  const auto it = ctx.overrides.find(cat(section, ".", key));
  return it != ctx.overrides.end() ? cat(ctx.path, ": ", clip(it->second)) : where(ctx, node);
}

std::string locate(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node) {
  return cat(origin(ctx, section, key, node), ": [", section, "] ", clip(key), " = ", value_text(node));
}

std::string locate(const Context& ctx, const KeyInfo& k, const toml::node& node) {
  return locate(ctx, k.section, k.name, node);
}

std::optional<double> number_of(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return f->get();
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  return std::nullopt;
}

double read_real(const KeyInfo& k, const toml::node& node, const std::string& loc) {
  const double x = number_of(node).value_or(std::numeric_limits<double>::quiet_NaN());
  if (const std::string need = k.requirement(x); !need.empty()) fail(cat(loc, ": ", need));
  return x;
}

int read_choice(const KeyInfo& k, const toml::node& node, const std::string& loc) {
  const auto* s = node.as_string();
  if (s != nullptr) {
    for (std::size_t i = 0; i < k.choices.size(); ++i) {
      if (k.choices[i] == s->get()) return static_cast<int>(i);
    }
  }
  std::string msg = loc + ": must be " + k.allowed();
  if (s != nullptr) {
    if (const auto hint = closest(s->get(), k.choices)) msg += cat(" (did you mean \"", *hint, "\"?)");
  }
  fail(msg);
}

long long read_boolean(const KeyInfo& k, const toml::node& node, const std::string& loc) {
  if (const auto* b = node.as_boolean()) return b->get() ? 1 : 0;
  fail(loc + ": must be " + k.allowed());
}

std::vector<std::string> string_list(const toml::node& node, const std::string& loc, std::string_view what) {
  const toml::array* a = node.as_array();
  std::vector<std::string> out;
  for (std::size_t i = 0; a != nullptr && i < a->size(); ++i) {
    const auto* s = a->get(i)->as_string();
    if (s == nullptr) break;
    out.push_back(s->get());
  }
  if (a == nullptr || out.size() != a->size()) fail(cat(loc, ": must be an array of strings (", what, ")"));
  return out;
}

namespace {

// ---------------------------------------------------------------------------------------
// Structure: sections, keys, overrides.

// Keys a scene may still carry from an earlier version, with what replaced them.
struct RetiredKey {
  std::string_view section, key, instead;
};
constexpr RetiredKey kRetiredKeys[] = {
    {"analysis", "basin_check",
     "the motion from the initial state is now the default answer (analysis.steady = \"follow\"); "
     "analysis.steady = \"shooting\" asks for the faster \"some stable orbit exists\" answer"},
    {"census", "soft_kcon", "soft has one definition everywhere: set analysis.soft_kcon"},
};

[[noreturn]] void fail_unknown_key(const std::string& loc, std::string_view section, std::string_view key) {
  for (const RetiredKey& r : kRetiredKeys)
    if (r.section == section && r.key == key) fail(cat(loc, ": [", section, "] ", key, " was removed: ", r.instead));
  std::string msg = cat(loc, ": unknown key '", clip(key), "' in [", section, "]");
  const auto keys = keys_of(section);
  const auto home = section_of(key);
  if (const std::optional<Key> k = Key::find(key); k && section == kOptimise && !k->is_parameter()) {
    msg += cat(" (", k->full_name(), " cannot be a free parameter: free parameters are the real keys of [system], ",
               "[contact] and [forcing])");
  } else if (home) {
    msg += cat(" (it belongs in [", *home, "])");
  } else if (const auto hint = closest(key, keys)) {
    msg += cat(" (did you mean '", *hint, "'?)");
  }
  fail(cat(msg, "; keys of [", section, "]: ", join(keys, ", ")));
}

[[noreturn]] void fail_unknown_section(const std::string& loc, std::string_view name) {
  std::string msg = cat(loc, ": unknown section [", clip(name), "]");
  if (const auto hint = closest(name, all_sections())) msg += cat(" (did you mean [", *hint, "]?)");
  fail(cat(msg, "; sections: ", join(all_sections(), ", ")));
}

[[noreturn]] void fail_key_outside_section(const std::string& loc, std::string_view key) {
  if (const auto home = section_of(key)) {
    fail(cat(loc, ": key '", clip(key), "' is outside any section: put it under [", *home, "]"));
  }
  fail_unknown_section(loc, key);
}

toml::table parse_toml(std::string_view text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& pos = e.source().begin;
    fail(cat(path, ":", std::to_string(pos.line), ":", std::to_string(pos.column), ": malformed TOML: ",
             e.description()));
  }
}

// Reads an override's value as TOML ("310", "1e-8", "\"rk4\""), else as a string ("rk4").
void assign_override_value(toml::table& section, std::string_view key, const std::string& raw) {
  try {
    const toml::table parsed = toml::parse("v = " + raw);
    const toml::node* node = parsed.get("v");
    if (parsed.size() == 1 && node != nullptr) {
      node->visit([&](const auto& n) { section.insert_or_assign(key, n); });
      return;
    }
  } catch (const toml::parse_error&) {
    // not a TOML value: a bare string
  }
  section.insert_or_assign(key, raw);
}

// The sections with a key of this name: the point keys', then [sweep], [optimise] and [census] options.
std::vector<std::string_view> sections_with_key(std::string_view name) {
  std::vector<std::string_view> homes;
  for (const Key k : Key::all())
    if (k.info().name == name) homes.push_back(k.info().section);
  const auto has = [&](const std::vector<std::string_view>& keys) { return std::find(keys.begin(), keys.end(), name) != keys.end(); };
  if (has(sweep_option_keys())) homes.push_back(kSweep);
  if (has(optimise_option_keys())) homes.push_back(kOptimise);
  if (has(census_keys())) homes.push_back(kCensus);
  return homes;
}

// An override named by its key alone (m2, omega, E1): section.key when only one section has
// that key, as a [sweep] axis is named (sweep_axes.cpp); else one line saying why not.
std::string qualified_override_name(const std::string& name, const std::string& loc) {
  const std::vector<std::string_view> homes = sections_with_key(name);
  if (homes.size() == 1) return cat(homes.front(), ".", name);
  if (homes.size() > 1) {
    std::vector<std::string> choices;
    for (const std::string_view s : homes) choices.push_back(cat(s, ".", name));
    fail(cat(loc, ": several sections have the key '", name, "': name it section.key (", join(views(choices), " or "), ")"));
  }
  std::vector<std::string> keys;
  for (const Key k : Key::all()) keys.emplace_back(k.info().name);
  std::string msg = cat(loc, ": unknown key '", clip(name), "'");
  if (const auto hint = closest(name, views(keys))) msg += cat(" (did you mean '", *hint, "'?)");
  fail(cat(msg, "; expected section.key=value, or key=value when only one section has the key (e.g. --set system.m2=310)"));
}

void apply_override(toml::table& table, const std::string& given, Context& ctx) {
  const std::string option = "--set " + given;
  const std::string loc = cat(ctx.path, ": ", clip(option));
  const auto eq = given.find('=');
  std::string name = trim(std::string_view(given).substr(0, std::min(eq, given.size())));
  if (eq != std::string::npos && !name.empty() && name.find('.') == std::string::npos)
    name = qualified_override_name(name, loc);  // m2=300 is system.m2=300
  const auto dot = name.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == name.size()) {
    const auto home = section_of(name);
    const std::string example = home ? cat(*home, ".", name, "=...") : std::string("system.m2=310");
    fail(cat(loc, ": expected section.key=value (e.g. --set ", example, ")"));
  }
  const std::string section = name.substr(0, dot), key = name.substr(dot + 1);
  if (!is_section(section)) fail_unknown_section(loc, section);
  if (section != kSweep && !has_key(section, key)) fail_unknown_key(loc, section, key);
  if (!table.contains(section)) table.insert(section, toml::table{});
  toml::table* sec = table.get_as<toml::table>(section);
  if (sec == nullptr) fail(cat(where(ctx, *table.get(section)), ": '", section, "' must be a section [", section, "]"));
  // --set replaces every spelling of the key and the other form of a pair
  if (section == kSweep && !is_sweep_option(key)) erase_sweep_axis(*sec, key, loc);
  if (section == kOptimise && !is_optimise_option(key)) erase_key_entries(*sec, *free_parameter(key), is_optimise_option);
  assign_override_value(*sec, key, trim(std::string_view(given).substr(eq + 1)));
  if (const auto partner = partner_of(section, key); !partner.empty()) sec->erase(partner);
  ctx.overrides[name] = option;
  ctx.override_list.push_back(option);
}

// A command's axes replace the file's axes of their keys (and of their pair partners).
void replace_file_axes(toml::table& table, const Context& ctx) {
  toml::table* sweep = table.get_as<toml::table>(kSweep);
  if (sweep == nullptr) return;
  for (const CommandAxis& a : ctx.axes) erase_key_entries(*sweep, Key::at(a.axis.key), is_sweep_option);
}

void check_structure(const toml::table& table, const Context& ctx) {
  for (auto&& [name, node] : table) {
    if (!is_section(name.str())) {
      if (node.is_table() || node.is_array_of_tables()) fail_unknown_section(where(ctx, node), name.str());
      fail_key_outside_section(where(ctx, node), name.str());
    }
    const toml::table* sec = node.as_table();
    if (sec == nullptr) {
      fail(cat(where(ctx, node), ": '", name.str(), "' must be a section [", name.str(), "], not a value"));
    }
    if (name.str() == kSweep) {
      sweep_axis_entries(*sec, ctx);  // checks the axes' names; the options are known keys
      continue;
    }
    if (name.str() == kOptimise) {  // the free parameters by any name, the options
      for_each_key_entry(*sec, is_optimise_option, [&](const std::string& given, const std::string&, const toml::node& value) {
        if (!free_parameter(given)) fail_unknown_key(where(ctx, value), kOptimise, given);
      });
      continue;
    }
    for (auto&& [key, value] : *sec) {
      if (!has_key(name.str(), key.str())) fail_unknown_key(where(ctx, value), name.str(), key.str());
    }
  }
}

void check_pair(const toml::table& section, const KeyInfo& k, const Context& ctx, const toml::node& node) {
  if (k.partner.empty() || !section.contains(k.partner)) return;
  const KeyInfo& other = Key::at(cat(k.section, ".", k.partner)).info();
  fail(cat(where(ctx, node), ": [", k.section, "] both ", k.name, " and ", k.partner, " given: give only one ",
           pair_advice(k, other)));
}

// ---------------------------------------------------------------------------------------
// Values.

// A whole number, from a TOML integer or a whole float such as 2000.0; NaN for anything else.
double whole_number(const toml::node& node) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  const double v = number_of(node).value_or(std::numeric_limits<double>::quiet_NaN());
  return v == std::trunc(v) ? v : std::numeric_limits<double>::quiet_NaN();
}

// The checked value of point key k as Key::set takes it (a choice: its index; a boolean: 0 or 1).
double read_value(Key k, const toml::node& node, const std::string& loc) {
  const KeyInfo& info = k.info();
  switch (info.type) {
    case KeyType::real: return read_real(info, node, loc);
    case KeyType::integer: {
      const double n = whole_number(node);
      if (const std::string need = k.requirement(n); !need.empty()) fail(cat(loc, ": ", need));
      return n;
    }
    case KeyType::choice: return read_choice(info, node, loc);
    case KeyType::boolean: return static_cast<double>(read_boolean(info, node, loc));
  }
  return 0.0;
}

// Every key in key table order ([initial] last, after D), then [sweep], [optimise] and [census].
Scene read_values(const toml::table& table, const Context& ctx) {
  Scene scene;
  for (const Key k : Key::all()) {
    const KeyInfo& info = k.info();
    const toml::table* sec = table.get_as<toml::table>(info.section);
    const toml::node* node = sec != nullptr ? sec->get(info.name) : nullptr;
    if (node == nullptr) continue;
    check_pair(*sec, info, ctx, *node);
    k.set(scene.params, scene.options, read_value(k, *node, locate(ctx, info, *node)));
    if (k.component() >= 0) scene.initial_given.at(static_cast<std::size_t>(k.component())) = true;
  }
  scene.sweep = read_sweep(table, ctx);
  scene.optimise = read_optimise(table, ctx);
  scene.census = read_census(table, ctx);
  if (scene.census)
    if (const std::string e = census_method_error(scene.options.integrator); !e.empty()) fail(cat(ctx.path, ": ", e));
  if (scene.census && scene.census->seed_from_neighbour && scene.sweep && scene.sweep->refine > 0)
    fail(cat(ctx.path, ": [census] seed_from_neighbour = true: needs a uniform map (sweep.refine = 0), whose lines "
                       "along the last axis are followed cell by cell"));
  return scene;
}

// The scene as TOML, keys in key table order, preceded by its source and overrides.
std::string scene_text(const toml::table& table, const Context& ctx) {
  std::ostringstream os;
  os << "# scene: " << ctx.path << "\n";
  if (!ctx.override_list.empty()) {
    os << "# overrides:";
    for (const std::string& o : ctx.override_list) os << " " << o;
    os << "\n";
  }
  for (std::string_view section : all_sections()) {
    const toml::table* sec = table.get_as<toml::table>(section);
    if (sec == nullptr || sec->empty()) continue;
    os << "\n[" << section << "]\n";
    if (section == kSweep) {  // the axes as given, in the default order, then the options
      for (const SweepAxisEntry& e : sweep_axis_entries(*sec, ctx)) os << e.text_key << " = " << node_text(*e.node) << "\n";
    }
    if (section == kOptimise) {  // the free parameters as given, in the default order, then the options
      std::vector<std::pair<std::size_t, std::string>> lines;
      for_each_key_entry(*sec, is_optimise_option, [&](const std::string& given, const std::string& text_key, const toml::node& node) {
        lines.emplace_back(key_rank(*free_parameter(given)), cat(text_key, " = ", node_text(node), "\n"));
      });
      std::stable_sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [rank, line] : lines) os << line;
    }
    for (std::string_view key : section == kOptimise ? optimise_option_keys() : keys_of(section)) {
      if (const toml::node* node = sec->get(key)) os << key << " = " << node_text(*node) << "\n";
    }
  }
  return os.str();
}

// ---------------------------------------------------------------------------------------
// The rules that combine keys: the scales derived from them are finite (derived_scale_error),
// and the forcing against the natural frequencies (frequency_ratio_error, parameters.hpp). Each
// moves one way with each key it reads, so over a [sweep] grid or an [optimise] box its
// extremes are at the corners: those are checked.
std::string combined_rule_error(const Parameters& p) {
  std::string err = derived_scale_error(p);
  return err.empty() ? frequency_ratio_error(p) : err;
}

// "file: --set forcing.omega=1e-9" when one of the rule's keys was overridden (a derived scale's
// refusal: the key it names, "[forcing] lambda = ..."), else "file".
std::string rule_origin(const Context& ctx, const std::string& error) {
  const bool derived = error.starts_with("[");  // a key's refusal; the ratio rule's names keys in its text
  for (const Key k : Key::all()) {
    const KeyInfo& i = k.info();
    const bool named = derived && error.starts_with(cat("[", i.section, "] ", i.name, " = "));
    if (named || (!derived && i.frequency_rule))
      if (const auto it = ctx.overrides.find(k.full_name()); it != ctx.overrides.end())
        return cat(ctx.path, ": ", clip(it->second, 200));
  }
  return ctx.path;
}

// "file: --param KEY" for a command's axis, "file: --set sweep.KEY=..." when one of the axes
// was set so, else "file: [sweep]".
std::string sweep_origin(const Context& ctx, const std::vector<Axis>& axes) {
  if (!ctx.axes.empty()) return cat(ctx.path, ": ", ctx.axes.front().option);
  for (const Axis& a : axes)
    for (const std::string& name : {a.key, a.name})
      if (const auto it = ctx.overrides.find(cat(kSweep, ".", name)); it != ctx.overrides.end())
        return cat(ctx.path, ": ", clip(it->second, 200));
  return cat(ctx.path, ": [", kSweep, "]");
}

// Per axis: the indices of its least and largest value (a categorical axis: its first only).
std::vector<std::array<std::size_t, 2>> axis_ends(const std::vector<Axis>& axes) {
  std::vector<std::array<std::size_t, 2>> ends;
  for (const Axis& a : axes) {
    if (!a.categories.empty()) {
      ends.push_back({0, 0});
      continue;
    }
    const auto [lo, hi] = std::minmax_element(a.values.begin(), a.values.end());
    ends.push_back({static_cast<std::size_t>(lo - a.values.begin()), static_cast<std::size_t>(hi - a.values.begin())});
  }
  return ends;
}

void check_grid_corners(const Scene& scene, const Context& ctx) {
  if (!scene.sweep || scene.sweep->axes.empty()) return;
  const std::vector<Axis>& axes = scene.sweep->axes;
  const Grid grid(axes);
  const CellMaker cells(scene, grid);
  const auto ends = axis_ends(axes);
  std::vector<std::size_t> index(axes.size());
  for (std::size_t corner = 0; corner < (std::size_t{1} << axes.size()); ++corner) {
    std::vector<std::string> at;
    for (std::size_t d = 0; d < axes.size(); ++d) {
      index[d] = ends[d][(corner >> d) & 1U];
      at.push_back(cat(axes[d].key, " = ", shortest(axes[d].values[index[d]])));
    }
    const std::string err = combined_rule_error(cells(grid.ravel(index)).params);
    if (!err.empty()) fail(cat(sweep_origin(ctx, axes), ": at the cell ", join(views(at), ", "), ": ", err));
  }
}

void check_optimise_corners(const Scene& scene, const Context& ctx) {
  if (!scene.optimise || scene.optimise->variables.empty()) return;
  const std::vector<FreeVariable>& vars = scene.optimise->variables;
  for (std::size_t corner = 0; corner < (std::size_t{1} << vars.size()); ++corner) {
    Parameters p = scene.params;
    std::vector<std::string> at;
    for (std::size_t d = 0; d < vars.size(); ++d) {
      const double v = ((corner >> d) & 1U) != 0 ? vars[d].max : vars[d].min;
      vars[d].key.set(p, v);
      at.push_back(cat(vars[d].name(), " = ", shortest(v)));
    }
    if (const std::string err = combined_rule_error(p); !err.empty())
      fail(cat(ctx.path, ": [", kOptimise, "] at the corner ", join(views(at), ", "), " of the box: ", err));
  }
}

Scene finish(Scene scene, const toml::table& table, const Context& ctx) {
  // The key table's checks cover validate() but for the rules that combine keys; this keeps the
  // two in step if the core adds one. A grid's base point need not obey those rules itself when
  // every cell does (an axis replaces the key that broke them).
  const auto errors = validate(scene.params);
  const bool rule_only = errors.size() == 1 && errors.front() == combined_rule_error(scene.params);
  if (rule_only && !scene.sweep) fail(cat(rule_origin(ctx, errors.front()), ": ", errors.front()));
  if (!errors.empty() && !rule_only) fail(ctx.path + ": " + errors.front());
  if (const std::string err = step_budget_error(scene.options.integrator); !err.empty())
    fail(cat(rule_origin(ctx, err), ": ", err));
  check_grid_corners(scene, ctx);
  check_optimise_corners(scene, ctx);
  scene.path = ctx.path;
  scene.text = scene_text(table, ctx);
  return scene;
}

struct FdCloser {
  int fd;
  ~FdCloser() { ::close(fd); }
};

// The one-line refusal of what is not a regular file of at most kMaxSceneBytes.
void check_scene_file(const std::string& path, const struct stat& st) {
  if (!S_ISREG(st.st_mode)) fail(cat(path, ": cannot read scene: it is ", file_kind(st.st_mode), ", not a regular file"));
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxSceneBytes)
    fail(cat(path, ": cannot read scene: ", std::to_string(st.st_size), " bytes, more than the ", kMaxSceneText,
             " a scene may have"));
}

// The scene's bytes, bounded (scene.hpp): the path must be a regular file of at most
// kMaxSceneBytes; it is opened without blocking (a FIFO with no writer would otherwise wait
// forever), and no more than kMaxSceneBytes + 1 bytes are ever read, so a file that grows
// while it is read is refused too.
std::string read_file(const std::string& path) {
  struct stat st {};
  // Looked at before it is opened, so a device is never opened; then again on the descriptor.
  if (::stat(path.c_str(), &st) == 0) check_scene_file(path, st);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) fail(path + ": cannot read scene: no such file");
    fail(cat(path, ": cannot read scene: ", std::strerror(err)));
  }
  const FdCloser closer{fd};
  if (::fstat(fd, &st) != 0) fail(cat(path, ": cannot read scene: ", std::strerror(errno)));
  check_scene_file(path, st);
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size) + 1);
  char buf[65536];
  while (text.size() <= kMaxSceneBytes) {
    const std::size_t want = std::min(sizeof buf, kMaxSceneBytes + 1 - text.size());
    const ssize_t got = ::read(fd, buf, want);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) continue;
      fail(cat(path, ": cannot read scene: ", std::strerror(errno)));
    }
    text.append(buf, static_cast<std::size_t>(got));
  }
  if (text.size() > kMaxSceneBytes)
    fail(cat(path, ": cannot read scene: it grew past the ", kMaxSceneText, " a scene may have while it was read"));
  return text;
}

}  // namespace
}  // namespace detail

Scene parse_scene(std::string_view text, const std::string& path, const std::vector<std::string>& overrides,
                  const std::vector<CommandAxis>& axes) {
  detail::Context ctx{path, {}, {}, axes};
  toml::table table = detail::parse_toml(text, path);
  for (const std::string& o : overrides) detail::apply_override(table, o, ctx);
  detail::replace_file_axes(table, ctx);
  detail::check_structure(table, ctx);
  return detail::finish(detail::read_values(table, ctx), table, ctx);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 const std::vector<CommandAxis>& axes) {
  return parse_scene(detail::read_file(path), path, overrides, axes);
}

}  // namespace vibromap
