// The bytes of a followed state: see state_codec.hpp.

#include "vibromap/campaigns/census/state_codec.hpp"

namespace vibromap::detail {
namespace {

constexpr std::size_t kMaxStrobe = 1 << 16;  // more stroboscopic states than any period a census keeps
constexpr double Attractor::*kReals[] = {&Attractor::T_con,  &Attractor::k_con, &Attractor::F_max,
                                         &Attractor::z_ratio, &Attractor::z_max, &Attractor::v_in,
                                         &Attractor::impulse, &Attractor::max_floquet};

}  // namespace

void PixelCodec::encode(const PixelResult& r, ByteWriter& out) const {
  out.put(r.label);
  out.put(r.periods);
  out.put(static_cast<std::uint8_t>(r.early));
  out.put(static_cast<std::uint8_t>(r.budget));
  out.put(static_cast<std::uint8_t>(r.failed));
  for (int i = 0; i < 4; ++i) out.put(r.end_state[i]);
  if (r.label < 0) return;
  const Attractor& a = r.attractor;
  out.put(static_cast<std::uint8_t>(a.periodic));
  out.put(static_cast<std::int32_t>(a.regime.kind));
  out.put(static_cast<std::int32_t>(a.regime.n));
  out.put(static_cast<std::int32_t>(a.regime.k));
  for (const auto member : kReals) out.put(a.*member);
  out.put(static_cast<std::uint8_t>(a.hertz_valid));
  out.put(static_cast<std::int32_t>(a.stable));
  out.put(static_cast<std::uint8_t>(a.soft));
  out.put(static_cast<std::uint8_t>(a.transient));
  out.put(static_cast<std::uint64_t>(a.strobe.size()));
  for (const Eigen::Vector4d& x : a.strobe)
    for (int i = 0; i < 4; ++i) out.put(x[i]);
}

PixelResult PixelCodec::decode(ByteReader& in) const {
  PixelResult r;
  r.label = in.get<std::int32_t>();
  r.periods = in.get<std::int64_t>();
  r.early = in.get<std::uint8_t>() != 0;
  r.budget = in.get<std::uint8_t>() != 0;
  r.failed = in.get<std::uint8_t>() != 0;
  for (int i = 0; i < 4; ++i) r.end_state[i] = in.get<double>();
  if (r.label < 0) return r;
  Attractor& a = r.attractor;
  a.periodic = in.get<std::uint8_t>() != 0;
  a.regime.kind = static_cast<RegimeKind>(in.get<std::int32_t>());
  a.regime.n = in.get<std::int32_t>();
  a.regime.k = in.get<std::int32_t>();
  for (const auto member : kReals) a.*member = in.get<double>();
  a.hertz_valid = in.get<std::uint8_t>() != 0;
  a.stable = in.get<std::int32_t>();
  a.soft = in.get<std::uint8_t>() != 0;
  a.transient = in.get<std::uint8_t>() != 0;
  const auto points = in.get<std::uint64_t>();
  if (points > kMaxStrobe) throw WireError("a pixel result with too many stroboscopic states");
  a.strobe.resize(static_cast<std::size_t>(points));
  for (Eigen::Vector4d& x : a.strobe)
    for (int i = 0; i < 4; ++i) x[i] = in.get<double>();
  return r;
}

}  // namespace vibromap::detail
