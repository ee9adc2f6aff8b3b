#include "vibromap/core/analysis/point/regime.hpp"

#include <array>
#include <charconv>
#include <stdexcept>
#include <utility>

namespace vibromap {

namespace {
constexpr std::array<std::pair<RegimeKind, std::string_view>, 9> kRegimeNames = {{
    {RegimeKind::periodic, "periodic"},
    {RegimeKind::chatter, "chatter"},
    {RegimeKind::no_contact, "no-contact"},
    {RegimeKind::permanent_contact, "permanent-contact"},
    {RegimeKind::quasi_periodic, "quasi-periodic"},
    {RegimeKind::chaotic, "chaotic"},
    {RegimeKind::non_periodic, "non-periodic"},
    {RegimeKind::unresolved, "unresolved"},
    {RegimeKind::failed, "failed"},
}};
}  // namespace

std::string to_string(RegimeKind k) {
  for (const auto& [kind, name] : kRegimeNames)
    if (kind == k) return std::string(name);
  return "unknown";
}

RegimeKind parse_regime_kind(std::string_view s) {
  for (const auto& [kind, name] : kRegimeNames)
    if (name == s) return kind;
  throw std::invalid_argument("unknown regime '" + std::string(s) + "'");
}

std::string Regime::label() const {
  if (kind != RegimeKind::periodic) return to_string(kind);
  std::string s = "(";
  s += std::to_string(n);
  s += ',';
  s += std::to_string(k);
  s += ')';
  return s;
}

Regime parse_regime(std::string_view s) {
  if (!s.empty() && s.front() == '(' && s.back() == ')') {
    const auto comma = s.find(',');
    Regime r{RegimeKind::periodic, 0, 0};
    const auto inner_n = s.substr(1, comma - 1);
    const auto inner_k = s.substr(comma + 1, s.size() - comma - 2);
    const auto rn = std::from_chars(inner_n.data(), inner_n.data() + inner_n.size(), r.n);
    const auto rk = std::from_chars(inner_k.data(), inner_k.data() + inner_k.size(), r.k);
    if (comma == std::string_view::npos || rn.ec != std::errc{} || rk.ec != std::errc{} ||
        rn.ptr != inner_n.data() + inner_n.size() || rk.ptr != inner_k.data() + inner_k.size() || r.n < 1 ||
        r.k < 0)
      throw std::invalid_argument("bad regime '" + std::string(s) + "': expected (n,k) with n >= 1, k >= 0");
    return r;
  }
  return Regime{parse_regime_kind(s), 0, 0};
}

bool is_soft(const Regime& regime, int stable, bool hertz_valid, double k_con, double soft_kcon) {
  return regime.kind == RegimeKind::periodic && regime.k > 0 && stable == 1 && hertz_valid && k_con > 0.0 &&
         k_con <= soft_kcon;
}

}  // namespace vibromap
