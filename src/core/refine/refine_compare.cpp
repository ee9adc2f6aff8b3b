#include "vibromap/core/refine/refine_compare.hpp"

#include <cmath>
#include <stdexcept>

#include "vibromap/core/text.hpp"

namespace vibromap {

namespace {

struct FieldRow {
  RefineField field;
  std::string_view name;
  bool is_class;
};

constexpr FieldRow kFields[] = {
    {RefineField::regime, "regime", true},       {RefineField::n, "n", true},
    {RefineField::k, "k", true},                 {RefineField::soft, "soft", true},
    {RefineField::hertz_valid, "hertz_valid", true}, {RefineField::attractors, "attractors", true},
    {RefineField::k_con, "k_con", false},        {RefineField::T_con, "T_con", false},
    {RefineField::F_max, "F_max", false},        {RefineField::z_ratio, "z_ratio", false},
    {RefineField::soft_fraction, "soft_fraction", false},
};

const FieldRow& row(RefineField f) { return kFields[static_cast<std::size_t>(f)]; }

}  // namespace

const std::vector<RefineField>& all_refine_fields() {
  static const std::vector<RefineField> all = [] {
    std::vector<RefineField> v;
    for (const FieldRow& r : kFields) v.push_back(r.field);
    return v;
  }();
  return all;
}

std::string to_string(RefineField f) { return std::string(row(f).name); }

RefineField parse_refine_field(std::string_view s) {
  std::string allowed;
  for (const FieldRow& r : kFields) {
    if (r.name == s) return r.field;
    allowed += allowed.empty() ? std::string(r.name) : cat(", ", r.name);
  }
  throw std::invalid_argument(cat("unknown refinement quantity '", clip(s), "' (allowed: ", allowed, ")"));
}

bool refine_field_is_class(RefineField f) { return row(f).is_class; }

const std::vector<RefineOn>& default_refine_on() {
  static const std::vector<RefineOn> on = {
      {RefineField::regime, 0.0}, {RefineField::n, 0.0}, {RefineField::k, 0.0}, {RefineField::soft, 0.0}};
  return on;
}

std::string validate_refine_on(const RefineOn& on) {
  if (refine_field_is_class(on.field))
    return on.rel == 0.0 ? std::string() : cat(to_string(on.field), " is a class and takes no threshold");
  if (!(std::isfinite(on.rel) && on.rel >= 0.0))
    return cat("the relative threshold of ", to_string(on.field), " must be a finite number >= 0");
  return {};
}

double refine_value(const CellResult& c, RefineField f) {
  switch (f) {
    case RefineField::regime: return c.regime;
    case RefineField::n: return c.n;
    case RefineField::k: return c.k;
    case RefineField::soft: return c.soft;
    case RefineField::hertz_valid: return c.hertz_valid;
    case RefineField::attractors: return static_cast<double>(c.census.size());
    case RefineField::k_con: return c.k_con;
    case RefineField::T_con: return c.T_con;
    case RefineField::F_max: return c.F_max;
    case RefineField::z_ratio: return c.z_ratio;
    case RefineField::soft_fraction: return c.soft_fraction;
  }
  throw std::logic_error("refine_value: unknown field");
}

bool values_differ(double a, double b, bool is_class, double rel) {
  const bool na = std::isnan(a), nb = std::isnan(b);
  if (na || nb) return na != nb;
  if (a == b) return false;  // the same number, or the same infinity
  if (is_class || !std::isfinite(a) || !std::isfinite(b)) return true;
  return std::fabs(a - b) > rel * std::fmax(std::fabs(a), std::fabs(b));
}

bool cells_differ(const CellResult& a, const CellResult& b, const std::vector<RefineOn>& on) {
  if (a.fragile == 1 || b.fragile == 1) return true;
  for (const RefineOn& q : on)
    if (values_differ(refine_value(a, q.field), refine_value(b, q.field), refine_field_is_class(q.field), q.rel))
      return true;
  return false;
}

}  // namespace vibromap
