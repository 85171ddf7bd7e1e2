// A Runge-Kutta stage: boundaries, the sweeps, and the update of each cell row the y sweep completes.
#pragma once

#include "fluid_solver/core/solver.h"

namespace cosim::fluid {

// One Runge-Kutta stage, U <- a U0 + b (U + dt R(U)): the sweeps assign and add their face fluxes into R, and
// each cell row that the y sweep (x in 1D) completes goes to update_row; exchange_dt > 0: the step's drag and
// heat exchange over that time follow in each row (the last stage).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::stage(double dt, double a, double b, bool fuse_primitives, double exchange_dt,
                                       StageTimes times) {
  const bool moving_volumes = conservative_ && !vrate_.empty();
  if (moving_volumes && times.in != 0.0) volumes_at(volumes_elapsed_ + times.in * dt);
  compute_primitives();
  if (moving_volumes) volumes_at(volumes_elapsed_ + times.out * dt);  // the contents it makes (its relaxations)
  primitives_valid_ = primitives_bad_ = false;
  {
    PassClock clk(pass_acc(Pass::Boundaries));
    // After the primitives pass has filled the x ghosts of the boundary conditions (fill_x_row): the neighbouring
    // blocks' x ghosts, then per axis the boundary conditions' and the neighbours' ghosts over those before it.
    if (links_) links_->exchange_ghosts(W_, 0);
    for (int d = 1; d < DIM; ++d) {
      bc_.fill_direction(W_, d);
      if (links_) links_->exchange_ghosts(W_, d);
    }
    if (emb_.active) {
      if (links_) exchange_far_cells();
      fill_ghost_cells<DIM, NP>(emb_, W_, eos_);
      fill_side_ghosts<DIM, NP>(emb_, W_, eos_, side_values_);
    }
  }
  if (a == 0.0) std::swap(U_, U0_);  // U0: the step's start state; update_row writes U's rows anew
  for (auto& sc : scratch_) {
    sc.boundary.fill(0.0);
    sc.flow_mass.fill(0.0);
    sc.wall.fill(0.0);
    sc.bad = 0.0;
  }
  const auto finish = [&](Scratch& sc, std::size_t base, int len, bool primitives_now) {
    update_row(sc, base, len, dt, a, b, fuse_primitives && primitives_now, exchange_dt);
  };
  if constexpr (DIM == 1) {
    sweep<0>(finish);
  } else {
    if constexpr (DIM == 3) sweep<2>([](Scratch&, std::size_t, int, bool) {});
    sweep<1>(finish);
    if (fuse_primitives) deferred_primitives();
  }
  double bad = 0.0;
  for (const auto& sc : scratch_) bad = std::max(bad, sc.bad);
  if (fuse_primitives) {
    primitives_valid_ = true;
    primitives_bad_ = bad > 0.0;  // reported where the next stage or stable_dt asks for them
  }
  // Boundary inflow of this stage, with the stage's Runge-Kutta weights: U - U0 = b (U_prev - U0 + dt R).
  for (std::size_t i = 0; i < step_inflow_.size(); ++i) {
    double f = 0;
    for (const auto& sc : scratch_) f += sc.boundary[i];
    step_inflow_[i] = b * (step_inflow_[i] + dt * f);
  }
  // Through the embedded walls: what entered the flow cells, less what came through the domain boundary.
  if (emb_.active)
    for (int k = 0; k < NP; ++k) {
      double f = 0;
      for (const auto& sc : scratch_) f += sc.flow_mass[k] - sc.boundary[fvar_flux(k, 0)];
      step_wall_mass_[k] = b * (step_wall_mass_[k] + dt * f);
    }
  if (emb_.active)
    for (std::size_t i = 0; i < step_wall_.size(); ++i) {
      double f = 0;
      for (const auto& sc : scratch_) f += sc.wall[i];
      step_wall_[i] = b * (step_wall_[i] + dt * f);
    }
}

// On a block of a split mesh: the primitives of the far cells its embedded records read (EmbeddedState::far_cells)
// from their owners, and those of its cells the other blocks read, after every block's ghost layers are filled.
// Every block takes part (one without bodies near it may still hold cells another one reads).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::exchange_far_cells() {
  const std::vector<std::size_t>& send = links_->far_send(0);
  const std::size_t nv = static_cast<std::size_t>(nprim_);
  far_send_.resize(send.size() * nv);
  for (std::size_t i = 0; i < send.size(); ++i)
    for (std::size_t v = 0; v < nv; ++v) far_send_[i * nv + v] = W_.var(static_cast<int>(v))[send[i]];
  far_recv_.resize(emb_.far_cells * nv);
  links_->exchange_far(0, far_send_.data(), far_recv_.data(), nprim_);
  for (std::size_t s = 0; s < emb_.far_cells; ++s)
    for (std::size_t v = 0; v < nv; ++v) W_.var(static_cast<int>(v))[g_.total + s] = far_recv_[s * nv + v];
}

