#pragma once
// Internal to the orbit-diagram campaign: one direction's steps as bytes (layout 1): the step
// count, then per step its status and its stroboscopic states (x1, x2, v1, v2).

#include <cstdint>
#include <vector>

#include "vibromap/core/analysis/continuation/orbit_diagram.hpp"
#include "vibromap/parallel/campaign.hpp"
#include "vibromap/parallel/wire.hpp"

namespace vibromap::detail {

using Steps = std::vector<DiagramStep>;

class StepsCodec : public ResultCodec<Steps> {
 public:
  std::uint32_t version() const override { return 1; }
  void encode(const Steps& steps, ByteWriter& out) const override {
    out.put(static_cast<std::uint64_t>(steps.size()));
    for (const DiagramStep& s : steps) {
      out.put(static_cast<std::int8_t>(s.status));
      out.put(static_cast<std::uint64_t>(s.strobe.size()));
      for (const Eigen::Vector4d& x : s.strobe)
        for (int c = 0; c < 4; ++c) out.put(x[c]);
    }
  }
  Steps decode(ByteReader& in) const override {
    Steps steps(in.get<std::uint64_t>());
    for (DiagramStep& s : steps) {
      s.status = static_cast<SolveStatus>(in.get<std::int8_t>());
      s.strobe.resize(in.get<std::uint64_t>());
      for (Eigen::Vector4d& x : s.strobe)
        for (int c = 0; c < 4; ++c) x[c] = in.get<double>();
    }
    return steps;
  }
};

}  // namespace vibromap::detail
