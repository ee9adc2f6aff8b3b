#pragma once
// Output of `vibromap restitution` (RestitutionResult, core/analysis/point/restitution.hpp): a
// table for people, or JSON for scripts: a list of {law, e, chi, e_effective}.

#include <iosfwd>
#include <vector>

#include "vibromap/core/analysis/point/restitution.hpp"

namespace vibromap {

void write_restitution_json(std::ostream& out, const std::vector<RestitutionResult>& rows);
// A row per (law, e): e, chi, the effective restitution, its miss and whether it was clipped.
void write_restitution_table(std::ostream& out, const std::vector<RestitutionResult>& rows);

}  // namespace vibromap
