// The bytes of an attractor: see attractor_codec.hpp.

#include "vibromap/campaigns/census/attractor_codec.hpp"

#include "vibromap/parallel/wire.hpp"

namespace vibromap::detail {
namespace {

constexpr std::uint64_t kMaxStrobe = 1 << 16;  // more stroboscopic states than any period a census keeps
constexpr double Attractor::*kReals[] = {
    &Attractor::T_con,       &Attractor::k_con,    &Attractor::F_max,           &Attractor::z_ratio,
    &Attractor::z_max,       &Attractor::v_in,     &Attractor::impulse,         &Attractor::max_floquet,
    &Attractor::fraction,    &Attractor::fraction_stderr, &Attractor::escape_rate};
constexpr bool Attractor::*kFlags[] = {&Attractor::hertz_valid, &Attractor::from_rest, &Attractor::soft,
                                       &Attractor::transient};

// A regime as kind, n, k (int32); `what` names the record in the refusal of an unknown kind.
Regime decode_regime(ByteReader& in, const char* what) {
  const auto kind = in.get<std::int32_t>();
  if (kind < 0 || kind > static_cast<std::int32_t>(RegimeKind::failed))
    throw WireError(std::string(what) + " unknown regime kind " + std::to_string(kind));
  Regime r;
  r.kind = static_cast<RegimeKind>(kind);
  r.n = in.get<std::int32_t>();
  r.k = in.get<std::int32_t>();
  return r;
}

void encode_shock(const CriticalShock& c, ByteWriter& out) {
  out.put(static_cast<std::int32_t>(c.status));
  for (const double v : {c.size, c.random_size, c.wall_s}) out.put(v);
  for (const Eigen::Vector4d* x : {&c.dx, &c.x_star})
    for (int i = 0; i < 4; ++i) out.put((*x)[i]);
  for (const int v : {c.strobe_index, c.to, static_cast<int>(c.to_regime.kind), c.to_regime.n, c.to_regime.k, c.unresolved})
    out.put(static_cast<std::int32_t>(v));
  out.put(static_cast<std::uint8_t>(c.verified));
  out.put(static_cast<std::int64_t>(c.follows));
}

CriticalShock decode_shock(ByteReader& in) {
  CriticalShock c;
  const auto status = in.get<std::int32_t>();
  if (status < 0 || status > static_cast<std::int32_t>(ShockStatus::failed))
    throw WireError("a shock of unknown status " + std::to_string(status));
  c.status = static_cast<ShockStatus>(status);
  for (double* v : {&c.size, &c.random_size, &c.wall_s}) *v = in.get<double>();
  for (Eigen::Vector4d* x : {&c.dx, &c.x_star})
    for (int i = 0; i < 4; ++i) (*x)[i] = in.get<double>();
  c.strobe_index = in.get<std::int32_t>();
  c.to = in.get<std::int32_t>();
  c.to_regime = decode_regime(in, "a shock leading to");
  c.unresolved = in.get<std::int32_t>();
  c.verified = in.get<std::uint8_t>() != 0;
  c.follows = static_cast<long>(in.get<std::int64_t>());
  return c;
}

}  // namespace

void AttractorCodec::encode(const Attractor& a, ByteWriter& out) const {
  out.put(static_cast<std::uint8_t>(a.periodic));
  out.put(static_cast<std::int32_t>(a.regime.kind));
  out.put(static_cast<std::int32_t>(a.regime.n));
  out.put(static_cast<std::int32_t>(a.regime.k));
  for (const auto member : kReals) out.put(a.*member);
  for (const auto member : kFlags) out.put(static_cast<std::uint8_t>(a.*member));
  out.put(static_cast<std::int32_t>(a.stable));
  out.put(static_cast<std::int32_t>(a.count));
  out.put(static_cast<std::int64_t>(a.escape_exposure));
  out.put(static_cast<std::int32_t>(a.escapes));
  out.put(static_cast<std::uint64_t>(a.strobe.size()));
  for (const Eigen::Vector4d& x : a.strobe)
    for (int i = 0; i < 4; ++i) out.put(x[i]);
  encode_shock(a.shock, out);
}

Attractor AttractorCodec::decode(ByteReader& in) const {
  Attractor a;
  a.periodic = in.get<std::uint8_t>() != 0;
  a.regime = decode_regime(in, "an attractor of");
  for (const auto member : kReals) a.*member = in.get<double>();
  for (const auto member : kFlags) a.*member = in.get<std::uint8_t>() != 0;
  a.stable = in.get<std::int32_t>();
  a.count = in.get<std::int32_t>();
  a.escape_exposure = static_cast<long>(in.get<std::int64_t>());
  a.escapes = in.get<std::int32_t>();
  const auto points = in.get<std::uint64_t>();
  if (points > kMaxStrobe) throw WireError("an attractor with too many stroboscopic states");
  a.strobe.resize(static_cast<std::size_t>(points));
  for (Eigen::Vector4d& x : a.strobe)
    for (int i = 0; i < 4; ++i) x[i] = in.get<double>();
  a.shock = decode_shock(in);
  return a;
}

}  // namespace vibromap::detail
