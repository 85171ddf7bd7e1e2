// The solver's state as others read and set it: the fields of a phase, cell samples, the totals and accounts, and
// the conserved cells of a checkpoint (fluid_state_entries.h).
#pragma once

#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

template <int DIM, int NP, FluxKind FK>
inline PhaseFields Solver<DIM, NP, FK>::phase_fields(int k) const {
  PhaseFields f;
  const std::size_t n = g_.interior_count();
  f.alpha.resize(n);
  f.rho.resize(n);
  f.velocity.assign(3 * n, 0.0);
  f.p.resize(n);
  f.T.resize(n);
  if (k == 1 && gran_) f.theta.resize(n);
  std::size_t o = 0;
  for (int kk = 0; kk < g_.n[2]; ++kk)
    for (int j = 0; j < g_.n[1]; ++j)
      for (int i = 0; i < g_.n[0]; ++i, ++o) {
        const std::size_t c = g_.index(i, j, kk);
        double a = 1.0;
        if constexpr (NP == 2) a = k == 0 ? U_.var(Lay::alpha)[c] : 1.0 - U_.var(Lay::alpha)[c];
        const double m = U_.var(Lay::mass(k))[c];
        const double av = a * fluid_volume(c);  // embedded.conservative: content over the fluid volume
        const double rho = m / av;
        for (int d = 0; d < DIM; ++d) f.velocity[3 * o + d] = U_.var(Lay::mom(k, d))[c] / m;
        const double rhoe = material_energy(U_, k, c) / av;
        f.alpha[o] = a;
        f.rho[o] = rho;
        f.p[o] = eos_[k].pressure(rho, rhoe / rho);
        f.T[o] = eos_[k].temperature(rho, f.p[o]);
        if (k == 1 && gran_) f.theta[o] = std::max(0.0, granular_per_mass(U_, c) * (2.0 / 3.0));
      }
  return f;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::cell_states(const std::size_t* cells, std::size_t count, CellSample* out) const {
  for (std::size_t n = 0; n < count; ++n) {
    const std::size_t c = cells[n];
    for (int k = 0; k < NP; ++k) {
      CellSample& o = out[n * NP + k];
      double a = 1.0;
      if constexpr (NP == 2) a = k == 0 ? U_.var(Lay::alpha)[c] : 1.0 - U_.var(Lay::alpha)[c];
      const double m = U_.var(Lay::mass(k))[c];
      o.velocity = {0, 0, 0};
      for (int d = 0; d < DIM; ++d) o.velocity[d] = U_.var(Lay::mom(k, d))[c] / m;
      o.alpha = a;
      const double av = a * fluid_volume(c);  // embedded.conservative: content over the fluid volume
      o.rho = m / av;
      const double rhoe = material_energy(U_, k, c) / av;
      o.p = eos_[k].pressure(o.rho, rhoe / o.rho);
      o.c = eos_[k].sound_speed(o.rho, o.p);
      if (k == 1 && gran_) o.granular = std::max(0.0, granular_per_mass(U_, c));
    }
  }
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<PhaseTotals> Solver<DIM, NP, FK>::boundary_inflow() const {
  std::vector<PhaseTotals> out(NP);
  for (int k = 0; k < NP; ++k) {
    out[k].mass = inflow_[fvar_flux(k, 0)];
    for (int d = 0; d < DIM; ++d) out[k].momentum[d] = inflow_[fvar_flux(k, 1 + d)];
    out[k].energy = inflow_[fvar_flux(k, 1 + DIM)];
  }
  return out;
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<EmbeddedMassAccount> Solver<DIM, NP, FK>::embedded_mass_account() const {
  std::vector<EmbeddedMassAccount> out(NP);
  for (int k = 0; k < NP; ++k) out[k] = {mass_by_walls_[k], mass_by_cells_[k]};
  return out;
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<PhaseTotals> Solver<DIM, NP, FK>::embedded_wall_exchange() const {
  std::vector<PhaseTotals> out(NP);
  for (int k = 0; k < NP; ++k) {
    out[k].mass = wall_[fvar_flux(k, 0)];
    for (int d = 0; d < DIM; ++d) out[k].momentum[d] = wall_[fvar_flux(k, 1 + d)];
    out[k].energy = wall_[fvar_flux(k, 1 + DIM)];
  }
  return out;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::save_state(checkpoint::PartWriter& w) const {
  write_fluid_state(w, {conserved_cells(), account_values(), t_, steps_, ncons_, {}, cells_held()}, 2 * NP,
                    wall_.size());
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::restore_state(const checkpoint::PartReader& r) {
  const FluidStateEntries e = read_fluid_state(r, ncons_, cells_held(), 0, inflow_.size(), 2 * NP, wall_.size());
  set_conserved_cells(e.conserved);
  restore_progress(e.time, e.steps, e.accounts);
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<double> Solver<DIM, NP, FK>::account_values() const {
  std::vector<double> out(inflow_.begin(), inflow_.end());
  out.insert(out.end(), mass_by_walls_.begin(), mass_by_walls_.end());
  out.insert(out.end(), mass_by_cells_.begin(), mass_by_cells_.end());
  out.insert(out.end(), wall_.begin(), wall_.end());
  return out;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::restore_progress(double time, long steps, const std::vector<double>& accounts) {
  // inflow, the embedded mass account and (absent in older checkpoints: zero) the wall exchange
  const std::size_t base = inflow_.size() + 2 * NP;
  if (accounts.size() != base && accounts.size() != base + wall_.size())
    throw std::invalid_argument(fmt::format("{} account values, {} expected", accounts.size(), base + wall_.size()));
  const auto at = [&](std::size_t i) { return accounts.begin() + static_cast<std::ptrdiff_t>(i); };
  std::copy(at(0), at(inflow_.size()), inflow_.begin());
  std::copy(at(inflow_.size()), at(inflow_.size() + NP), mass_by_walls_.begin());
  std::copy(at(inflow_.size() + NP), at(base), mass_by_cells_.begin());
  wall_.fill(0.0);
  if (accounts.size() > base) std::copy(at(base), accounts.end(), wall_.begin());
  t_ = time;
  steps_ = steps;
  primitives_valid_ = false;
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<double> Solver<DIM, NP, FK>::conserved_cells() const {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(ncons_) * g_.interior_count());
  for (int v = 0; v < ncons_; ++v)
    for (int k = 0; k < g_.n[2]; ++k)
      for (int j = 0; j < g_.n[1]; ++j) {
        const double* row = U_.var(v) + g_.index(0, j, k);
        out.insert(out.end(), row, row + g_.n[0]);
      }
  return out;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::set_conserved_cells(const std::vector<double>& values) {
  if (values.size() != static_cast<std::size_t>(ncons_) * g_.interior_count())
    throw std::invalid_argument(
        fmt::format("{} conserved values for {} variables of {} cells", values.size(), ncons_, g_.interior_count()));
  const double* in = values.data();
  for (int v = 0; v < ncons_; ++v)
    for (int k = 0; k < g_.n[2]; ++k)
      for (int j = 0; j < g_.n[1]; ++j, in += g_.n[0]) std::copy(in, in + g_.n[0], U_.var(v) + g_.index(0, j, k));
  U0_.data = U_.data;
  primitives_valid_ = false;
  restored_cells_ = true;
}

template <int DIM, int NP, FluxKind FK>
inline std::vector<PhaseTotals> Solver<DIM, NP, FK>::totals() const {
  std::vector<PhaseTotals> out(NP);
  const double vol = g_.cell_volume();
  for (int k = 0; k < NP; ++k) {
    for (int kk = 0; kk < g_.n[2]; ++kk)
      for (int j = 0; j < g_.n[1]; ++j)
        for (int i = 0; i < g_.n[0]; ++i) {
          const std::size_t c = g_.index(i, j, kk);
          if (emb_.active && !is_flow_cell(emb_.kind[c])) continue;  // the fluid domain only
          out[k].mass += U_.var(Lay::mass(k))[c];
          for (int d = 0; d < DIM; ++d) out[k].momentum[d] += U_.var(Lay::mom(k, d))[c];
          out[k].energy += U_.var(Lay::energy(k))[c];
        }
    out[k].mass *= vol;
    for (auto& m : out[k].momentum) m *= vol;
    out[k].energy *= vol;
  }
  return out;
}

}  // namespace cosim::fluid
