// The finite-volume DEM solver, templated on dimension, phase count and same-phase flux.
// One time step (SSP-RK2 or RK3), per stage:
//   1. primitives of the interior cells, with the admissibility check;
//   2. ghost cells from the boundary conditions (on primitives), and, with an embedded boundary,
//      ghost/solid-cut cells from image points (paper step 3);
//   3. residual: for each direction, face rows of MUSCL-reconstructed states (with mirrored
//      solid-side states at embedded wall faces, steps 5-6) -> DEM face contributions -> applied
//      to the two neighbouring cell rows;
//   4. Runge-Kutta combination of the flow cells, then instantaneous relaxation (two phases).
// Finite-rate exchange (drag, heat) is applied once per step after the hyperbolic step.
#pragma once

#include <omp.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "common/app/threads.h"
#include "fluid_solver/core/boundary.h"
#include "fluid_solver/core/dem_face.h"
#include "fluid_solver/core/ghost_fill.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/initial_state.h"
#include "fluid_solver/core/layout.h"
#include "fluid_solver/core/reconstruction.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/flux/aufs_row.h"
#include "fluid_solver/flux/cross_row.h"
#include "fluid_solver/physics/exchange_row.h"
#include "fluid_solver/physics/particle_stress_row.h"
#include "fluid_solver/physics/relax_row.h"
#include "fluid_solver/physics/relaxation.h"

namespace cosim::fluid {

enum class ReconMode { First, Minmod, VanLeer, MC };

template <int DIM, int NP, FluxKind FK>
class Solver final : public FluidSimulation {
  using Lay = Layout<DIM, NP>;
  static constexpr int kFaceVars = NP * (2 + DIM) + (NP > 1 ? 7 : 0);

 public:
  explicit Solver(const FluidScene& scene)
      : scene_(scene),
        g_(scene.cells, scene.lower, scene.upper),
        gran_(NP == 2 && scene.exchange.dispersed && scene.exchange.granular.enabled),
        ncons_(Lay::cons_vars(gran_)),
        nprim_(Lay::prim_vars(gran_)) {
    for (int k = 0; k < NP; ++k) eos_[k] = scene.phases[k].eos;
    U_.resize(ncons_, g_.total);
    U0_.resize(ncons_, g_.total);
    R_.resize(ncons_, g_.total);
    W_.resize(nprim_, g_.total);
    // The scene's (or --threads) count, else one thread per 16 rows of cells along x (1D: one row, one thread).
    omp_set_num_threads(scene.threads > 0 ? scene.threads : app::threads_for(static_cast<long>(g_.n[1]) * g_.n[2], 16));
    allocate_scratch();
    if (scene.reconstruction == Reconstruction::FirstOrder) mode_ = ReconMode::First;
    else if (scene.limiter == Limiter::Minmod) mode_ = ReconMode::Minmod;
    else if (scene.limiter == Limiter::VanLeer) mode_ = ReconMode::VanLeer;
    else mode_ = ReconMode::MC;
    bc_ = BoundaryFiller<DIM, NP>(scene, g_, eos_);
    if (NP == 2 && scene.exchange.pressure_relaxation) trace_.fill(scene.exchange.trace_alpha);
    if (NP == 2 && scene.exchange.dispersed) trace_[NP - 1] = 2.0;  // a trace everywhere (§2.8)
    set_initial_state<DIM, NP>(scene, g_, eos_, U_);
    if constexpr (NP == 2)
      if (gran_)  // at rest relative to its mean motion: all of E - u^2/2 is the material's
        for (std::size_t c = 0; c < g_.total; ++c) U_.var(Lay::heat)[c] = U_.var(Lay::energy(1))[c] - kinetic(U_, 1, c);
  }

  const FluidScene& scene() const override { return scene_; }
  double time() const override { return t_; }
  long steps() const override { return steps_; }
  std::size_t interior_cells() const override { return g_.interior_count(); }
  std::size_t state_bytes() const override {
    std::size_t b = (U_.data.size() + U0_.data.size() + R_.data.size() + W_.data.size()) * sizeof(double);
    for (const auto& sc : scratch_) b += sc.data.size() * sizeof(double);
    return b;
  }

  void set_embedded(EmbeddedState state, bool second_order) override {
    emb_ = std::move(state);
    wall_second_order_ = second_order;
    for (auto& faces : emb_.faces)  // sorted by the face's high cell, to find a face row's faces
      std::sort(faces.begin(), faces.end(),
                [](const WallFace& a, const WallFace& b) { return high_cell(a) < high_cell(b); });
    for (auto& bf : emb_.blocked)
      std::sort(bf.begin(), bf.end(),
                [](const BlockedFace& a, const BlockedFace& b) { return a.high.fluid_cell < b.high.fluid_cell; });
    for (auto& sg : emb_.side_ghosts)  // by flow cell, low side first (thin-body edges, fix_side_edges)
      std::sort(sg.begin(), sg.end(), [](const SideGhost& a, const SideGhost& b) {
        return a.flow_cell != b.flow_cell ? a.flow_cell < b.flow_cell : a.across_high < b.across_high;
      });
    if (emb_.active && emb_.kind.size() != g_.total)
      throw std::invalid_argument("embedded state: kind array does not match the grid");
  }
  const EmbeddedState& embedded() const override { return emb_; }
  std::vector<double> embedded_categories() const override {
    std::vector<double> out;
    out.reserve(g_.interior_count());
    for (int k = 0; k < g_.n[2]; ++k)
      for (int j = 0; j < g_.n[1]; ++j)
        for (int i = 0; i < g_.n[0]; ++i) out.push_back(emb_.active ? emb_.kind[g_.index(i, j, k)] : 0.0);
    return out;
  }

  double stable_dt() override {
    compute_primitives(U_);
    double smax = 0.0;
    const bool dispersed = NP == 2 && scene_.exchange.dispersed, b3 = scene_.exchange.particle_stress.beta == 3.0;
    if (!dispersed) smax = max_wave_rate<false, false, 0>();
    else if (gran_) smax = b3 ? max_wave_rate<true, true, 3>() : max_wave_rate<true, true, 0>();
    else smax = b3 ? max_wave_rate<true, false, 3>() : max_wave_rate<true, false, 0>();
    if (emb_.active) {  // a moving body must not cross more than a CFL fraction of a cell per step
      double w = 0;
      for (int d = 0; d < DIM; ++d) w += emb_.max_wall_speed / g_.dx[d];
      smax = std::max(smax, w);
    }
    return scene_.cfl / smax;
  }

