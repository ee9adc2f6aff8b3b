// The bytes of a followed state: see state_codec.hpp.

#include "vibromap/campaigns/census/state_codec.hpp"

namespace vibromap::detail {

void PixelCodec::encode(const PixelResult& r, ByteWriter& out) const {
  out.put(r.label);
  out.put(r.periods);
  out.put(static_cast<std::uint8_t>(r.early));
  out.put(static_cast<std::uint8_t>(r.budget));
  out.put(static_cast<std::uint8_t>(r.failed));
  for (int i = 0; i < 4; ++i) out.put(r.end_state[i]);
  if (r.label >= 0) AttractorCodec().encode(r.attractor, out);
}

PixelResult PixelCodec::decode(ByteReader& in) const {
  PixelResult r;
  r.label = in.get<std::int32_t>();
  r.periods = in.get<std::int64_t>();
  r.early = in.get<std::uint8_t>() != 0;
  r.budget = in.get<std::uint8_t>() != 0;
  r.failed = in.get<std::uint8_t>() != 0;
  for (int i = 0; i < 4; ++i) r.end_state[i] = in.get<double>();
  if (r.label >= 0) r.attractor = AttractorCodec().decode(in);
  return r;
}

}  // namespace vibromap::detail
