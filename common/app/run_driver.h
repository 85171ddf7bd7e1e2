// The time loop both standalone solvers share: CFL steps up to each output time (the last step
// of an interval is split so no step is tiny), a snapshot at each output time, a progress line,
// and the mapping of failures to exit codes (common/app/errors.h: 2 bad input, 3 numerical, 4 I/O, 1 any other
// failure, 130 interrupted).
#pragma once

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/app/errors.h"
#include "common/util/progress.h"

namespace cosim::app {

// SIGINT/SIGTERM set a flag that drive() checks between steps.
void install_interrupt_handlers();
bool interrupted();

struct DriveOptions {
  std::vector<double> output_times;  // sorted, last = t_end
  double t_end = 0;
  long max_steps = 0;
  double dt_min = 0;         // a smaller stable step is a numerical failure; 0: 1e-6 of the first stable step
  double work_per_step = 1;  // cells or elements, for the rate on the progress line
  std::string rate_unit;     // e.g. "Mcell-updates/s"
  bool quiet = false;
  // A resumed run (checkpoint): outputs_done output times already have their snapshot and the initial snapshot is
  // not written again.
  bool resumed = false;
  std::size_t outputs_done = 0;
};

struct DriveResult {
  std::string status = "completed";  // completed | failed | interrupted
  std::string error;
  int code = 0;
  double wall = 0;
};

// "; <what limits the step>" when the simulation can say (a member limiting_step() returning text), else "".
template <class Sim>
std::string limiting_hint(const Sim& sim) {
  if constexpr (requires { sim.limiting_step(); }) {
    const std::string w = sim.limiting_step();
    return w.empty() ? "" : "; " + w;
  } else {
    return "";
  }
}

// Sim provides stable_dt(), advance(dt), time(), steps(); snapshot() writes one output; after_step(t_prev) runs
// after every step (a checkpoint when one is due), before the snapshot of an output time the step reached.
template <class Sim, class Snapshot, class AfterStep>
DriveResult drive(Sim& sim, const DriveOptions& o, Snapshot&& snapshot, AfterStep&& after_step) {
  DriveResult r;
  util::Progress progress(!o.quiet);
  double t_last = 0.0, rate = 0.0;
  long steps_last = sim.steps();
  double floor = -1;
  try {
    if (!o.resumed) as_io("writing a snapshot", snapshot);
    for (std::size_t i = o.outputs_done; i < o.output_times.size(); ++i) {
      const double t_out = o.output_times[i];
      while (sim.time() < t_out * (1.0 - 1e-14) && sim.steps() < o.max_steps) {
        if (interrupted()) throw std::runtime_error("interrupted");
        double dt = sim.stable_dt();
        // A stable step that collapses (a tangled element, a runaway state) would spin forever: below the floor
        // the run stops as a numerical failure, its last snapshot kept.
        if (floor < 0 && (o.dt_min > 0 || std::isfinite(dt))) floor = o.dt_min > 0 ? o.dt_min : 1e-6 * dt;
        if (floor > 0 && dt < floor)
          throw NumericalError(
              fmt::format("the stable time step collapsed to {:g} s at t = {:.9g} s (step {}), below "
                          "the floor {:g} s ({}){}",
                          dt, sim.time(), sim.steps(), floor,
                          o.dt_min > 0 ? "numerics.dt_min" : "1e-6 of the first step", limiting_hint(sim)));
        const double remaining = t_out - sim.time();
        if (dt >= remaining) dt = remaining;
        else if (dt > 0.5 * remaining) dt = 0.5 * remaining;  // avoid a tiny last step
        if (!(dt > 0.0) || !std::isfinite(dt) || dt < o.dt_min)
          throw NumericalError(
              fmt::format("time step collapsed to {:g} s at t = {:.9g} s (step {})", dt, sim.time(), sim.steps()));
        const double t_prev = sim.time();
        sim.advance(dt);
        after_step(t_prev);
        const double now = progress.elapsed();
        if (now - t_last > 1.0) {
          rate = static_cast<double>(sim.steps() - steps_last) * o.work_per_step / (now - t_last);
          t_last = now;
          steps_last = sim.steps();
        }
        progress.update(sim.steps(), sim.time(), o.t_end,
                        fmt::format("dt={:.3g}  {:.3g} {}", dt, rate * 1e-6, o.rate_unit));
      }
      as_io("writing a snapshot", snapshot);
      if (sim.steps() >= o.max_steps) {
        spdlog::warn("stopped at max_steps = {} (t = {:.6g})", o.max_steps, sim.time());
        break;
      }
    }
  } catch (const std::exception& e) {
    // A failure of none of the types of errors.h is not hidden as one of them: exit code 1, said so.
    const int code = exit_code_of(e);
    if (code == kExitUnforeseen && interrupted()) {
      r = {"interrupted", "", kExitInterrupted, 0};
      spdlog::warn("interrupted at t = {:.6g}; the last complete snapshot is kept", sim.time());
    } else {
      r = {"failed", code == kExitUnforeseen ? fmt::format("unforeseen failure: {}", e.what()) : e.what(), code, 0};
      spdlog::error("{}", r.error);
    }
  }
  progress.finish();
  r.wall = progress.elapsed();
  return r;
}

template <class Sim, class Snapshot>
DriveResult drive(Sim& sim, const DriveOptions& o, Snapshot&& snapshot) {
  return drive(sim, o, std::forward<Snapshot>(snapshot), [](double) {});
}

}  // namespace cosim::app
