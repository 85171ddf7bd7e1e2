// The fluid pressures the coupler hands on, extrapolated in time (coupling.predictor: linear).
// The solid applies a cycle's traction in its next step, from t^{n+1} = t^n + dt on, but the fluid sampled
// at t^n: a one-step lag that pumps energy into an oscillating structure (a delayed restoring force grows the
// amplitude by exp(w^2 dt t / 2)). The pressures are therefore extrapolated linearly to t^{n+1} from this and
// the previous cycle's samples (a second-order predictor, as in Farhat & Lesoinne's staggered schemes);
// unchanged where a face was not wetted both times or where the extrapolation would not be positive.
#pragma once

#include <vector>

#include "common/checkpoint/part_file.h"
#include "common/coupling/types.h"

namespace cosim::coupler {

class PressurePredictor {
 public:
  // with_velocity: the normal velocities too (mode robin, where the solid takes the characteristic
  // p - z_f u at t^{n+1}: a lagged u would act as an added mass z_f dt per area).
  explicit PressurePredictor(bool with_velocity = false) : with_velocity_(with_velocity) {}
  // s: the samples taken at time t; dt: the step that follows. Keeps the raw samples for the next call.
  void apply(coupling::FluidSamples& s, double t, double dt);
  // The samples it keeps, for checkpoints.
  void save(checkpoint::PartWriter& w) const;
  void restore(const checkpoint::PartReader& r);

 private:
  bool with_velocity_;
  std::vector<double> prev_pressure_, prev_velocity_;
  std::vector<char> prev_wetted_;
  double prev_time_ = 0;
  bool have_prev_ = false;
};

}  // namespace cosim::coupler
