#include "start_codec.hpp"

#include <string>

namespace vibromap::detail {
namespace {

void put_evaluation(ByteWriter& w, const EvaluationRecord& e) {
  w.put(e.x);
  w.put(e.result.value);
  w.put(e.result.violation);
  w.put(static_cast<std::uint8_t>(e.result.feasible));
  w.put(static_cast<std::int32_t>(e.result.regime.kind));
  w.put(static_cast<std::int32_t>(e.result.regime.n));
  w.put(static_cast<std::int32_t>(e.result.regime.k));
  w.put(static_cast<std::int32_t>(e.result.stable));
  w.put(e.result.measures);
  w.put(std::string_view(e.result.message));
  w.put(e.wall_s);
}

EvaluationRecord get_evaluation(ByteReader& r) {
  EvaluationRecord e;
  e.x = r.get_doubles();
  e.result.value = r.get<double>();
  e.result.violation = r.get<double>();
  e.result.feasible = r.get<std::uint8_t>() != 0;
  e.result.regime.kind = static_cast<RegimeKind>(r.get<std::int32_t>());
  e.result.regime.n = r.get<std::int32_t>();
  e.result.regime.k = r.get<std::int32_t>();
  e.result.stable = r.get<std::int32_t>();
  e.result.measures = r.get_doubles();
  e.result.message = r.get_string();
  e.wall_s = r.get<double>();
  return e;
}

}  // namespace

void StartCodec::encode(const StartRecord& s, ByteWriter& w) const {
  const LocalResult& r = s.result;
  w.put(static_cast<std::int32_t>(s.spec.index));
  w.put(static_cast<std::int32_t>(s.rank));
  w.put(static_cast<std::uint64_t>(r.evaluations.size()));
  for (const EvaluationRecord& e : r.evaluations) put_evaluation(w, e);
  w.put(static_cast<std::int64_t>(r.best ? static_cast<std::int64_t>(*r.best) : -1));
  w.put(std::string_view(r.stop));
  w.put(static_cast<std::int32_t>(r.nlopt_code));
  w.put(static_cast<std::int64_t>(r.calls));
  w.put(static_cast<std::int64_t>(r.cache_hits));
  w.put(r.wall_s);
}

StartRecord StartCodec::decode(ByteReader& r) const {
  StartRecord s;
  const auto index = r.get<std::int32_t>();
  if (index < 0 || static_cast<std::size_t>(index) >= plan_.size()) throw WireError("a result for an unknown start");
  s.spec = plan_[static_cast<std::size_t>(index)];
  s.rank = r.get<std::int32_t>();
  const auto evaluations = r.get<std::uint64_t>();
  if (evaluations > r.remaining()) throw WireError("malformed start record");
  s.result.evaluations.resize(static_cast<std::size_t>(evaluations));
  for (EvaluationRecord& e : s.result.evaluations) e = get_evaluation(r);
  if (const auto best = r.get<std::int64_t>(); best >= 0) s.result.best = static_cast<std::size_t>(best);
  s.result.stop = r.get_string();
  s.result.nlopt_code = r.get<std::int32_t>();
  s.result.calls = static_cast<long>(r.get<std::int64_t>());
  s.result.cache_hits = static_cast<long>(r.get<std::int64_t>());
  s.result.wall_s = r.get<double>();
  return s;
}

}  // namespace vibromap::detail