// A row of cells whose residual is complete: the Runge-Kutta combination of its flow cells (at a = 0, U0
// holds the current state and every cell of the row is written), the instantaneous relaxations (two phases),
// drag and heat exchange over exchange_dt where it is > 0, and, with `fuse_primitives`, its primitives for the
// next stage or step.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::update_row(Scratch& sc, std::size_t base, int len, double dt, double a, double b,
                                            bool fuse_primitives, double exchange_dt) {
  {
    PassClock clk(pass_acc(Pass::Update));
    const std::uint8_t* kind = emb_.active ? emb_.kind.data() + base : nullptr;
    for (int v = 0; v < ncons_; ++v) {
      double* u = U_.var(v) + base;
      const double* u0 = U0_.var(v) + base;
      const double* r = R_.var(v) + base;
      if (kind) {
        // Only flow cells are advanced: ghost and solid-cut cells get their states from step 3,
        // the interior of a body is never read.
        if (a == 0.0)
          for (int i = 0; i < len; ++i) u[i] = is_flow_cell(kind[i]) ? u0[i] + dt * r[i] : u0[i];
        else
          for (int i = 0; i < len; ++i) {
            const double un = a * u0[i] + b * (u[i] + dt * r[i]);
            u[i] = is_flow_cell(kind[i]) ? un : u[i];
          }
      } else if (a == 0.0) {
        for (int i = 0; i < len; ++i) u[i] = u0[i] + dt * r[i];
      } else {
        for (int i = 0; i < len; ++i) u[i] = a * u0[i] + b * (u[i] + dt * r[i]);
      }
    }
    if (kind) {  // the mass rate into the row's flow cells (embedded_mass_account)
      const double vol = g_.cell_volume();
      for (int k = 0; k < NP; ++k) {
        const double* r = R_.var(Lay::mass(k)) + base;
        double s = 0;
        for (int i = 0; i < len; ++i) s += is_flow_cell(kind[i]) ? r[i] : 0.0;
        sc.flow_mass[k] += vol * s;
      }
    }
  }
  // embedded.conservative: the relaxations and the exchange act on densities, U / V (§5.8), and give contents back.
  const bool by_volume = NP == 2 && conservative_ && !vfrac_.empty();
  if (by_volume) contents_to_densities(base, len, true);
  if constexpr (NP == 2) {
    PassClock clk(pass_acc(Pass::Relaxation));
    relax_cells(base, len, scene_.exchange.velocity == VelocityRelaxation::Instant,
                scene_.exchange.pressure_relaxation);
  }
  if constexpr (NP == 2)
    if (exchange_dt > 0.0) {
      PassClock clk(pass_acc(Pass::Exchange));
      exchange_cells(sc, base, len, exchange_dt);
    }
  if (by_volume) contents_to_densities(base, len, false);
  if (fuse_primitives) {
    PassClock clk(pass_acc(Pass::Primitives));
    sc.bad = std::max(sc.bad, primitives_row(base, len));
  }
}

// Chunks of layers along a transverse direction D per line of rows (the sweep's parallel tasks).
template <int DIM, int NP, FluxKind FK>
template <int D>
inline int Solver<DIM, NP, FK>::sweep_chunks() const {
  return std::max(1, std::min(g_.n[D], 4 * omp_get_max_threads()));
}

// The primitives of the rows that the y sweep left to the end (the two at each end of a chunk).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::deferred_primitives() {
  const int ny = g_.n[1], chunks = sweep_chunks<1>(), tasks = g_.n[2] * chunks;
#pragma omp parallel for schedule(static)
  for (int t = 0; t < tasks; ++t) {
    Scratch& sc = scratch_[static_cast<std::size_t>(omp_get_thread_num())];
    PassClock clk(pass_acc(Pass::Primitives));
    const int o = t / chunks, ch = t % chunks;
    const int a = static_cast<int>(static_cast<long>(ch) * ny / chunks);
    const int b = static_cast<int>(static_cast<long>(ch + 1) * ny / chunks);
    for (int j = a; j < b; ++j)
      if (j < a + 2 || j >= b - 2) sc.bad = std::max(sc.bad, primitives_row(g_.index(0, j, o), g_.n[0]));
  }
}

}  // namespace cosim::fluid
