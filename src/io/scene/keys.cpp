// The scene's view of the key table: see include/vibromap/io/scene/keys.hpp.

#include "vibromap/io/scene/keys.hpp"

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {

std::vector<std::string_view> scene_sections() {
  std::vector<std::string_view> sections = detail::point_sections();
  sections.push_back(detail::kSweep);
  return sections;
}

std::string parameter_override(Key k, double value) { return cat(k.full_name(), "=", float_text(value)); }

std::vector<std::string> optimised_overrides(const Parameters& p, const OptimiseOptions& o) {
  std::vector<std::string> out;
  for (const FreeVariable& f : o.variables) out.push_back(parameter_override(f.key, f.key.value(p)));
  if (!o.laws.empty()) out.push_back("contact.law=" + to_string(p.law));
  return out;
}

}  // namespace vibromap
