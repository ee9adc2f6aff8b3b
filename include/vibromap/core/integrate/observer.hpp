#pragma once
// What an integrator shows the outside: accepted steps with dense output, contact events,
// and the stroboscopic state at the end of each forcing period. Observers keep the
// integrator free of analysis and output (odeint's observer idea); a steady-state
// detector is an observer that asks to stop.

#include <initializer_list>
#include <vector>

#include "vibromap/core/model/system.hpp"

namespace vibromap {

// Continuous extension of one step: the state at any tau in the step's interval.
class DenseOutput {
 public:
  virtual ~DenseOutput() = default;
  virtual State eval(double tau) const = 0;
};

// One accepted step, or the part of it before an event: [tau0, tau1] within forcing
// period `period` (0-based), integrated in contact mode `mode`.
struct StepView {
  long period;
  double tau0;
  double tau1;
  ContactMode mode;
  const DenseOutput* dense;
  State eval(double tau) const { return dense->eval(tau); }
};

struct ContactEvent {
  enum class Kind { entry, exit };
  Kind kind;
  long period;  // forcing period (0-based) in which the event falls
  double tau;   // time since the start of that period, s
  State u;      // state at the event (z = 0 for dopri5)
};

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void on_step(const StepView& /*step*/) {}
  virtual void on_event(const ContactEvent& /*event*/) {}
  // State at the end of forcing period `period` (0-based, just completed).
  // Return true to ask the driver to stop after this period.
  virtual bool on_period_end(long /*period*/, const State& /*u*/) { return false; }
};

}  // namespace vibromap

namespace vibromap {

// Shows everything to several observers in order; asks to stop when any of them does.
class ObserverList final : public Observer {
 public:
  ObserverList(std::initializer_list<Observer*> list) : list_(list) {}
  void add(Observer* o) { list_.push_back(o); }
  void on_step(const StepView& step) override {
    for (Observer* o : list_) o->on_step(step);
  }
  void on_event(const ContactEvent& event) override {
    for (Observer* o : list_) o->on_event(event);
  }
  bool on_period_end(long period, const State& u) override {
    bool stop = false;
    for (Observer* o : list_) stop = o->on_period_end(period, u) || stop;
    return stop;
  }

 private:
  std::vector<Observer*> list_;
};

}  // namespace vibromap
