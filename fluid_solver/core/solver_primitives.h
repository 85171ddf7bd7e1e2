// Stage step 1: conservative -> primitive (admissibility, x ghosts), energy helpers, the wave-speed maximum.
#pragma once

#include <type_traits>

#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

// |alpha rho u|^2 / (2 alpha rho) of phase k in cell c.
template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::kinetic(const FieldArray& U, int k, std::size_t c) {
  double q = 0;
  for (int d = 0; d < DIM; ++d) q += U.var(Lay::mom(k, d))[c] * U.var(Lay::mom(k, d))[c];
  return 0.5 * q / U.var(Lay::mass(k))[c];
}

// alpha rho e of phase k in cell c: the total energy less the kinetic energy, and less the granular energy of a
// dispersed phase (its material energy is a variable of its own there).
template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::material_energy(const FieldArray& U, int k, std::size_t c) const {
  if constexpr (NP == 2)
    if (k == 1 && gran_) return U.var(Lay::heat)[c];
  return U.var(Lay::energy(k))[c] - kinetic(U, k, c);
}

// alpha rho k = alpha rho E - kinetic - alpha rho e of the dispersed phase (docs/methods.md §2.9), and k.
template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::granular_energy(const FieldArray& U, std::size_t c) const {
  return U.var(Lay::energy(NP - 1))[c] - kinetic(U, NP - 1, c) - U.var(Lay::heat)[c];
}

template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::granular_per_mass(const FieldArray& U, std::size_t c) const {
  return granular_energy(U, c) / U.var(Lay::mass(NP - 1))[c];
}

// Interior primitives of U, with the x ghosts of the rows; a state that fails the admissibility check throws
// StateError naming the first bad cell. A no-op when the last stage computed them row by row (update_row), but
// for the report of a bad state it found, made here, where the unfused pass would have made it.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::compute_primitives() {
  if (primitives_valid_) {
    if (primitives_bad_) report_bad_cell();
    return;
  }
  double bad = 0.0;
  for_each_row(
      Pass::Primitives, [&](std::size_t base, int len, double& acc) { acc = std::max(acc, primitives_row(base, len)); },
      bad);
  if (bad > 0.0) report_bad_cell();
  primitives_valid_ = true;
}

// Primitives of one interior row of U into W, and the row's x ghosts while it is in cache (stage fills the
// others); returns 1 when a cell of the row is inadmissible, else 0.
template <int DIM, int NP, FluxKind FK>
inline double Solver<DIM, NP, FK>::primitives_row(std::size_t base, int len) {
  // The row's views in locals: loop-invariant to the compiler, so that the loop vectorises.
  const double* uc[Lay::kCons];
  double* wp[Lay::kPrim];
  for (int v = 0; v < Lay::kCons; ++v) uc[v] = v < ncons_ ? U_.var(v) + base : nullptr;
  for (int v = 0; v < Lay::kPrim; ++v) wp[v] = v < nprim_ ? W_.var(v) + base : nullptr;
  double bad_row = 0.0;
  // GRAN as a compile-time constant: a run-time select of the material energy does not vectorise.
  // embedded.conservative: a cell's content over its fluid volume (vol: that volume / the cell's, §5.8).
  const double* vol = conservative_ && !vfrac_.empty() ? vfrac_.data() + base : nullptr;
  const auto row = [&](auto gran_tag, auto vol_tag) {
    constexpr bool gran = decltype(gran_tag)::value;
    constexpr bool by_volume = decltype(vol_tag)::value;
#pragma GCC ivdep
    for (int c = 0; c < len; ++c) {
      double a0 = 1.0;
      if constexpr (NP == 2) {
        a0 = uc[Lay::alpha][c];
        wp[Lay::palpha][c] = a0;
        bad_row = (a0 > 0.0 && a0 < 1.0) ? bad_row : 1.0;
      }
      for (int k = 0; k < NP; ++k) {
        double a = k == 0 ? a0 : 1.0 - a0;
        if constexpr (by_volume) a *= vol[c];
        const double m = uc[Lay::mass(k)][c];
        const double rho = m / a;
        const double inv = 1.0 / m;
        double q = 0;
        for (int d = 0; d < DIM; ++d) {
          const double u = uc[Lay::mom(k, d)][c] * inv;
          wp[Lay::vel(k, d)][c] = u;
          q += u * u;
        }
        double rhoe = uc[Lay::energy(k)][c] / a - 0.5 * rho * q;
        if constexpr (NP == 2)
          if (k == 1 && gran) {  // its material energy apart, and k from what is left (§2.9)
            const double h = uc[Lay::heat][c] / a;
            wp[Lay::pgran][c] = (rhoe - h) / rho;
            rhoe = h;
          }
        const auto& e = eos_[k];
        const double p = (e.gamma - 1.0) * (rhoe - rho * e.q) - e.gamma * e.pinf;
        const double c2 = e.gamma * (p + e.pinf) / rho;
        wp[Lay::rho(k)][c] = rho;
        wp[Lay::pres(k)][c] = p;
        bad_row = (rho > 0.0 && c2 > 0.0 && c2 < 1e300) ? bad_row : 1.0;  // also false for NaN
      }
    }
  };
  if (vol) {
    if (gran_) row(std::true_type{}, std::true_type{});
    else row(std::false_type{}, std::true_type{});
  } else if (gran_) {
    row(std::true_type{}, std::false_type{});
  } else {
    row(std::false_type{}, std::false_type{});
  }
  bc_.fill_x_row(W_, base);
  return bad_row;
}

