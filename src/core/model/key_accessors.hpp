#pragma once
// Private to src/core/model: the accessors of the key table (keys.cpp), which read and write one
// key's field of a point. A field is named by a chain of member pointers that starts at a member
// of Parameters or of PointOptions; a spring or damper given in either of its forms, a component
// of the initial state and an enum chosen by name have accessors of their own.

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap::detail {

using Setter = void (*)(Parameters&, PointOptions&, double);
using Getter = std::optional<double> (*)(const Parameters&, const PointOptions&);  // nullopt: not set in this form
using Deriver = double (*)(const Parameters&);  // the value at the point, whatever the form (Parameters keys)

struct Accessors {
  Setter set;
  Getter stored;
  Deriver value = nullptr;  // nullptr: a key of PointOptions (no derived value)
  long long int_max = 0;    // integer keys: the largest value the field's type holds
  int component = -1;       // [initial] keys: the index into Parameters::initial (x1, x2, v1, v2)
};

template <class T, class C>
C member_class(T C::*);

template <auto First>
constexpr bool kOfParameters = std::is_same_v<decltype(member_class(First)), Parameters>;

// The object a chain starts from: `params` for a member of Parameters, else `options`.
template <auto First, class P, class O>
auto& chain_root(P& params, O& options) {
  if constexpr (kOfParameters<First>) {
    return params;
  } else {
    return options;
  }
}

template <auto First, auto... Rest, class P, class O>
auto& member(P& params, O& options) {
  return ((chain_root<First>(params, options).*First).*....*Rest);
}

// A plain field (a double, an integer or a bool).
template <auto First, auto... Rest>
constexpr Accessors field() {
  using T = std::remove_cvref_t<decltype(member<First, Rest...>(std::declval<Parameters&>(),
                                                                 std::declval<PointOptions&>()))>;
  static_assert(std::is_arithmetic_v<T>);
  Accessors a{};
  a.set = [](Parameters& p, PointOptions& o, double v) { member<First, Rest...>(p, o) = static_cast<T>(v); };
  a.stored = [](const Parameters& p, const PointOptions& o) -> std::optional<double> {
    return static_cast<double>(member<First, Rest...>(p, o));
  };
  if constexpr (kOfParameters<First>) {
    a.value = [](const Parameters& p) {
      PointOptions unused;
      return static_cast<double>(member<First, Rest...>(p, unused));
    };
  }
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) a.int_max = std::numeric_limits<T>::max();
  return a;
}

// The value of a spring or damper member of Parameters in form `Form`, whatever form it is
// given in: k or omega = sqrt(k/m) of a spring, c or xi = c/(2 sqrt(m k)) of a damper.
template <auto Member, auto Form>
double pair_value(const Parameters& p) {
  using T = std::remove_cvref_t<decltype(p.*Member)>;
  constexpr bool is_spring = std::is_same_v<T, Spring>;
  bool first = false;  // body 1's spring or damper
  if constexpr (is_spring) {
    first = Member == &Parameters::spring1;
  } else {
    first = Member == &Parameters::damper1;
  }
  const double m = first ? p.m1 : p.m2;
  const double k = (first ? p.spring1 : p.spring2).stiffness(m);
  if constexpr (is_spring) {
    return Form == Spring::Form::stiffness ? k : std::sqrt(k / m);
  } else {
    const double c = (p.*Member).coefficient(m, k);
    return Form == Damper::Form::coefficient ? c : c / (2.0 * std::sqrt(m * k));
  }
}

// A Spring or Damper member of Parameters given in form `Form` (k or omega, c or xi).
template <auto Member, auto Form>
constexpr Accessors either_form() {
  using T = std::remove_cvref_t<decltype(std::declval<Parameters&>().*Member)>;
  Accessors a{};
  a.set = [](Parameters& p, PointOptions&, double v) { p.*Member = T{Form, v}; };
  a.stored = [](const Parameters& p, const PointOptions&) -> std::optional<double> {
    const T& f = p.*Member;
    if (f.form != Form) return std::nullopt;
    return f.value;
  };
  a.value = pair_value<Member, Form>;
  return a;
}

// Component I of the initial state; the first one set fills the others from the rest state
// (0, D, 0, 0).
template <int I>
constexpr Accessors initial_component() {
  Accessors a{};
  a.set = [](Parameters& p, PointOptions&, double v) {
    if (!p.initial) p.initial = p.initial_state();
    (*p.initial)[I] = v;
  };
  a.stored = [](const Parameters& p, const PointOptions&) -> std::optional<double> {
    if (!p.initial) return std::nullopt;
    return (*p.initial)[I];
  };
  a.value = [](const Parameters& p) { return p.initial_state()[I]; };
  a.component = I;
  return a;
}

// The names of Values (static storage: KeyInfo::choices holds views of them).
template <auto Values>
const std::vector<std::string>& enum_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto v : Values) n.push_back(to_string(v));
    return n;
  }();
  return names;
}

template <auto Values, class E>
std::optional<double> index_of(E e) {
  for (std::size_t i = 0; i < Values.size(); ++i)
    if (Values[i] == e) return static_cast<double>(i);
  return std::nullopt;
}

// An enum field chosen by name from Values (the value is the index into Values).
template <auto Values, auto First, auto... Rest>
Accessors enum_field() {
  Accessors a{};
  a.set = [](Parameters& p, PointOptions& o, double v) {
    member<First, Rest...>(p, o) = Values.at(static_cast<std::size_t>(v));
  };
  a.stored = [](const Parameters& p, const PointOptions& o) { return index_of<Values>(member<First, Rest...>(p, o)); };
  if constexpr (kOfParameters<First>) {
    a.value = [](const Parameters& p) {
      PointOptions unused;
      return index_of<Values>(member<First, Rest...>(p, unused)).value_or(-1.0);
    };
  }
  return a;
}

// The damping factor given directly (Parameters::damping; unset: calibrated from the restitution).
constexpr Accessors damping_field() {
  Accessors a{};
  a.set = [](Parameters& p, PointOptions&, double v) { p.damping = v; };
  a.stored = [](const Parameters& p, const PointOptions&) -> std::optional<double> { return p.damping; };
  a.value = [](const Parameters& p) { return p.damping_factor(); };
  return a;
}

}  // namespace vibromap::detail