  // max over the flow cells and phases of sum_d (|u_d| + c) / dx_d. A trace phase is advected with the carrier's
  // pressure: its sound speed does not limit the step; a dispersed phase's waves are its compaction waves and the
  // sound of its granular gas (docs/methods.md §2.7-2.9; B: the collision stress's integer exponent, 0 any).
  template <bool DISPERSED, bool GRAN, int B>
  double max_wave_rate() {
    double smax = 0.0;
    const ParticleStress& ps = scene_.exchange.particle_stress;
    const GranularGas& gr = scene_.exchange.granular;
    for_each_row(
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

  void advance(double dt) override {
    step_inflow_.fill(0.0);  // the first stage (a = 0) keeps U in U0 as it updates it
    if (scene_.integrator == TimeIntegrator::RK2) {
      stage(dt, 0.0, 1.0);
      stage(dt, 0.5, 0.5);
    } else {
      stage(dt, 0.0, 1.0);
      stage(dt, 0.75, 0.25);
      stage(dt, 1.0 / 3.0, 2.0 / 3.0);
    }
    if constexpr (NP == 2) exchange_sources(dt);
    if (emb_.active) store_ghost_states();
    for (std::size_t i = 0; i < inflow_.size(); ++i) inflow_[i] += step_inflow_[i];
    t_ += dt;
    ++steps_;
    primitives_valid_ = false;
  }

  PhaseFields phase_fields(int k) const override {
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
          const double rho = m / a;
          double q = 0;
          for (int d = 0; d < DIM; ++d) {
            f.velocity[3 * o + d] = U_.var(Lay::mom(k, d))[c] / m;
            q += f.velocity[3 * o + d] * f.velocity[3 * o + d];
          }
          const double rhoe = material_energy(U_, k, c) / a;
          f.alpha[o] = a;
          f.rho[o] = rho;
          f.p[o] = eos_[k].pressure(rho, rhoe / rho);
          f.T[o] = eos_[k].temperature(rho, f.p[o]);
          if (k == 1 && gran_) f.theta[o] = std::max(0.0, granular_per_mass(U_, c) * (2.0 / 3.0));
        }
    return f;
  }

  void cell_states(const std::size_t* cells, std::size_t count, CellSample* out) const override {
    for (std::size_t n = 0; n < count; ++n) {
      const std::size_t c = cells[n];
      for (int k = 0; k < NP; ++k) {
        CellSample& o = out[n * NP + k];
        double a = 1.0;
        if constexpr (NP == 2) a = k == 0 ? U_.var(Lay::alpha)[c] : 1.0 - U_.var(Lay::alpha)[c];
        const double m = U_.var(Lay::mass(k))[c];
        double q = 0;
        o.velocity = {0, 0, 0};
        for (int d = 0; d < DIM; ++d) {
          o.velocity[d] = U_.var(Lay::mom(k, d))[c] / m;
          q += o.velocity[d] * o.velocity[d];
        }
        o.alpha = a;
        o.rho = m / a;
        const double rhoe = material_energy(U_, k, c) / a;
        o.p = eos_[k].pressure(o.rho, rhoe / o.rho);
        o.c = eos_[k].sound_speed(o.rho, o.p);
        if (k == 1 && gran_) o.granular = std::max(0.0, granular_per_mass(U_, c));
      }
    }
  }

  std::vector<PhaseTotals> boundary_inflow() const override {
    std::vector<PhaseTotals> out(NP);
    for (int k = 0; k < NP; ++k) {
      out[k].mass = inflow_[fvar_flux(k, 0)];
      for (int d = 0; d < DIM; ++d) out[k].momentum[d] = inflow_[fvar_flux(k, 1 + d)];
      out[k].energy = inflow_[fvar_flux(k, 1 + DIM)];
    }
    return out;
  }

  void save_state(checkpoint::PartWriter& w) const override {
    w.put("fluid.conserved", U_.data);  // every padded cell as stored: a restart continues bit for bit
    w.put("fluid.boundary_inflow", std::span<const double>(inflow_.data(), inflow_.size()));
    w.put_scalar("fluid.time", t_);
    w.put_integer("fluid.steps", steps_);
    w.put_integer("fluid.conserved_vars", ncons_);
  }

  void restore_state(const checkpoint::PartReader& r) override {
    if (r.integer("fluid.conserved_vars") != ncons_)
      throw std::runtime_error(fmt::format("{}: {} conserved variables per cell, this scene has {}", r.path().string(),
                                           r.integer("fluid.conserved_vars"), ncons_));
    U_.data = r.doubles("fluid.conserved", U_.data.size());
    const std::vector<double> in = r.doubles("fluid.boundary_inflow", inflow_.size());
    std::copy(in.begin(), in.end(), inflow_.begin());
    t_ = r.scalar("fluid.time");
    steps_ = r.integer("fluid.steps");
    primitives_valid_ = false;
  }

  std::vector<PhaseTotals> totals() const override {
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

 private:
  // Calls f(base, len, acc) for every interior x-row in parallel; acc is max-reduced into result.
  template <class F>
  void for_each_row(F&& f, double& result) {
    const int rows = g_.n[1] * g_.n[2];
    double r = result;
#pragma omp parallel for schedule(static) reduction(max : r)
    for (int row = 0; row < rows; ++row) {
      const int j = row % g_.n[1], k = row / g_.n[1];
      f(g_.index(0, j, k), g_.n[0], r);
    }
    result = r;
  }

  // |alpha rho u|^2 / (2 alpha rho) of phase k in cell c.
  static double kinetic(const FieldArray& U, int k, std::size_t c) {
    double q = 0;
    for (int d = 0; d < DIM; ++d) q += U.var(Lay::mom(k, d))[c] * U.var(Lay::mom(k, d))[c];
    return 0.5 * q / U.var(Lay::mass(k))[c];
  }
  // alpha rho e of phase k in cell c: the total energy less the kinetic energy, and less the granular energy of a
  // dispersed phase (its material energy is a variable of its own there).
  double material_energy(const FieldArray& U, int k, std::size_t c) const {
    if constexpr (NP == 2)
      if (k == 1 && gran_) return U.var(Lay::heat)[c];
    return U.var(Lay::energy(k))[c] - kinetic(U, k, c);
  }
  // alpha rho k = alpha rho E - kinetic - alpha rho e of the dispersed phase (docs/methods.md §2.9), and k.
  double granular_energy(const FieldArray& U, std::size_t c) const {
    return U.var(Lay::energy(NP - 1))[c] - kinetic(U, NP - 1, c) - U.var(Lay::heat)[c];
  }
  double granular_per_mass(const FieldArray& U, std::size_t c) const {
    return granular_energy(U, c) / U.var(Lay::mass(NP - 1))[c];
  }

  // Interior primitives from conservative U, and the x ghosts of the rows; throws StateError naming the first bad
  // cell.
  void compute_primitives(const FieldArray& U) {
    if (primitives_valid_ && &U == &U_) return;
    double bad = 0.0;
    const double* Uc[Lay::kCons];
    double* Wp[Lay::kPrim];
    for (int v = 0; v < ncons_; ++v) Uc[v] = U.var(v);
    for (int v = 0; v < nprim_; ++v) Wp[v] = W_.var(v);
    for_each_row(
        [&](std::size_t base, int len, double& acc) {
          // The row's views in locals: loop-invariant to the compiler, so that the loop vectorises.
          const double* uc[Lay::kCons];
          double* wp[Lay::kPrim];
          for (int v = 0; v < Lay::kCons; ++v) uc[v] = v < ncons_ ? Uc[v] + base : nullptr;
          for (int v = 0; v < Lay::kPrim; ++v) wp[v] = v < nprim_ ? Wp[v] + base : nullptr;
          double bad_row = 0.0;
          // GRAN as a compile-time constant: a run-time select of the material energy does not vectorise.
          const auto row = [&](auto gran_tag) {
            constexpr bool gran = decltype(gran_tag)::value;
#pragma GCC ivdep
            for (int c = 0; c < len; ++c) {
              double a0 = 1.0;
              if constexpr (NP == 2) {
                a0 = uc[Lay::alpha][c];
                wp[Lay::palpha][c] = a0;
                bad_row = (a0 > 0.0 && a0 < 1.0) ? bad_row : 1.0;
              }
              for (int k = 0; k < NP; ++k) {
                const double a = k == 0 ? a0 : 1.0 - a0;
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
          if (gran_) row(std::true_type{});
          else row(std::false_type{});
          acc = std::max(acc, bad_row);
          bc_.fill_x_row(W_, base);  // the row's x ghosts while it is in cache (stage fills the others)
        },
        bad);
    if (bad > 0.0) report_bad_cell(U);
    if (&U == &U_) primitives_valid_ = true;
  }

  [[noreturn]] void report_bad_cell(const FieldArray& U) const {
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
          std::string where = fmt::format("cell (i={}", i);
          if (DIM > 1) where += fmt::format(", j={}", j);
          if (DIM > 2) where += fmt::format(", k={}", kk);
          where += fmt::format(") at x=({:.6g}", g_.center(0, i));
          if (DIM > 1) where += fmt::format(", {:.6g}", g_.center(1, j));
          if (DIM > 2) where += fmt::format(", {:.6g}", g_.center(2, kk));
          throw StateError(
              fmt::format("inadmissible state in {}) at t={:.9g} (step {}):{}", where, t_, steps_ + 1, msg));
        }
    throw StateError(fmt::format("inadmissible state at t={:.9g} (step {})", t_, steps_ + 1));
  }

  void stage(double dt, double a, double b) {
    compute_primitives(U_);
    primitives_valid_ = false;
    bc_.fill(W_);  // after the primitives pass has filled the x ghosts (fill_x_row)
    if (emb_.active) {
      fill_ghost_cells<DIM, NP>(emb_, W_, eos_);
      fill_side_ghosts<DIM, NP>(emb_, W_, eos_, side_values_);
    }
    residual();
    // Boundary inflow of this stage, with the stage's Runge-Kutta weights: U - U0 = b (U_prev - U0 + dt R).
    for (std::size_t i = 0; i < step_inflow_.size(); ++i) {
      double f = 0;
      for (const auto& sc : scratch_) f += sc.boundary[i];
      step_inflow_[i] = b * (step_inflow_[i] + dt * f);
    }
    double* Uv[Lay::kCons];
    double* U0v[Lay::kCons];
    const double* Rv[Lay::kCons];
    for (int v = 0; v < ncons_; ++v) {
      Uv[v] = U_.var(v);
      U0v[v] = U0_.var(v);
      Rv[v] = R_.var(v);
    }
    double dummy = 0;
    for_each_row(
        [&](std::size_t base, int len, double&) {
          for (int v = 0; v < ncons_; ++v) {
            double* u = Uv[v] + base;
            double* u0 = U0v[v] + base;
            const double* r = Rv[v] + base;
            if (a == 0.0) std::copy(u, u + len, u0);  // the step's start state, for the later stages
            if (emb_.active) {
              // Only flow cells are advanced: ghost and solid-cut cells get their states from step 3,
              // the interior of a body is never read (fused here: no extra pass over the grid).
              const std::uint8_t* kind = emb_.kind.data() + base;
              for (int i = 0; i < len; ++i) {
                const double un = a * u0[i] + b * (u[i] + dt * r[i]);
                u[i] = is_flow_cell(kind[i]) ? un : u[i];
              }
            } else if (a == 0.0) {
              for (int i = 0; i < len; ++i) u[i] += dt * r[i];
            } else {
              for (int i = 0; i < len; ++i) u[i] = a * u0[i] + b * (u[i] + dt * r[i]);
            }
          }
          if constexpr (NP == 2) {
            relax_cells(base, len, scene_.exchange.velocity == VelocityRelaxation::Instant,
                        scene_.exchange.pressure_relaxation);
          }
        },
        dummy);
  }

  // After a step, the ghost and solid-cut cells keep the conservative form of their image-point
  // states, so a cell the moving body uncovers is valid at once.
  void store_ghost_states() {
    for (const GhostRecord& gr : emb_.ghosts) {
      const std::size_t c = gr.cell;
      double a0 = 1.0;
      if constexpr (NP == 2) {
        a0 = W_.var(Lay::palpha)[c];
        U_.var(Lay::alpha)[c] = a0;
      }
      for (int k = 0; k < NP; ++k) {
        const double a = k == 0 ? a0 : 1.0 - a0;
        const double rho = W_.var(Lay::rho(k))[c], p = W_.var(Lay::pres(k))[c];
        double q = 0;
        U_.var(Lay::mass(k))[c] = a * rho;
        for (int d = 0; d < DIM; ++d) {
          const double u = W_.var(Lay::vel(k, d))[c];
          U_.var(Lay::mom(k, d))[c] = a * rho * u;
          q += u * u;
        }
        const double rhoe = eos_[k].rho_e(rho, p);
        U_.var(Lay::energy(k))[c] = a * (rhoe + 0.5 * rho * q);
        if constexpr (NP == 2)
          if (k == 1 && gran_) {
            U_.var(Lay::heat)[c] = a * rhoe;
            U_.var(Lay::energy(k))[c] += a * rho * W_.var(Lay::pgran)[c];
          }
      }
    }
  }

  // Paper steps 5-6 on the reconstructed edge states of one face row: at every face between a
  // flow cell and a ghost/solid-cut cell, the solid-side state becomes the mirror of the flow-side
  // state about the interface moving with u*: (alpha, rho, u - 2 ((u - u*).n) n, p) per phase, so
  // that the face Riemann problem has its contact exactly at u* (docs/methods.md §5.4). u*.n is the
  // interface velocity (first order) or its d-weighted extrapolation to the face (eqs. 23-26).
  template <int D>
  void mirror_wall_faces(std::size_t base, int len, double* left_edges, int left_off, double* right_edges,
                         int right_off) const {
    const auto& faces = emb_.faces[D];
    auto it = std::lower_bound(faces.begin(), faces.end(), base,
                               [](const WallFace& f, std::size_t b) { return high_cell(f) < b; });
    const std::size_t len_e = edge_row_len();
    for (; it != faces.end() && high_cell(*it) < base + static_cast<std::size_t>(len); ++it) {
      const WallFace& wf = *it;
      const int f = static_cast<int>(high_cell(wf) - base);
      // Flow side: hi edge of the low cell or lo edge of the high cell; the solid side gets the mirror.
      const double* from =
          wf.solid_on_high_side ? left_edges + Lay::kPrim * len_e + f + left_off : right_edges + f + right_off;
      double* to = wf.solid_on_high_side ? right_edges + f + right_off : left_edges + Lay::kPrim * len_e + f + left_off;
      mirror_edge(wf, from, to);
    }
  }

  // The mirror of the flow-side edge state `from` about the interface of wall face wf into `to` (both with the
  // edge rows' variable stride): (alpha, rho, u - 2 ((u - u*).n) n, p) per phase, u*.n the interface
  // velocity or its d-weighted extrapolation to the face (eqs. 23-26).
  void mirror_edge(const WallFace& wf, const double* from, double* to) const {
    const std::size_t len_e = edge_row_len();
    for (int v = 0; v < Lay::kPrim; ++v) to[v * len_e] = from[v * len_e];
    for (int k = 0; k < NP; ++k) {
      double un = 0, uIn = 0;
      for (int d = 0; d < DIM; ++d) {
        un += from[Lay::vel(k, d) * len_e] * wf.normal[d];
        uIn += wf.wall_velocity[d] * wf.normal[d];
      }
      double ustar = uIn;
      if (wall_second_order_) {  // eqs. 23, 25, 26 with the minmod limiter
        double u1 = 0, u2 = 0;
        for (int d = 0; d < DIM; ++d) {
          u1 += W_.var(Lay::vel(k, d))[wf.fluid_cell] * wf.normal[d];
          u2 += W_.var(Lay::vel(k, d))[wf.fluid_cell2] * wf.normal[d];
        }
        const double s = (uIn - u1) + (1.0 - wf.d) / (1.0 + wf.d) * (uIn - u2);
        const double s2 = u1 - u2;
        const double lim = s * s2 > 0.0 ? (std::abs(s) < std::abs(s2) ? s : s2) : 0.0;
        ustar = uIn + (0.5 - wf.d) * lim;
      }
      for (int d = 0; d < DIM; ++d) to[Lay::vel(k, d) * len_e] -= 2.0 * (un - ustar) * wf.normal[d];
    }
  }

  // Blocked faces (a body thinner than a cell between two flow cells) of one face row: the face buffer gets the
  // wall flux of the high cell (its mirrored lo edge | its lo edge) before apply_right, and that of the low cell
  // (its hi edge | the mirror) before apply_left. Same arguments as mirror_wall_faces.
  template <int D, ReconMode RM>
  void blocked_face_fluxes(bool high_side, std::size_t base, int len, const double* left_edges, int left_off,
                           const double* right_edges, int right_off, double* mini, double* face1, double* buf,
                           std::size_t flen) {
    const auto& faces = emb_.blocked[D];
    if (faces.empty()) return;
    auto it = std::lower_bound(faces.begin(), faces.end(), base,
                               [](const BlockedFace& f, std::size_t b) { return f.high.fluid_cell < b; });
    const std::size_t len_e = edge_row_len(), hi = Lay::kPrim * len_e;
    // One-face row in the scratch edges: face 0 = (hi edge of edge 0 | lo edge of edge 1); edge 1's hi edge is
    // the right cell's other edge (its intra-cell term, two phases).
    double* m0hi = mini + hi;
    double* m1lo = mini + 1;
    double* m1hi = mini + hi + 1;
    for (; it != faces.end() && it->high.fluid_cell < base + static_cast<std::size_t>(len); ++it) {
      const int f = static_cast<int>(it->high.fluid_cell - base);
      if (high_side) {
        const double* lo_edge = right_edges + f + right_off;
        for (int v = 0; v < Lay::kPrim; ++v) {
          m1lo[v * len_e] = lo_edge[v * len_e];
          m1hi[v * len_e] = lo_edge[hi + v * len_e];
        }
        mirror_edge(it->high, lo_edge, m0hi);
      } else {
        const double* hi_edge = left_edges + hi + f + left_off;
        for (int v = 0; v < Lay::kPrim; ++v) m0hi[v * len_e] = hi_edge[v * len_e];
        mirror_edge(it->low, hi_edge, m1lo);
        for (int v = 0; v < Lay::kPrim; ++v) m1hi[v * len_e] = m1lo[v * len_e];
      }
      compute_faces<D, RM>(1, mini, 0, mini, 1, face1, 1);
      for (int v = 0; v < kFaceVars; ++v) buf[v * flen + f] = face1[v];
    }
  }

  // Thin bodies: the flow cells with side ghosts along D among the `count` cells from `first` get their edges
  // again, with the side ghost in place of the cell across the body (compute_edges' layout).
  template <int D, ReconMode RM>
  void fix_side_edges(std::size_t first, int count, double* edges) const {
    const auto& sgs = emb_.side_ghosts[D];
    if (sgs.empty()) return;
    const std::size_t s = static_cast<std::size_t>(g_.stride[D]), len = edge_row_len();
    auto it = std::lower_bound(sgs.begin(), sgs.end(), first,
                               [](const SideGhost& g, std::size_t c) { return g.flow_cell < c; });
    const double* values = side_values_[D].data();
    while (it != sgs.end() && it->flow_cell < first + static_cast<std::size_t>(count)) {
      const std::size_t c = it->flow_cell;
      const double *below = nullptr, *above = nullptr;
      for (; it != sgs.end() && it->flow_cell == c; ++it)
        (it->across_high ? above : below) = values + static_cast<std::size_t>(it - sgs.begin()) * Lay::kPrim;
      const std::size_t e = c - first;
      for (int v = 0; v < nprim_; ++v) {
        if (is_sound_var(v)) continue;
        const double* w = W_.var(v);
        const double wm = below ? below[v] : w[c - s], wp = above ? above[v] : w[c + s];
        const double half = 0.5 * slope<RM>(wm, w[c], wp);
        edges[v * len + e] = w[c] - half;
        edges[(Lay::kPrim + v) * len + e] = w[c] + half;
      }
      for (int k = 0; k < NP; ++k)
        for (int side = 0; side < 2; ++side) {
          double* b = edges + side * Lay::kPrim * len + e;
          b[Lay::sound(k) * len] = eos_[k].sound_speed(b[Lay::rho(k) * len], b[Lay::pres(k) * len]);
        }
    }
  }
  static std::size_t high_cell(const WallFace& f) { return f.solid_on_high_side ? f.solid_cell : f.fluid_cell; }

  // The row's conservative arrays for the two-phase row kernels (physics/two_phase_row.h).
  TwoPhaseRow<DIM> two_phase_row(std::size_t base) {
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
  void relax_cells(std::size_t base, int len, bool vrelax, bool prelax) {
    if (gran_) relax_cells_as<true>(base, len, vrelax, prelax);
    else relax_cells_as<false>(base, len, vrelax, prelax);
  }
  template <bool GRAN>
  void relax_cells_as(std::size_t base, int len, bool vrelax, bool prelax) {
    const TwoPhaseRow<DIM> v = two_phase_row(base);
    const double amin = scene_.exchange.alpha_min;
    if (vrelax && prelax) relax_row<DIM, true, true, GRAN>(len, v, eos_[0], eos_[1], amin);
    else if (vrelax) relax_row<DIM, true, false, GRAN>(len, v, eos_[0], eos_[1], amin);
    else if (prelax) relax_row<DIM, false, true, GRAN>(len, v, eos_[0], eos_[1], amin);
    else relax_row<DIM, false, false, GRAN>(len, v, eos_[0], eos_[1], amin);  // clamps alpha
  }

  // Drag, heat exchange and, with a granular temperature, the loss of the particles' random motion to drag (its
  // energy decays at twice the slip's rate of the particles alone) and to inelastic collisions (GranularGas); the
  // granular energy lost becomes the material's heat (docs/methods.md §2.9, §6).
  void exchange_sources(double dt) {
    const auto& ex = scene_.exchange;
    const bool drag = ex.velocity == VelocityRelaxation::Drag;
    if (!drag && !ex.heat_transfer && !gran_) return;
    double dummy = 0;
    if constexpr (NP == 2)
      if (!drag || ex.drag_law == DragLaw::AkhatovVainshtein) {  // the row kernel (physics/exchange_row.h)
        if (drag) exchange_rows_as<true>(dt);
        else exchange_rows_as<false>(dt);
        return;
      }
    for_each_row(
        [&](std::size_t base, int len, double&) {
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
          // Drag heats the gas and heat exchange moves energy: bring the pressures back to equilibrium
          // (vectorised row pass).
          if (ex.pressure_relaxation) relax_cells(base, len, false, true);
        },
        dummy);
  }

  template <bool DRAG>
  void exchange_rows_as(double dt) {
    const bool heat = scene_.exchange.heat_transfer;
    if (gran_ && heat) exchange_rows<DRAG, true, true>(dt);
    else if (gran_) exchange_rows<DRAG, false, true>(dt);
    else if (heat) exchange_rows<DRAG, true, false>(dt);
    else exchange_rows<DRAG, false, false>(dt);
  }
  template <bool DRAG, bool HEAT, bool GRAN>
  void exchange_rows(double dt) {
    double dummy = 0;
    for_each_row(
        [&](std::size_t base, int len, double&) {
          exchange_row<DIM, DRAG, HEAT, GRAN>(len, two_phase_row(base), eos_, scene_.exchange, dt,
                                              scratch_[static_cast<std::size_t>(omp_get_thread_num())].exchange);
          if (scene_.exchange.pressure_relaxation) relax_cells(base, len, false, true);
        },
        dummy);
  }

  CellState2 load_cell(std::size_t c) const {
    CellState2 s{};
    if constexpr (NP == 2) s.alpha0 = U_.var(Lay::alpha)[c];
    for (int k = 0; k < NP; ++k) {
      s.m[k] = U_.var(Lay::mass(k))[c];
      for (int d = 0; d < DIM; ++d) s.mom[k][d] = U_.var(Lay::mom(k, d))[c];
      s.E[k] = U_.var(Lay::energy(k))[c];
    }
    return s;
  }
  void store_cell(std::size_t c, const CellState2& s) {
    if constexpr (NP == 2) U_.var(Lay::alpha)[c] = s.alpha0;
    for (int k = 0; k < NP; ++k) {
      U_.var(Lay::mass(k))[c] = s.m[k];
      for (int d = 0; d < DIM; ++d) U_.var(Lay::mom(k, d))[c] = s.mom[k][d];
      U_.var(Lay::energy(k))[c] = s.E[k];
    }
  }

  void residual() {
    for (auto& sc : scratch_) sc.boundary.fill(0.0);
    sweep<0>();  // assigns R (no zeroing pass)
    if constexpr (DIM > 1) sweep<1>();
    if constexpr (DIM > 2) sweep<2>();
  }

  template <int D>
  void sweep() {
    switch (mode_) {
      case ReconMode::First: sweep_impl<D, ReconMode::First>(); break;
      case ReconMode::Minmod: sweep_impl<D, ReconMode::Minmod>(); break;
      case ReconMode::VanLeer: sweep_impl<D, ReconMode::VanLeer>(); break;
      case ReconMode::MC: sweep_impl<D, ReconMode::MC>(); break;
    }
  }

  // Face-row buffer layout: per phase (mass, mom[DIM], energy) fluxes, then for NP = 2 the
  // phase-0 Lagrangian parts into the left cell (3) and into the right cell (3), and the material-energy flux of a
  // dispersed phase with a granular temperature.
  static constexpr int fvar_flux(int k, int q) { return k * (2 + DIM) + q; }
  static constexpr int fvar_lag_left = NP * (2 + DIM);
  static constexpr int fvar_lag_right = NP * (2 + DIM) + 3;
  static constexpr int fvar_heat = NP * (2 + DIM) + 6;  // a dispersed phase's material energy (granular temperature)

  // Per-thread scratch: the face-row buffer, two rows of reconstructed edge states, and a one-face row
  // (edges and face values) for the blocked faces of thin bodies.
  struct Scratch {
    std::vector<double> data;
    double* faces = nullptr;
    double* edges[2] = {nullptr, nullptr};
    double* mini = nullptr;
    double* face1 = nullptr;
    double* exchange = nullptr;  // kExchangeScratch rows of cells: exchange_row's scratch, max_wave_rate's rates
    std::array<double, NP*(2 + DIM)> boundary{};  // this residual's flux into the domain [per second]
  };
  std::size_t edge_row_len() const { return static_cast<std::size_t>(g_.n[0] + 2); }
  void allocate_scratch() {
    const std::size_t flen = static_cast<std::size_t>(g_.n[0] + 1), elen = edge_row_len();
    const std::size_t fsize = static_cast<std::size_t>(kFaceVars) * flen, esize = 2 * Lay::kPrim * elen;
    scratch_.resize(static_cast<std::size_t>(omp_get_max_threads()));
    for (auto& sc : scratch_) {
      const std::size_t xsize = static_cast<std::size_t>(kExchangeScratch) * static_cast<std::size_t>(g_.n[0]);
      sc.data.assign(fsize + 3 * esize + kFaceVars + xsize, 0.0);
      sc.faces = sc.data.data();
      sc.edges[0] = sc.faces + fsize;
      sc.edges[1] = sc.edges[0] + esize;
      sc.mini = sc.edges[1] + esize;
      sc.face1 = sc.mini + esize;
      sc.exchange = sc.face1 + kFaceVars;
    }
  }

  template <int D, ReconMode RM>
  void sweep_impl() {
    const double inv_dx = 1.0 / g_.dx[D];
    const std::size_t s = static_cast<std::size_t>(g_.stride[D]);
    const int n0 = g_.n[0];
    const std::size_t flen = static_cast<std::size_t>(n0 + 1);
    if constexpr (D == 0) {
      const int rows = g_.n[1] * g_.n[2];
#pragma omp parallel for schedule(static)
      for (int row = 0; row < rows; ++row) {
        Scratch& sc = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
        const std::size_t base = g_.index(0, row % g_.n[1], row / g_.n[1]);
        // Edge index e <-> cell base - 1 + e; face f has left edge row index f, right f + 1.
        compute_edges<D, RM>(base - 1, n0 + 2, sc.edges[0]);
        if (emb_.active) {
          fix_side_edges<D, RM>(base - 1, n0 + 2, sc.edges[0]);
          mirror_wall_faces<D>(base, n0 + 1, sc.edges[0], 0, sc.edges[0], 1);
        }
        compute_faces<D, RM>(n0 + 1, sc.edges[0], 0, sc.edges[0], 1, sc.faces, flen);
        const auto blocked = [&](bool high_side) {
          if (emb_.active)
            blocked_face_fluxes<D, RM>(high_side, base, n0 + 1, sc.edges[0], 0, sc.edges[0], 1, sc.mini, sc.face1,
                                       sc.faces, flen);
        };
        add_boundary_flux<D>(sc, sc.faces, flen, 0, base, 1);
        add_boundary_flux<D>(sc, sc.faces, flen, n0, base + n0 - 1, -1);
        blocked(true);
        apply_right<D, true>(sc.faces, flen, base, 0, n0, inv_dx);
        blocked(false);
        apply_left<D>(sc.faces, flen, base - 1, 1, n0 + 1, inv_dx);
      }
    } else {
      const int nD = g_.n[D];
      const int others = D == 1 ? g_.n[2] : g_.n[1];
      const int chunks = std::max(1, std::min(nD, 4 * omp_get_max_threads()));
      const int tasks = others * chunks;
#pragma omp parallel for schedule(static)
      for (int t = 0; t < tasks; ++t) {
        Scratch& sc = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
        const int o = t / chunks, ch = t % chunks;
        const int a = static_cast<int>(static_cast<long>(ch) * nD / chunks);
        const int b = static_cast<int>(static_cast<long>(ch + 1) * nD / chunks);
        auto row_base = [&](int layer) { return D == 1 ? g_.index(0, layer, o) : g_.index(0, o, layer); };
        // Edge rows alternate between the two buffers: `prev` holds the cell row below the face layer.
        int prev = 0;
        compute_edges<D, RM>(row_base(a - 1), n0, sc.edges[prev]);
        if (emb_.active) fix_side_edges<D, RM>(row_base(a - 1), n0, sc.edges[prev]);
        for (int layer = a; layer <= b; ++layer) {
          const std::size_t base = row_base(layer);
          compute_edges<D, RM>(base, n0, sc.edges[1 - prev]);
          if (emb_.active) {
            fix_side_edges<D, RM>(base, n0, sc.edges[1 - prev]);
            mirror_wall_faces<D>(base, n0, sc.edges[prev], 0, sc.edges[1 - prev], 0);
          }
          compute_faces<D, RM>(n0, sc.edges[prev], 0, sc.edges[1 - prev], 0, sc.faces, flen);
          const auto blocked = [&](bool high_side) {
            if (emb_.active)
              blocked_face_fluxes<D, RM>(high_side, base, n0, sc.edges[prev], 0, sc.edges[1 - prev], 0, sc.mini,
                                         sc.face1, sc.faces, flen);
          };
          if (layer == 0)
            for (int f = 0; f < n0; ++f) add_boundary_flux<D>(sc, sc.faces, flen, f, base + f, 1);
          if (layer == nD)
            for (int f = 0; f < n0; ++f) add_boundary_flux<D>(sc, sc.faces, flen, f, base - s + f, -1);
          if (layer < b) {
            blocked(true);
            apply_right<D>(sc.faces, flen, base, 0, n0, inv_dx);
          }
          if (layer > a) {
            blocked(false);
            apply_left<D>(sc.faces, flen, base - s, 0, n0, inv_dx);
          }
          prev = 1 - prev;
        }
      }
    }
  }

  // A domain-boundary face f of a face row whose interior cell is `cell`: sign +1 when the flux along +e_D
  // enters the domain (the low boundary), -1 at the high one; times the face area. Faces next to a body's
  // cell (not a flow cell) carry nothing into the flow cells.
  template <int D>
  void add_boundary_flux(Scratch& sc, const double* buf, std::size_t flen, int f, std::size_t cell, int sign) const {
    if (emb_.active && !is_flow_cell(emb_.kind[cell])) return;
    const double area = sign * g_.cell_volume() / g_.dx[D];
    for (int k = 0; k < NP; ++k)
      for (int q = 0; q < 2 + DIM; ++q) sc.boundary[fvar_flux(k, q)] += area * buf[fvar_flux(k, q) * flen + f];
  }

  // Faces f in [f0, f1) of the row add (F + Lag_right) to cell rbase + f. The x sweep comes first
  // and assigns instead (ASSIGN), which saves a pass that zeroes the residual.
  template <int D, bool ASSIGN = false>
  void apply_right(const double* buf, std::size_t flen, std::size_t rbase, int f0, int f1, double inv_dx) {
    for (int k = 0; k < NP; ++k)
      for (int q = 0; q < 2 + DIM; ++q) {
        double* r = R_.var(Lay::mass(k) + q) + rbase;
        const double* F = buf + fvar_flux(k, q) * flen;
        if constexpr (ASSIGN)
          for (int f = f0; f < f1; ++f) r[f] = inv_dx * F[f];
        else
          for (int f = f0; f < f1; ++f) r[f] += inv_dx * F[f];
      }
    if constexpr (NP == 2) {
      if constexpr (ASSIGN) std::fill(R_.var(Lay::alpha) + rbase + f0, R_.var(Lay::alpha) + rbase + f1, 0.0);
      apply_lagrangian<D>(buf + fvar_lag_right * flen, flen, rbase, f0, f1, inv_dx);
      if (gran_) {
        double* r = R_.var(Lay::heat) + rbase;
        const double* F = buf + fvar_heat * flen;
        if constexpr (ASSIGN)
          for (int f = f0; f < f1; ++f) r[f] = inv_dx * F[f];
        else
          for (int f = f0; f < f1; ++f) r[f] += inv_dx * F[f];
      }
    }
  }
  // Faces f in [f0, f1) subtract F and add Lag_left to cell lbase + f.
  template <int D>
  void apply_left(const double* buf, std::size_t flen, std::size_t lbase, int f0, int f1, double inv_dx) {
    for (int k = 0; k < NP; ++k)
      for (int q = 0; q < 2 + DIM; ++q) {
        double* r = R_.var(Lay::mass(k) + q) + lbase;
        const double* F = buf + fvar_flux(k, q) * flen;
        for (int f = f0; f < f1; ++f) r[f] -= inv_dx * F[f];
      }
    if constexpr (NP == 2) {
      apply_lagrangian<D>(buf + fvar_lag_left * flen, flen, lbase, f0, f1, inv_dx);
      if (gran_) {
        double* r = R_.var(Lay::heat) + lbase;
        const double* F = buf + fvar_heat * flen;
        for (int f = f0; f < f1; ++f) r[f] -= inv_dx * F[f];
      }
    }
  }
  // Phase 0 gets +Lag, phase 1 gets -Lag (its [X_k] is opposite); momentum along the face normal.
  template <int D>
  void apply_lagrangian(const double* lag, std::size_t flen, std::size_t base, int f0, int f1, double inv_dx) {
    double* ra = R_.var(Lay::alpha) + base;
    double* rm0 = R_.var(Lay::mom(0, D)) + base;
    double* rm1 = R_.var(Lay::mom(NP - 1, D)) + base;
    double* re0 = R_.var(Lay::energy(0)) + base;
    double* re1 = R_.var(Lay::energy(NP - 1)) + base;
    const double* la = lag;
    const double* lm = lag + flen;
    const double* le = lag + 2 * flen;
    for (int f = f0; f < f1; ++f) {
      ra[f] += inv_dx * la[f];
      rm0[f] += inv_dx * lm[f];
      rm1[f] -= inv_dx * lm[f];
      re0[f] += inv_dx * le[f];
      re1[f] -= inv_dx * le[f];
    }
  }

  template <ReconMode RM>
  static double slope(double wm, double w0, double wp) {
    if constexpr (RM == ReconMode::First) {  // first order: the edges are the cell values
      (void)wm, (void)w0, (void)wp;
      return 0.0;
    } else if constexpr (RM == ReconMode::Minmod) return limited_slope<Limiter::Minmod>(w0 - wm, wp - w0);
    else if constexpr (RM == ReconMode::VanLeer) return limited_slope<Limiter::VanLeer>(w0 - wm, wp - w0);
    else return limited_slope<Limiter::MC>(w0 - wm, wp - w0);
  }

  // The primitive slots that hold a phase's sound speed: edges get it from their rho and p, not by reconstruction.
  static constexpr bool is_sound_var(int v) {
    for (int k = 0; k < NP; ++k)
      if (v == Lay::sound(k)) return true;
    return false;
  }

  // Limited MUSCL edge states of `count` consecutive cells starting at `first` along direction D.
  // Edge buffer layout: for every primitive variable v, lo[v][e] at e + v * len and hi at
  // e + (kPrim + v) * len, len = edge_row_len(). Every cell's slopes are computed once per sweep.
  template <int D, ReconMode RM>
  void compute_edges(std::size_t first, int count, double* edges) const {
    const std::size_t s = static_cast<std::size_t>(g_.stride[D]), len = edge_row_len();
    for (int v = 0; v < nprim_; ++v) {
      if (is_sound_var(v)) continue;  // from rho and p below
      const double* w = W_.var(v) + first;
      double* lo = edges + v * len;
      double* hi = edges + (Lay::kPrim + v) * len;
      for (int e = 0; e < count; ++e) {
        const double half = 0.5 * slope<RM>(w[e - s], w[e], w[e + s]);
        lo[e] = w[e] - half;
        hi[e] = w[e] + half;
      }
    }
    for (int k = 0; k < NP; ++k)
      for (int side = 0; side < 2; ++side) {
        const std::size_t off = side * Lay::kPrim * len;
        const double* r = edges + off + Lay::rho(k) * len;
        const double* p = edges + off + Lay::pres(k) * len;
        double* c = edges + off + Lay::sound(k) * len;
        const double g = eos_[k].gamma, pinf = eos_[k].pinf;
        for (int e = 0; e < count; ++e) c[e] = std::sqrt(g * (p[e] + pinf) / r[e]);
      }
  }

  // Phase state of edge e (side 0 = lo, 1 = hi) of an edge row.
  PhaseState<DIM> edge_state(const double* edges, int side, int k, int e) const {
    const std::size_t len = edge_row_len();
    const double* b = edges + side * Lay::kPrim * len + e;
    PhaseState<DIM> st;
    st.rho = b[Lay::rho(k) * len];
    for (int d = 0; d < DIM; ++d) st.u[d] = b[Lay::vel(k, d) * len];
    st.p = b[Lay::pres(k) * len];
    st.c = b[Lay::sound(k) * len];
    return st;
  }
  double edge_alpha(const double* edges, int side, int e) const {
    return edges[(side * Lay::kPrim + Lay::palpha) * edge_row_len() + e];
  }

  // Faces f in [0, len) of a row. Left states: hi edges of
  // `left_edges` at f + left_off; right states: lo edges of `right_edges` at f + right_off.
  template <int D, ReconMode RM>
  void compute_faces(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                     double* buf, std::size_t flen) {
    const bool lowmach = scene_.low_mach;
    const double cutoff = scene_.low_mach_cutoff;
    // Face f's reconstructed left/right phase states and phase-0 volume fractions.
    auto load_face = [&](int f, PhaseState<DIM>(&L)[NP], PhaseState<DIM>(&R)[NP], double& aL, double& aR) {
      aL = aR = 1.0;
      for (int k = 0; k < NP; ++k) {
        L[k] = edge_state(left_edges, 1, k, f + left_off);
        R[k] = edge_state(right_edges, 0, k, f + right_off);
      }
      if constexpr (NP == 2) {
        aL = edge_alpha(left_edges, 1, f + left_off);
        aR = edge_alpha(right_edges, 0, f + right_off);
      }
    };
    if constexpr (FK == FluxKind::AUFS) {
      // Same-phase contacts with the vectorised AUFS row kernel, one phase at a time.
      const std::size_t elen = edge_row_len();
      for (int k = 0; k < NP; ++k) {
        const double* lv[Lay::kPrimPerPhase];
        const double* rv[Lay::kPrimPerPhase];
        double* fv[2 + DIM];
        for (int q = 0; q < Lay::kPrimPerPhase; ++q) {
          const int v = Lay::rho(k) + q;
          lv[q] = left_edges + (Lay::kPrim + v) * elen + left_off;
          rv[q] = right_edges + v * elen + right_off;
        }
        for (int q = 0; q < 2 + DIM; ++q) fv[q] = buf + fvar_flux(k, q) * flen;
        if (trace_[k] > 1.0) {  // a dispersed phase: the trace flux everywhere
          if (gran_)
            trace_row<DIM, D, true>(len, lv, rv, fv, eos_[k], left_edges + (Lay::kPrim + Lay::pgran) * elen + left_off,
                                    right_edges + Lay::pgran * elen + right_off, buf + fvar_heat * flen);
          else trace_row<DIM, D>(len, lv, rv, fv, eos_[k]);
          continue;
        }
        if (lowmach) aufs_row<DIM, D, true>(len, lv, rv, fv, eos_[k], cutoff);
        else aufs_row<DIM, D, false>(len, lv, rv, fv, eos_[k], cutoff);
        if constexpr (NP == 2) trace_faces<D>(k, len, left_edges, left_off, right_edges, right_off, fv);
      }
      if constexpr (NP == 2) {
        // Weight by the same-phase contact fractions S_kk = min(alpha_k-, alpha_k+).
        const double* al = left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off;
        const double* ar = right_edges + Lay::palpha * elen + right_off;
        for (int q = 0; q < 2 + DIM; ++q) {
          double* f0 = buf + fvar_flux(0, q) * flen;
          double* f1 = buf + fvar_flux(1, q) * flen;
#pragma GCC ivdep
          for (int f = 0; f < len; ++f) {
            f0[f] *= std::min(al[f], ar[f]);
            f1[f] *= std::min(1.0 - al[f], 1.0 - ar[f]);
          }
        }
        if (gran_) {
          double* fh = buf + fvar_heat * flen;
#pragma GCC ivdep
          for (int f = 0; f < len; ++f) fh[f] *= std::min(1.0 - al[f], 1.0 - ar[f]);
        }
        std::fill_n(buf + fvar_lag_left * flen, 6 * flen, 0.0);
        cross_faces<D, RM>(len, left_edges, left_off, right_edges, right_off, buf, flen);
      }
      add_particle_stress<D>(len, left_edges, left_off, right_edges, right_off, buf, flen);
      return;
    }
    for (int f = 0; f < len; ++f) {
      PhaseState<DIM> L[NP], R[NP];
      double aL, aR;
      load_face(f, L, R, aL, aR);
      FaceResult<DIM, NP> res;
      if (lowmach) {
        PhaseState<DIM> sL[NP], sR[NP];
        for (int k = 0; k < NP; ++k) {
          sL[k] = L[k];
          sR[k] = R[k];
          const double amin = k == 0 ? std::min(aL, aR) : std::min(1.0 - aL, 1.0 - aR);
          if (amin > 1e-6) low_mach_correction<DIM>(sL[k].u, sL[k].c, sR[k].u, sR[k].c, cutoff);
        }
        dem_face<FK, DIM, NP, D>(L, R, sL, sR, aL, aR, eos_, res, trace_.data());
      } else {
        dem_face<FK, DIM, NP, D>(L, R, L, R, aL, aR, eos_, res, trace_.data());
      }
      for (int k = 0; k < NP; ++k) {
        buf[fvar_flux(k, 0) * flen + f] = res.flux[k].mass;
        for (int d = 0; d < DIM; ++d) buf[fvar_flux(k, 1 + d) * flen + f] = res.flux[k].mom[d];
        buf[fvar_flux(k, 1 + DIM) * flen + f] = res.flux[k].energy;
      }
      if constexpr (NP == 2)
        store_lagrangian(buf, flen, f, res.to_left,
                         add_intra_cell<D, RM>(R, aR, right_edges, f + right_off, res.to_right));
    }
    add_particle_stress<D>(len, left_edges, left_off, right_edges, right_off, buf, flen);
  }

  // The cross contacts of a row's faces and the second-order intra-cell contacts of their right cells, over the
  // span of faces where the volume fraction varies (flux/cross_row.h); outside it they are zero.
  template <int D, ReconMode RM>
  void cross_faces(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                   double* buf, std::size_t flen) const {
    if constexpr (NP == 2) {
      const std::size_t elen = edge_row_len();
      const double* al = left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off;
      const double* ar = right_edges + Lay::palpha * elen + right_off;
      const double* arhi = right_edges + (Lay::kPrim + Lay::palpha) * elen + right_off;
      const bool intra = RM != ReconMode::First;
      const auto varies = [&](int f) { return al[f] != ar[f] || (intra && ar[f] != arhi[f]); };
      int lo = 0, hi = len;
      while (lo < hi && !varies(lo)) ++lo;
      while (hi > lo && !varies(hi - 1)) --hi;
      if (lo == hi) return;
      // Views of the span: phase k's (rho, u, p, c) on the left cells' hi edges, the right cells' lo and hi edges.
      const double *Lv[2][Lay::kPrimPerPhase], *Rv[2][Lay::kPrimPerPhase], *Hv[2][Lay::kPrimPerPhase];
      for (int k = 0; k < 2; ++k)
        for (int q = 0; q < Lay::kPrimPerPhase; ++q) {
          const int v = Lay::rho(k) + q;
          Lv[k][q] = left_edges + (Lay::kPrim + v) * elen + left_off + lo;
          Rv[k][q] = right_edges + v * elen + right_off + lo;
          Hv[k][q] = right_edges + (Lay::kPrim + v) * elen + right_off + lo;
        }
      double *f0[2 + DIM], *f1[2 + DIM], *lagl[3], *lagr[3];
      for (int q = 0; q < 2 + DIM; ++q) {
        f0[q] = buf + fvar_flux(0, q) * flen + lo;
        f1[q] = buf + fvar_flux(1, q) * flen + lo;
      }
      for (int q = 0; q < 3; ++q) {
        lagl[q] = buf + (fvar_lag_left + q) * flen + lo;
        lagr[q] = buf + (fvar_lag_right + q) * flen + lo;
      }
      CrossRowOut out;
      out.flux0 = f0;
      out.flux1 = f1;
      out.lag_left = lagl;
      out.lag_right = lagr;
      if (gran_) out.heat = buf + fvar_heat * flen + lo;
      const int n = hi - lo;
      cross_row<DIM, D, false>(n, Lv[0], Lv[1], Rv[0], Rv[1], al + lo, ar + lo, eos_, out);
      if (intra) cross_row<DIM, D, true>(n, Rv[0], Rv[1], Hv[0], Hv[1], ar + lo, arhi + lo, eos_, out);
    } else {
      (void)len, (void)left_edges, (void)left_off, (void)right_edges, (void)right_off, (void)buf, (void)flen;
    }
  }

  // A dispersed phase's collision stress Pi(alpha) at the faces of a row (docs/methods.md §2.8): the centred
  // stress in its normal momentum and energy fluxes, with the local Lax-Friedrichs dissipation of its compaction
  // waves, -c_f/2 (U+ - U-), c_f = max of the two sides' sqrt(Pi'/rho_p), on its conserved variables.
  template <int D>
  void add_particle_stress(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                           double* buf, std::size_t flen) const {
    if constexpr (NP == 2) {
      if (!scene_.exchange.dispersed) return;
      const bool b3 = scene_.exchange.particle_stress.beta == 3.0;
      if (gran_ && b3) particle_stress_row<D, 3, true>(len, left_edges, left_off, right_edges, right_off, buf, flen);
      else if (gran_) particle_stress_row<D, 0, true>(len, left_edges, left_off, right_edges, right_off, buf, flen);
      else if (b3) particle_stress_row<D, 3, false>(len, left_edges, left_off, right_edges, right_off, buf, flen);
      else particle_stress_row<D, 0, false>(len, left_edges, left_off, right_edges, right_off, buf, flen);
    } else {
      (void)len, (void)left_edges, (void)left_off, (void)right_edges, (void)right_off, (void)buf, (void)flen;
    }
  }
  // The row's edge views for physics/particle_stress_row.h.
  template <int D, int B, bool GRAN>
  void particle_stress_row(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                           double* buf, std::size_t flen) const {
    const std::size_t elen = edge_row_len();
    const auto lv = [&](int v) { return left_edges + (Lay::kPrim + v) * elen + left_off; };  // hi edge, left cell
    const auto rv = [&](int v) { return right_edges + v * elen + right_off; };               // lo edge, right cell
    DispersedFaceRow<DIM> r;
    r.alpha_left = lv(Lay::palpha);
    r.alpha_right = rv(Lay::palpha);
    r.rho_left = lv(Lay::rho(1));
    r.rho_right = rv(Lay::rho(1));
    r.p_left = lv(Lay::pres(1));
    r.p_right = rv(Lay::pres(1));
    for (int d = 0; d < DIM; ++d) {
      r.u_left[d] = lv(Lay::vel(1, d));
      r.u_right[d] = rv(Lay::vel(1, d));
      r.flux_mom[d] = buf + fvar_flux(1, 1 + d) * flen;
    }
    r.flux_mass = buf + fvar_flux(1, 0) * flen;
    r.flux_energy = buf + fvar_flux(1, 1 + DIM) * flen;
    if constexpr (GRAN) {
      r.k_left = lv(Lay::pgran);
      r.k_right = rv(Lay::pgran);
      r.flux_heat = buf + fvar_heat * flen;
    }
    add_particle_stress_row<DIM, D, B, GRAN>(len, r, scene_.exchange.particle_stress, scene_.exchange.granular,
                                             eos_[NP - 1]);
  }

  // Faces of a row where phase k is a trace on both sides get the trace flux (flux/trace_flux.h) in place of
  // the row kernel's, per unit contact (before the contact-fraction weights).
  template <int D>
  void trace_faces(int k, int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                   double* const* fv) const {
    if (trace_[k] <= 0.0) return;
    const std::size_t elen = edge_row_len();
    const double* al = left_edges + (Lay::kPrim + Lay::palpha) * elen + left_off;
    const double* ar = right_edges + Lay::palpha * elen + right_off;
    for (int f = 0; f < len; ++f) {
      const double akL = k == 0 ? al[f] : 1.0 - al[f], akR = k == 0 ? ar[f] : 1.0 - ar[f];
      if (!(akL < trace_[k] && akR < trace_[k])) continue;  // phase k not a trace on both sides
      const PhaseFlux<DIM> t = trace_flux<DIM, D>(edge_state(left_edges, 1, k, f + left_off),
                                                  edge_state(right_edges, 0, k, f + right_off), eos_[k]);
      fv[0][f] = t.mass;
      for (int d = 0; d < DIM; ++d) fv[1 + d][f] = t.mom[d];
      fv[1 + DIM][f] = t.energy;
    }
  }

  // Adds the second-order intra-cell Lagrangian term of the face's right cell (docs/methods.md §2.6 step 3).
  template <int D, ReconMode RM>
  Lagrangian add_intra_cell(const PhaseState<DIM> (&R)[NP], double aR, const double* right_edges, int e,
                            Lagrangian right) const {
    if constexpr (NP == 2 && RM != ReconMode::First) {
      const double aRhi = edge_alpha(right_edges, 1, e);
      if (aR != aRhi) {
        PhaseState<DIM> Rhi[NP];
        for (int k = 0; k < NP; ++k) Rhi[k] = edge_state(right_edges, 1, k, e);
        const Lagrangian in = intra_cell_term<DIM, D>(R, aR, Rhi, aRhi, eos_);
        right.alpha += in.alpha;
        right.mom += in.mom;
        right.energy += in.energy;
      }
    } else {
      (void)R;
      (void)aR;
      (void)right_edges;
      (void)e;
    }
    return right;
  }

  static void store_lagrangian(double* buf, std::size_t flen, int f, const Lagrangian& left, const Lagrangian& right) {
    buf[(fvar_lag_left + 0) * flen + f] = left.alpha;
    buf[(fvar_lag_left + 1) * flen + f] = left.mom;
    buf[(fvar_lag_left + 2) * flen + f] = left.energy;
    buf[(fvar_lag_right + 0) * flen + f] = right.alpha;
    buf[(fvar_lag_right + 1) * flen + f] = right.mom;
    buf[(fvar_lag_right + 2) * flen + f] = right.energy;
  }

  FluidScene scene_;
  Grid<DIM> g_;
  eos::StiffenedGas eos_[NP];
  FieldArray U_, U0_, R_, W_;
  std::vector<Scratch> scratch_;
  BoundaryFiller<DIM, NP> bc_;
  ReconMode mode_ = ReconMode::VanLeer;
  double t_ = 0.0;
  long steps_ = 0;
  bool primitives_valid_ = false;
  EmbeddedState emb_;
  std::array<double, NP*(2 + DIM)> inflow_{}, step_inflow_{};  // boundary_inflow(): since the start, this step
  std::array<std::vector<double>, 3> side_values_;             // side ghosts' primitives, kPrim each (fill_side_ghosts)
  bool wall_second_order_ = true;
  // Per phase: below this volume fraction the phase is a trace (docs/methods.md §2.7); 2 for a dispersed phase.
  std::array<double, NP> trace_{};
  // A dispersed phase with a granular temperature (docs/methods.md §2.9): the last conservative slot holds its
  // material energy, the last primitive slot its granular energy per unit mass; ncons_ / nprim_ variables in use.
  const bool gran_;
  const int ncons_, nprim_;
};

}  // namespace cosim::fluid
