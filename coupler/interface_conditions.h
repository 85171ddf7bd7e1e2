// Interface conditions per face and per phase (paper section 7, eqs. 17-22; docs/methods.md §4.1).
// Pure function: no I/O, no state. Conventions: n is the face's outward normal of the solid (pointing into
// the fluid); v_s = velocity . n, sigma_s = n.sigma.n (tension positive), z_s = rho c of the solid (+inf: rigid);
// per phase k: v_f = u_k . n, p_f = p_k (sigma_f = -p_f), z_f = rho_k c_k. With w_s = z_s/(z_f+z_s), w_f = 1-w_s:
//   impedance      (eqs. 21-22):  v_I = w_f v_f + w_s v_s,                       p_I = w_s p_f + w_f p_s
//   characteristic (eqs. 17, 19): v_I = ... + (sigma_f - sigma_s)/(z_f+z_s),     p_I = ... - z_f w_s (v_f - v_s)
//   standard:                     v_I = v_s (fluid gets the wall velocity),     p_I = p_f (solid gets the fluid
//   pressure)
//   robin:                        v_I = v_s,                                    p_I = p_f - z_f (v_f - v_s)
//     and the solid gets face_impedance Z = sum_k alpha_k z_k / sum_k alpha_k with the face pressure: it applies
//     p_I + Z (v - v_s) at the normal velocity v its boundary reaches in its next step, implicitly (methods §4.4)
// with p_s = -sigma_s. The solid gets the volume average over phases (paper section 8, step 1):
//   face_pressure = sum_k alpha_k p_I,k / sum_k alpha_k, face_normal_velocity likewise.
// Unwetted faces (no fluid next to them): per phase v_I = v_s, p_I = p_s; face_pressure = 0 (no load).
#pragma once

#include "common/coupling/types.h"

namespace cosim::coupler {

// One face, one phase: returns {v_I, p_I}.
struct PointState {
  double velocity, pressure;
};
PointState interface_point(coupling::Mode mode, double v_s, double sigma_s, double z_s, double v_f, double p_f,
                           double z_f);

// All faces and phases. faces.count must equal samples.count (std::invalid_argument otherwise).
coupling::InterfaceStates interface_conditions(const coupling::Faces& faces, const coupling::FluidSamples& samples,
                                               coupling::Mode mode);

}  // namespace cosim::coupler
