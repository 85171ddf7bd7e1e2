// Quasi-static reference for a piston between two gas chambers (docs/methods.md §8.2): each chamber uniform and
// isentropic, so the piston displacement x(t) (positive to the right) obeys
//   (m + m_extra) x'' = A [ pL0 (VL0 / (VL0 + A x))^gamma - pR0 (VR0 / (VR0 - A x))^gamma ],  x(0) = x'(0) = 0.
// m_extra = 0 is the ODE of docs/methods.md §8.2; m_extra = (mL_gas + mR_gas)/3 adds the kinetic energy of the gas
// with a linear velocity profile in each chamber (Rayleigh's effective mass of a spring), the first-order
// correction for gas inertia. Integrated with classical RK4; x(t) between steps by cubic Hermite interpolation.
// Shared by the solid solver's conforming-mesh piston test and the coupled piston scenes.
#pragma once

#include <vector>

namespace cosim::verification {

struct PistonOde {
  double area = 1.0;        // cross-section A [m^2]
  double mass = 1.0;        // piston mass m [kg]
  double extra_mass = 0.0;  // effective added mass of the gas [kg] (0: the plain quasi-static ODE)
  double p_left = 2.0;      // pL0 [Pa]
  double p_right = 1.0;     // pR0 [Pa]
  double v_left = 1.0;      // VL0 [m^3]
  double v_right = 2.0;     // VR0 [m^3]
  double gamma = 1.4;       // ratio of specific heats (1: isothermal chambers)
};

struct PistonEquilibrium {
  double v_left, v_right;  // VL*, VR* [m^3]: VL*/VR* = (KL/KR)^(1/gamma), VL* + VR* = VL0 + VR0
  double pressure;         // p* = KL / VL*^gamma [Pa]
  double x_eq;             // (VL* - VL0) / A [m]
  double omega;            // small-amplitude angular frequency, omega^2 = gamma A^2 p* (1/VL* + 1/VR*) / m [1/s]
};

PistonEquilibrium piston_equilibrium(const PistonOde& p);

// Acceleration x'' at displacement x [m/s^2].
double piston_acceleration(const PistonOde& p, double x);

struct PistonTrajectory {
  double dt = 0.0;
  std::vector<double> x, v;     // at t = i dt
  double x_at(double t) const;  // cubic Hermite between the RK4 samples [m]
  double x_min() const;         // turning points [m]
  double x_max() const;
  double period() const;  // mean time between successive maxima of x [s] (0 if fewer than two)
};

// RK4 from x = v = 0 to t_end with step dt.
PistonTrajectory integrate_piston(const PistonOde& p, double t_end, double dt);

}  // namespace cosim::verification
