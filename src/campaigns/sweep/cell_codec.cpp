#include "cell_codec.hpp"

namespace vibromap::detail {

// The member pointers of CellResult's floating-point fields, in wire order.
namespace {
constexpr double CellResult::*kReals[] = {&CellResult::wall_s, &CellResult::steady_residual, &CellResult::T_con,
                                           &CellResult::k_con,  &CellResult::F_max,           &CellResult::z_max,
                                           &CellResult::z_ratio, &CellResult::v_in,           &CellResult::impulse,
                                           &CellResult::max_multiplier, &CellResult::lyapunov};
}  // namespace

void CellCodec::encode(const CellResult& c, ByteWriter& out) const {
  out.put(c.status);
  out.put(c.regime);
  out.put(c.hertz_valid);
  out.put(c.stable);
  out.put(c.n);
  out.put(c.k);
  out.put(c.periods);
  out.put(c.rhs_evals);
  for (const auto member : kReals) out.put(c.*member);
}

CellResult CellCodec::decode(ByteReader& in) const {
  CellResult c;
  c.status = in.get<std::int8_t>();
  c.regime = in.get<std::int8_t>();
  c.hertz_valid = in.get<std::int8_t>();
  c.stable = in.get<std::int8_t>();
  c.n = in.get<std::int32_t>();
  c.k = in.get<std::int32_t>();
  c.periods = in.get<std::int64_t>();
  c.rhs_evals = in.get<std::int64_t>();
  for (const auto member : kReals) c.*member = in.get<double>();
  return c;
}

}  // namespace vibromap::detail
