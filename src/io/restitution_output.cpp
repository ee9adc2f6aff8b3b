// The effective restitution's output: see include/vibromap/io/restitution_output.hpp.

#include "vibromap/io/restitution_output.hpp"

#include <cmath>
#include <ostream>
#include <string>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"

namespace vibromap {

void write_restitution_table(std::ostream& out, const std::vector<RestitutionResult>& rows) {
  out << "law                  e      chi        e_effective  e_effective - e  clipped\n";
  for (const RestitutionResult& r : rows) {
    const double miss = std::abs(r.e_effective - r.e) < 5e-7 ? 0.0 : r.e_effective - r.e;  // no "-0.000000"
    std::string law = to_string(r.law);
    law.resize(20, ' ');
    out << law << " " << printf_number(r.e, "%-6.3g") << " " << printf_number(r.chi, "%-10.5g") << " " << printf_number(r.e_effective, "%-12.6f")
        << " " << printf_number(miss, "%+-16.6f") << " " << (r.clipped ? "yes" : "no") << "\n";
  }
  out << "(two free bodies, one impact integrated at rtol 1e-12; the result depends on the law and e only)\n";
}

void write_restitution_json(std::ostream& out, const std::vector<RestitutionResult>& rows) {
  JsonWriter w(out);
  w.begin_array();
  for (const RestitutionResult& r : rows)
    w.begin_object()
        .field("law", to_string(r.law))
        .field("e", r.e)
        .field("chi", r.chi)
        .field("e_effective", r.e_effective)
        .end_object();
  w.end_array();
  out << "\n";
}

}  // namespace vibromap
