// Per-cell relaxation and exchange operators of the two-phase model, applied to the conservative
// state of one cell (numerics.md 2.5 and 6). All of them conserve mixture mass, momentum and energy.
#pragma once

#include <array>

#include "common/eos/stiffened_gas.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Conservative two-phase state of one cell (3 velocity slots; unused ones stay zero).
struct CellState2 {
  double alpha0;
  double m[2];
  double mom[2][3];
  double E[2];
};

// Instantaneous velocity relaxation to the mass-weighted mean velocity; the lost kinetic
// energy of each phase becomes its internal energy (numerics.md 2.5(a)).
void relax_velocity(CellState2& s, int dim);

// Instantaneous pressure relaxation with implicit interface pressure p_I = p (numerics.md 2.5(b)):
// each phase follows e_k - e_k0 = -p (v_k - v_k0); for stiffened gases sum_k m_k v_k(p) = 1 is a
// quadratic in p, solved in closed form and polished with one Newton step. Returns the pressure.
double relax_pressure(CellState2& s, const eos::StiffenedGas (&eos)[2], int dim);

// Drag over dt with the coefficient frozen at its start value: the slip decays exactly as
// exp(-dt beta (1/m_g + 1/m_p)). Phase 0 is the gas, phase 1 the particles. The particles' kinetic
// energy change is taken from the gas energy, so the dissipation heats the gas (numerics.md 6.5).
void apply_drag(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt);

// Heat exchange (Ranz-Marshall) over dt at frozen densities and coefficient: T_g - T_p decays
// exponentially; the heat leaves the gas and enters the particles.
void apply_heat_transfer(CellState2& s, const eos::StiffenedGas (&eos)[2], const Exchange& ex, int dim, double dt);

}  // namespace cosim::fluid
