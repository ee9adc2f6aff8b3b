#pragma once
// What "differs" means for adaptive refinement (sweep.refine_on): the quantities two
// solved cells are compared in, and the comparison.
//
//   A class (regime, n, k, soft, hertz_valid, attractors: the census's attractor count) is
//   compared exactly: equal or not.
//   A continuous quantity (k_con, T_con, F_max, z_ratio, soft_fraction) differs when
//   |a - b| > rel max(|a|, |b|), rel >= 0 its relative threshold (rel = 0: any difference;
//   two zeros never differ).
//   Either kind: NaN against a number differs; two NaN are alike (both say "none"); an
//   infinity differs from everything but the same infinity.
// Two cells differ when any quantity of the list differs. The default list is regime, n, k
// and soft (the soft flag of regime.hpp's is_soft), as the issue asks. A fragile cell
// (analysis.fragility: a perturbation of its initial state ends elsewhere) differs from every
// cell: its answer changes under perturbation, so a block with a fragile corner is refined and
// no point inherits a fragile answer.

#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/quantities.hpp"

namespace vibromap {

enum class RefineField { regime, n, k, soft, hertz_valid, attractors, k_con, T_con, F_max, z_ratio, soft_fraction };

struct RefineOn {
  RefineField field = RefineField::regime;
  double rel = 0.0;  // relative threshold of a continuous field; 0 for a class
};

const std::vector<RefineField>& all_refine_fields();  // in enum order
std::string to_string(RefineField f);                 // "regime", "k_con", ...
// Throws std::invalid_argument naming the allowed names.
RefineField parse_refine_field(std::string_view s);
bool refine_field_is_class(RefineField f);
const std::vector<RefineOn>& default_refine_on();     // regime, n, k, soft
// Empty when usable, else what is wrong (a threshold on a class; a negative or non-finite one).
std::string validate_refine_on(const RefineOn& on);

// The field of a cell as a double (classes exactly; attractors = census.size()).
double refine_value(const CellResult& c, RefineField f);
// The comparison above for one quantity.
bool values_differ(double a, double b, bool is_class, double rel);
bool cells_differ(const CellResult& a, const CellResult& b, const std::vector<RefineOn>& on);

}  // namespace vibromap
