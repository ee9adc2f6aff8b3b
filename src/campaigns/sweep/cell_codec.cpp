#include "cell_codec.hpp"

#include "vibromap/campaigns/census/attractor_codec.hpp"
#include "vibromap/parallel/wire.hpp"

namespace vibromap::detail {

// The member pointers of the floating-point fields, in wire order.
namespace {
constexpr double CellResult::*kReals[] = {&CellResult::wall_s, &CellResult::steady_residual, &CellResult::T_con,
                                           &CellResult::k_con,  &CellResult::F_max,           &CellResult::z_max,
                                           &CellResult::z_ratio, &CellResult::v_in,           &CellResult::impulse,
                                           &CellResult::max_multiplier, &CellResult::lyapunov,
                                           &CellResult::e_effective, &CellResult::energy_dissipated};
constexpr double CellResult::*kCensusReals[] = {&CellResult::soft_fraction, &CellResult::unresolved_fraction,
                                                 &CellResult::unlisted_fraction, &CellResult::budget_fraction};
}  // namespace

void CellCodec::encode(const CellResult& c, ByteWriter& out) const {
  out.put(c.status);
  out.put(c.regime);
  out.put(c.hertz_valid);
  out.put(c.stable);
  out.put(c.soft);
  out.put(c.n);
  out.put(c.k);
  out.put(c.periods);
  out.put(c.rhs_evals);
  out.put(c.clipped_impacts);
  for (const auto member : kReals) out.put(c.*member);
  // The census: one byte (0) in a sweep without one.
  out.put(static_cast<std::uint8_t>(census_ ? 1 : 0));
  if (!census_) return;
  for (const auto member : kCensusReals) out.put(c.*member);
  out.put(static_cast<std::uint32_t>(c.census.size()));
  for (const Attractor& a : c.census) AttractorCodec().encode(a, out);
}

CellResult CellCodec::decode(ByteReader& in) const {
  CellResult c;
  c.status = in.get<std::int8_t>();
  c.regime = in.get<std::int8_t>();
  c.hertz_valid = in.get<std::int8_t>();
  c.stable = in.get<std::int8_t>();
  c.soft = in.get<std::int8_t>();
  c.n = in.get<std::int32_t>();
  c.k = in.get<std::int32_t>();
  c.periods = in.get<std::int64_t>();
  c.rhs_evals = in.get<std::int64_t>();
  c.clipped_impacts = in.get<std::int64_t>();
  for (const auto member : kReals) c.*member = in.get<double>();
  if (in.get<std::uint8_t>() == 0) return c;
  for (const auto member : kCensusReals) c.*member = in.get<double>();
  const auto attractors = in.get<std::uint32_t>();
  if (attractors > kMaxCensusAttractors) throw WireError("a cell result lists more attractors than a census keeps");
  c.census.resize(attractors);
  for (Attractor& a : c.census) a = AttractorCodec().decode(in);
  return c;
}

}  // namespace vibromap::detail
