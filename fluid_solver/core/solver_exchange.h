// Phase exchange: the instantaneous relaxations and the finite-rate drag and heat exchange.
#pragma once

#include "fluid_solver/core/solver.h"
#include "fluid_solver/physics/relax_row.h"

namespace cosim::fluid {

// The row's conservative arrays for the two-phase row kernels (physics/two_phase_row.h).
template <int DIM, int NP, FluxKind FK>
inline TwoPhaseRow<DIM> Solver<DIM, NP, FK>::two_phase_row(std::size_t base) {
  TwoPhaseRow<DIM> v;
  v.alpha = U_.var(Lay::alpha) + base;
  for (int k = 0; k < 2; ++k) {
    v.m[k] = U_.var(Lay::mass(k)) + base;
    for (int d = 0; d < DIM; ++d) v.mom[k][d] = U_.var(Lay::mom(k, d)) + base;
    v.E[k] = U_.var(Lay::energy(k)) + base;
  }
  if (gran_) v.heat = U_.var(Lay::heat) + base;
  return v;
}

// The instantaneous relaxations of a row of cells (physics/relax_row.h).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::relax_cells(std::size_t base, int len, bool vrelax, bool prelax) {
  if (gran_) relax_cells_as<true>(base, len, vrelax, prelax);
  else relax_cells_as<false>(base, len, vrelax, prelax);
}

template <int DIM, int NP, FluxKind FK>
template <bool GRAN>
inline void Solver<DIM, NP, FK>::relax_cells_as(std::size_t base, int len, bool vrelax, bool prelax) {
  const TwoPhaseRow<DIM> v = two_phase_row(base);
  const double amin = scene_.exchange.alpha_min;
  if (vrelax && prelax) relax_row<DIM, true, true, GRAN>(len, v, eos_[0], eos_[1], amin);
  else if (vrelax) relax_row<DIM, true, false, GRAN>(len, v, eos_[0], eos_[1], amin);
  else if (prelax) relax_row<DIM, false, true, GRAN>(len, v, eos_[0], eos_[1], amin);
  else relax_row<DIM, false, false, GRAN>(len, v, eos_[0], eos_[1], amin);  // clamps alpha
}

// Drag, heat exchange and, with a granular temperature, the loss of the particles' random motion to drag (its
// energy decays at twice the slip's rate of the particles alone) and to inelastic collisions (GranularGas); the
// granular energy lost becomes the material's heat (docs/methods.md §2.9, §6). Cell by cell, so the last
// Runge-Kutta stage applies it to each row it finishes (update_row), in cache.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::exchange_cells(Scratch& sc, std::size_t base, int len, double dt) {
  const auto& ex = scene_.exchange;
  const bool drag = ex.velocity == VelocityRelaxation::Drag;
  if constexpr (NP == 2) {
    if (!drag || ex.drag_law == DragLaw::AkhatovVainshtein) {  // the row kernel (physics/exchange_row.h)
      if (drag) exchange_row_as<true>(sc, base, len, dt);
      else exchange_row_as<false>(sc, base, len, dt);
    } else {
      for (int i = 0; i < len; ++i) {
        const std::size_t c = base + i;
        const double G = gran_ ? granular_energy(U_, c) : 0.0;
        CellState2 s = load_cell(c);
        s.E[NP - 1] -= G;  // drag and heat exchange see the material's energy
        const double beta = drag ? apply_drag(s, eos_, ex, DIM, dt) : 0.0;
        if (ex.heat_transfer) apply_heat_transfer(s, eos_, ex, DIM, dt);
        s.E[NP - 1] += G;
        store_cell(c, s);
        if (gran_) {
          const double m = s.m[NP - 1];
          const double k = ex.granular.after_collisions(1.0 - s.alpha0, G / m * std::exp(-2.0 * dt * beta / m), dt);
          U_.var(Lay::heat)[c] = s.E[NP - 1] - kinetic(U_, NP - 1, c) - m * k;
        }
      }
    }
    // Drag heats the gas and heat exchange moves energy: bring the pressures back to equilibrium
    // (vectorised row pass).
    if (ex.pressure_relaxation) {
      PassClock clk(pass_acc(Pass::Relaxation), pass_acc(Pass::Exchange));
      relax_cells(base, len, false, true);
    }
  }
}

template <int DIM, int NP, FluxKind FK>
template <bool DRAG>
inline void Solver<DIM, NP, FK>::exchange_row_as(Scratch& sc, std::size_t base, int len, double dt) {
  const bool heat = scene_.exchange.heat_transfer;
  const TwoPhaseRow<DIM> v = two_phase_row(base);
  if (gran_ && heat) exchange_row<DIM, DRAG, true, true>(len, v, eos_, scene_.exchange, dt, sc.exchange);
  else if (gran_) exchange_row<DIM, DRAG, false, true>(len, v, eos_, scene_.exchange, dt, sc.exchange);
  else if (heat) exchange_row<DIM, DRAG, true, false>(len, v, eos_, scene_.exchange, dt, sc.exchange);
  else exchange_row<DIM, DRAG, false, false>(len, v, eos_, scene_.exchange, dt, sc.exchange);
}

template <int DIM, int NP, FluxKind FK>
inline CellState2 Solver<DIM, NP, FK>::load_cell(std::size_t c) const {
  CellState2 s{};
  if constexpr (NP == 2) s.alpha0 = U_.var(Lay::alpha)[c];
  for (int k = 0; k < NP; ++k) {
    s.m[k] = U_.var(Lay::mass(k))[c];
    for (int d = 0; d < DIM; ++d) s.mom[k][d] = U_.var(Lay::mom(k, d))[c];
    s.E[k] = U_.var(Lay::energy(k))[c];
  }
  return s;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::store_cell(std::size_t c, const CellState2& s) {
  if constexpr (NP == 2) U_.var(Lay::alpha)[c] = s.alpha0;
  for (int k = 0; k < NP; ++k) {
    U_.var(Lay::mass(k))[c] = s.m[k];
    for (int d = 0; d < DIM; ++d) U_.var(Lay::mom(k, d))[c] = s.mom[k][d];
    U_.var(Lay::energy(k))[c] = s.E[k];
  }
}

}  // namespace cosim::fluid
