// Where a fluid time step spends its time: thread-seconds per pass over the grid, measured per row (a clock read
// costs tens of nanoseconds, a row of cells tens of microseconds), only when profiling is switched on.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>

namespace cosim::fluid {

enum class Pass : int {
  Primitives,      // conservative -> primitive, admissibility check, x ghosts
  WaveRate,        // the CFL wave-speed maximum
  Boundaries,      // ghost cells: domain boundary conditions, embedded-body ghost and side cells
  Reconstruction,  // MUSCL slopes and edge states (with the embedded wall-face mirrors)
  Fluxes,          // face fluxes of a face row (same-phase, cross contacts, intra-cell terms, particle stress)
  Apply,           // face fluxes into the residual of the two neighbouring cell rows, boundary inflow
  Update,          // the Runge-Kutta combination
  Relaxation,      // instantaneous velocity and pressure relaxation (two phases)
  Exchange,        // drag, heat transfer, granular energy (two phases)
  Count
};
constexpr int kPassCount = static_cast<int>(Pass::Count);
constexpr const char* kPassNames[kPassCount] = {"primitives", "wave rate", "boundaries", "reconstruction", "fluxes",
                                                "apply",      "update",    "relaxation", "exchange"};

struct PassTimes {
  std::array<double, kPassCount> seconds{};  // summed over threads
  double& operator[](Pass p) { return seconds[static_cast<std::size_t>(p)]; }
  double operator[](Pass p) const { return seconds[static_cast<std::size_t>(p)]; }
};

inline double pass_clock_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Adds the seconds of its scope to `acc` (nothing when acc is null: profiling off). A nested clock may name the
// enclosing pass as `outer`, which it debits, so that each second is counted in one pass only.
class PassClock {
 public:
  explicit PassClock(double* acc, double* outer = nullptr)
      : acc_(acc), outer_(outer), t0_(acc ? pass_clock_s() : 0.0) {}
  ~PassClock() {
    if (!acc_) return;
    const double dt = pass_clock_s() - t0_;
    *acc_ += dt;
    if (outer_) *outer_ -= dt;
  }
  PassClock(const PassClock&) = delete;
  PassClock& operator=(const PassClock&) = delete;

 private:
  double* acc_;
  double* outer_;
  double t0_;
};

}  // namespace cosim::fluid
