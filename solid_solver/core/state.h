// Structure-of-arrays state of the Lagrangian solid. Nodal vectors are interleaved per node (dim values),
// element tensors per element (6 stress components, npe*dim corner forces).
#pragma once

#include "common/app/run_driver.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace cosim::solid {

// A numerical failure (inverted element, non-finite state, time step collapse): exit code 3.
class StateError : public app::NumericalError {
 public:
  using app::NumericalError::NumericalError;
};

// Node boundary-condition flags: bits 0..2 prescribe velocity component d; bit 3 marks external loads;
// bit 4 marks nodes of a rigid block (moved by the rigid-body update, core/rigid_body.h); bit 5 nodes under the
// fluid's Robin condition (Simulation::set_face_impedances).
enum : std::uint8_t { kBcLoaded = 8, kBcRigid = 16, kBcImpedance = 32 };

struct State {
  // nodes
  std::vector<double> x;     // position at t^n [m]
  std::vector<double> v;     // velocity at t^{n-1/2} [m/s]
  std::vector<double> vbar;  // (v^{n-1/2} + v^{n+1/2}) / 2 of the last nodal update [m/s]
  std::vector<double> mass;  // lumped nodal mass [kg]
  std::vector<double> fext;  // external (pressure) force [N]
  std::vector<std::uint8_t> bc_mask;
  std::vector<double> bc_value;  // prescribed velocity per component [m/s]
  std::vector<double> bc_ramp;   // ramp time of the prescribed velocity [s]
  // elements
  std::vector<double> emass;  // [kg]
  std::vector<double> vol;    // volume at t^n [m^3] (area x 1 m in 2D)
  std::vector<double> ie;     // internal energy [J] (not specific)
  std::vector<double> p, q;   // pressure, artificial viscosity [Pa]
  std::vector<double> c;      // sound speed used for the step (longitudinal with strength) [m/s]
  std::vector<double> s;      // deviatoric stress, 6 per element (xx, yy, zz, xy, yz, zx) [Pa]
  std::vector<double> eps_p;  // equivalent plastic strain [-]
  std::vector<double> w_p;    // plastic work done in the element since t = 0 [J]
  std::vector<double> fc;     // corner forces, npe*dim per element [N]
};

}  // namespace cosim::solid
