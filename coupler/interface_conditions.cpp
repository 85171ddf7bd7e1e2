#include "coupler/interface_conditions.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace cosim::coupler {

using coupling::Mode;

PointState interface_point(Mode mode, double v_s, double sigma_s, double z_s, double v_f, double p_f, double z_f) {
  const double p_s = -sigma_s;
  if (mode == Mode::Standard) return {v_s, p_f};
  // Robin: the wall moves with the solid, whose step has already met the fluid's characteristic; the wall
  // pressure is the fluid's along its incoming characteristic p - z_f v (eq. 19 with z_s -> inf).
  if (mode == Mode::Robin) return {v_s, p_f - z_f * (v_f - v_s)};
  // Weights written so that z_s = +inf gives w_s = 1, w_f = 0 exactly.
  const double w_s = 1.0 / (1.0 + z_f / z_s);
  const double w_f = 1.0 - w_s;
  double v = w_f * v_f + w_s * v_s;  // eq. 22
  double p = w_s * p_f + w_f * p_s;  // eq. 21
  if (mode == Mode::Characteristic) {
    const double sigma_f = -p_f;
    v += (sigma_f - sigma_s) / (z_f + z_s);  // last term of eq. 17 (0 for z_s = inf)
    p -= z_f * w_s * (v_f - v_s);            // last term of eq. 19: z_f z_s/(z_f+z_s) (v_f - v_s), sigma = -p
  }
  return {v, p};
}

coupling::InterfaceStates interface_conditions(const coupling::Faces& faces, const coupling::FluidSamples& s,
                                               Mode mode) {
  if (faces.count != s.count)
    throw std::invalid_argument(
        fmt::format("FluidSamples.count = {} but InterfaceFaces.count = {}", s.count, faces.count));
  const int n = faces.count, np = s.phases, d = faces.dim;
  coupling::InterfaceStates out;
  out.count = n;
  out.phases = np;
  out.mode = mode;
  out.pressure.resize(static_cast<std::size_t>(n) * np);
  out.normal_velocity.resize(out.pressure.size());
  out.face_pressure.assign(n, 0.0);
  out.face_normal_velocity.assign(n, 0.0);
  out.face_wetted.assign(n, 0);
  if (mode == Mode::Robin) out.face_impedance.assign(n, 0.0);
  for (int f = 0; f < n; ++f) {
    double v_s = 0.0;
    for (int c = 0; c < d; ++c) v_s += faces.velocity[f * d + c] * faces.normal[f * d + c];
    const double sigma_s = faces.normal_stress[f], z_s = faces.impedance[f];
    const bool wet = s.wetted.empty() || s.wetted[f];
    double sum_a = 0.0, sum_p = 0.0, sum_v = 0.0, sum_z = 0.0;
    for (int k = 0; k < np; ++k) {
      const std::size_t i = static_cast<std::size_t>(f) * np + k;
      const PointState st =
          wet ? interface_point(mode, v_s, sigma_s, z_s, s.normal_velocity[i], s.pressure[i], s.impedance[i])
              : PointState{v_s, -sigma_s};
      out.pressure[i] = st.pressure;
      out.normal_velocity[i] = st.velocity;
      sum_a += s.alpha[i];
      sum_p += s.alpha[i] * st.pressure;
      sum_v += s.alpha[i] * st.velocity;
      sum_z += s.alpha[i] * s.impedance[i];
    }
    if (wet && sum_a > 0.0) {
      out.face_wetted[f] = 1;
      out.face_pressure[f] = sum_p / sum_a;
      out.face_normal_velocity[f] = sum_v / sum_a;
      if (mode == Mode::Robin) out.face_impedance[f] = sum_z / sum_a;
    } else {
      out.face_normal_velocity[f] = v_s;
    }
  }
  return out;
}

}  // namespace cosim::coupler
