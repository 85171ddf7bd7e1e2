#include "coupler/pressure_predictor.h"

#include <utility>

namespace cosim::coupler {

void PressurePredictor::apply(coupling::FluidSamples& s, double t, double dt) {
  const std::vector<double> p_now = s.pressure;
  std::vector<double> u_now;
  if (with_velocity_) u_now = s.normal_velocity;
  const std::vector<char> wet_now = s.wetted;
  if (have_prev_ && t > prev_time_ && dt > 0 && prev_pressure_.size() == s.pressure.size() &&
      prev_wetted_.size() == s.wetted.size()) {
    const double r = dt / (t - prev_time_);
    for (int f = 0; f < s.count; ++f) {
      const bool wet = s.wetted.empty() || s.wetted[f], was_wet = prev_wetted_.empty() || prev_wetted_[f];
      if (!wet || !was_wet) continue;
      for (int k = 0; k < s.phases; ++k) {
        const std::size_t i = static_cast<std::size_t>(f) * s.phases + k;
        const double p = s.pressure[i] + r * (s.pressure[i] - prev_pressure_[i]);
        if (p > 0) s.pressure[i] = p;
        if (with_velocity_ && prev_velocity_.size() == s.normal_velocity.size())
          s.normal_velocity[i] += r * (s.normal_velocity[i] - prev_velocity_[i]);
      }
    }
  }
  if (!have_prev_ || t > prev_time_) {  // the first of several samples at one time (cycle 0 and 1) counts
    prev_pressure_ = p_now;
    prev_velocity_ = std::move(u_now);
    prev_wetted_ = wet_now;
    prev_time_ = t;
    have_prev_ = true;
  }
}

void PressurePredictor::save(checkpoint::PartWriter& w) const {
  w.put("predictor.pressure", prev_pressure_);
  w.put("predictor.velocity", prev_velocity_);
  w.put_flags("predictor.wetted", prev_wetted_);
  w.put_scalar("predictor.time", prev_time_);
  w.put_integer("predictor.have", have_prev_ ? 1 : 0);
}

void PressurePredictor::restore(const checkpoint::PartReader& r) {
  prev_pressure_ = r.doubles("predictor.pressure");
  prev_velocity_ = r.doubles("predictor.velocity");
  prev_wetted_ = r.flags("predictor.wetted");
  prev_time_ = r.scalar("predictor.time");
  have_prev_ = r.integer("predictor.have") != 0;
}

}  // namespace cosim::coupler