template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::report_bad_cell() const {
  const FieldArray& U = U_;
  for (int kk = 0; kk < g_.n[2]; ++kk)
    for (int j = 0; j < g_.n[1]; ++j)
      for (int i = 0; i < g_.n[0]; ++i) {
        const std::size_t c = g_.index(i, j, kk);
        const double a0 = NP == 2 ? U.var(Lay::alpha)[c] : 1.0;
        std::string msg;
        bool bad = NP == 2 && !(a0 > 0.0 && a0 < 1.0);
        for (int k = 0; k < NP; ++k) {
          const double rho = W_.var(Lay::rho(k))[c], p = W_.var(Lay::pres(k))[c];
          const double c2 = eos_[k].sound_speed_sq(rho, p);
          if (!(rho > 0.0 && c2 > 0.0 && std::isfinite(c2))) bad = true;
          msg += fmt::format(" phase '{}': alpha={:.6g} rho={:.6g} p={:.6g} (p+pinf must be > 0, pinf={:.6g});",
                             scene_.phases[k].name, k == 0 ? a0 : 1.0 - a0, rho, p, eos_[k].pinf);
        }
        if (!bad) continue;
        std::string where = fmt::format("cell (i={}", g_.first[0] + i);  // global indices on a block
        if (DIM > 1) where += fmt::format(", j={}", g_.first[1] + j);
        if (DIM > 2) where += fmt::format(", k={}", g_.first[2] + kk);
        where += fmt::format(") at x=({:.6g}", g_.center(0, i));
        if (DIM > 1) where += fmt::format(", {:.6g}", g_.center(1, j));
        if (DIM > 2) where += fmt::format(", {:.6g}", g_.center(2, kk));
        throw StateError(fmt::format("inadmissible state in {}) at t={:.9g} (step {}):{}", where, t_, steps_ + 1, msg));
      }
  throw StateError(fmt::format("inadmissible state at t={:.9g} (step {})", t_, steps_ + 1));
}

// max over the flow cells and phases of sum_d (|u_d| + c) / dx_d. A trace phase is advected with the carrier's
// pressure: its sound speed does not limit the step; a dispersed phase's waves are its compaction waves and the
// sound of its granular gas (docs/methods.md §2.7-2.9; B: the collision stress's integer exponent, 0 any).
template <int DIM, int NP, FluxKind FK>
template <bool DISPERSED, bool GRAN, int B>
inline double Solver<DIM, NP, FK>::max_wave_rate() {
  double smax = 0.0;
  const ParticleStress& ps = scene_.exchange.particle_stress;
  const GranularGas& gr = scene_.exchange.granular;
  for_each_row(
      Pass::WaveRate,
      [&](std::size_t base, int len, double& acc) {
        const double* w[Lay::kPrim];  // the row's views in locals, so that the loop vectorises
        for (int v = 0; v < Lay::kPrim; ++v) w[v] = v < nprim_ ? W_.var(v) + base : nullptr;
        const std::uint8_t* kind = emb_.active ? emb_.kind.data() + base : nullptr;
        double dx[DIM], trace[NP];
        for (int d = 0; d < DIM; ++d) dx[d] = g_.dx[d];
        for (int k = 0; k < NP; ++k) trace[k] = trace_[k];
        const auto rate = [&](int c) {
          double r = 0.0;
          for (int k = 0; k < NP; ++k) {
            const double rho = w[Lay::rho(k)][c];
            double cs = std::sqrt(eos_[k].gamma * (w[Lay::pres(k)][c] + eos_[k].pinf) / rho);
            if constexpr (NP == 2) {
              const double ak = k == 0 ? w[Lay::palpha][c] : 1.0 - w[Lay::palpha][c];
              if (DISPERSED && k == 1) {
                cs = ps.wave_speed_as<B>(ak, rho);
                if constexpr (GRAN) {
                  double pg, cg;
                  gr.pressure_and_speed(ak, rho, w[Lay::pgran][c], pg, cg);
                  cs = std::max(cs, cg);
                }
              } else {
                cs = ak < trace[k] ? 0.0 : cs;
              }
            }
            double s = 0;
            for (int d = 0; d < DIM; ++d) s += (std::abs(w[Lay::vel(k, d)][c]) + cs) / dx[d];
            r = std::max(r, s);
          }
          return r;
        };
        // The rates into a scratch row (vectorised), then their max (a max reduction does not vectorise).
        double* r = scratch_[static_cast<std::size_t>(omp_get_thread_num())].exchange;
        if (kind) {  // the fluid domain only: ghost and solid states are not flow
#pragma GCC ivdep
          for (int c = 0; c < len; ++c) r[c] = is_flow_cell(kind[c]) ? 1.0 : 0.0;
#pragma GCC ivdep
          for (int c = 0; c < len; ++c) {
            const double rc = rate(c);  // evaluated everywhere (no branch), kept in flow cells
            r[c] = r[c] != 0.0 ? rc : 0.0;
          }
        } else {
#pragma GCC ivdep
          for (int c = 0; c < len; ++c) r[c] = rate(c);
        }
        double m = acc;
        for (int c = 0; c < len; ++c) m = std::max(m, r[c]);
        acc = m;
      },
      smax);
  return smax;
}

}  // namespace cosim::fluid
