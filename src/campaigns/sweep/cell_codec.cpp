#include "cell_codec.hpp"

#include <string_view>
#include <type_traits>

#include "vibromap/campaigns/census/attractor_codec.hpp"
#include "vibromap/parallel/wire.hpp"

namespace vibromap::detail {

// Wire order: the int8 flags status, regime, hertz_valid, stable, soft and fragile; n and k (int32); the
// integer quantities but hertz_valid (int64); wall_s and steady_residual; the float quantities
// (double); then one byte, 1 when the census follows. Quantities go in the table's order.
// hertz_valid, a flag every map keeps, rides as one byte with the other flags.
namespace {

// The fixed head of a cell, in wire order: visit(member) for each, for encode and decode alike.
template <class Cell, class Visit>
void visit_head(Cell& c, Visit&& visit) {
  visit(c.status);
  visit(c.regime);
  visit(c.hertz_valid);
  visit(c.stable);
  visit(c.soft);
  visit(c.fragile);
  visit(c.n);
  visit(c.k);
}

// An integer quantity carried as an int64 of its own (hertz_valid is in the head).
bool int64_on_wire(Quantity q) { return quantity_is_integer(q) && q != Quantity::hertz_valid; }

// The census's fractions and basin entropy (not map quantities: a census map keeps them as
// datasets of their own).
constexpr double CellResult::*kCensusReals[] = {&CellResult::soft_fraction, &CellResult::unresolved_fraction,
                                                 &CellResult::unlisted_fraction, &CellResult::budget_fraction,
                                                 &CellResult::basin_entropy};

// FNV-1a (32 bits) over each quantity's name and kind ("T_con real;...hertz_valid integer;..."),
// in the order given: what the wire layout of the quantities depends on.
std::uint32_t layout_fingerprint(std::span<const Quantity> quantities) {
  std::uint32_t h = 2166136261u;  // FNV-1a's offset basis; 16777619 its prime
  const auto mix = [&h](std::string_view text) {
    for (const char ch : text) h = (h ^ static_cast<unsigned char>(ch)) * 16777619u;
  };
  for (const Quantity q : quantities) {
    mix(to_string(q));
    mix(quantity_is_integer(q) ? " integer;" : " real;");
  }
  return h;
}

// The fingerprint of the 15 quantities the generations were set for: those give the generation
// itself. Generations 6 and 8: the bytes ranks exchanged before the codec followed the table;
// 10 and 13: the head with the fragile flag (13: the census with its basin entropy).
constexpr std::uint32_t kGenerationQuantities = 0x7e7b7156;

}  // namespace

std::uint32_t cell_layout_version(bool census, std::span<const Quantity> quantities) {
  return (census ? 13u : 10u) ^ layout_fingerprint(quantities) ^ kGenerationQuantities;
}

// Ranks built apart compare it (parallel/farm.hpp): the layout follows the table, so does this.
std::uint32_t CellCodec::version() const { return cell_layout_version(census_, all_quantities()); }

void CellCodec::encode(const CellResult& c, ByteWriter& out) const {
  visit_head(c, [&out](const auto& member) { out.put(member); });
  for (const Quantity q : all_quantities())
    if (int64_on_wire(q)) out.put(quantity_int(c, q));
  out.put(c.wall_s);
  out.put(c.steady_residual);
  for (const Quantity q : all_quantities())
    if (!quantity_is_integer(q)) out.put(c.value(q));
  // The census: one byte (0) in a sweep without one.
  out.put(static_cast<std::uint8_t>(census_ ? 1 : 0));
  if (!census_) return;
  for (const auto member : kCensusReals) out.put(c.*member);
  out.put(static_cast<std::uint32_t>(c.census.size()));
  for (const Attractor& a : c.census) AttractorCodec().encode(a, out);
}

CellResult CellCodec::decode(ByteReader& in) const {
  CellResult c;
  visit_head(c, [&in](auto& member) { member = in.get<std::remove_reference_t<decltype(member)>>(); });
  for (const Quantity q : all_quantities())
    if (int64_on_wire(q)) set_quantity_int(c, q, in.get<std::int64_t>());
  c.wall_s = in.get<double>();
  c.steady_residual = in.get<double>();
  for (const Quantity q : all_quantities())
    if (!quantity_is_integer(q)) set_quantity(c, q, in.get<double>());
  if (in.get<std::uint8_t>() == 0) return c;
  for (const auto member : kCensusReals) c.*member = in.get<double>();
  const auto attractors = in.get<std::uint32_t>();
  if (attractors > kMaxCensusAttractors) throw WireError("a cell result lists more attractors than a census keeps");
  c.census.resize(attractors);
  for (Attractor& a : c.census) a = AttractorCodec().decode(in);
  return c;
}

}  // namespace vibromap::detail
