// The finite-volume DEM solver, templated on dimension, phase count and same-phase flux.
// One time step (SSP-RK2 or RK3), per stage:
//   1. primitives of the interior cells, with the admissibility check;
//   2. ghost cells from the boundary conditions (on primitives), and, with an embedded boundary,
//      ghost/solid-cut cells from image points (paper step 3);
//   3. residual: for each direction, face rows of MUSCL-reconstructed states (with mirrored
//      solid-side states at embedded wall faces, steps 5-6) -> DEM face contributions -> applied
//      to the two neighbouring cell rows; z first (3D), then y, which finishes each cell row as soon as both
//      its y face rows are known: the row's x faces at once, while the row is in cache (x_row), and
//   4. the Runge-Kutta combination of its flow cells, its instantaneous relaxation (two phases) and step 1 of
//      the next stage for it (update_row).
// Finite-rate exchange (drag, heat) is applied once per step after the hyperbolic step.
// This file holds the class, its data, the step structure and the FluidSimulation interface; the member functions of
// the physics steps are defined in the solver_*.h headers included at its end.
#pragma once

#include <omp.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "common/app/threads.h"
#include "fluid_solver/core/boundary.h"
#include "fluid_solver/core/dem_face.h"
#include "fluid_solver/core/fluid_state_entries.h"
#include "fluid_solver/core/ghost_fill.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/initial_state.h"
#include "fluid_solver/core/layout.h"
#include "fluid_solver/core/pass_profile.h"
#include "fluid_solver/core/reconstruction.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/physics/exchange_row.h"
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
        g_(scene.cells, scene.lower, scene.upper, scene.block.first,
           scene.block.whole() ? scene.cells : scene.block.count),
        conservative_(scene.embedded.conservative),
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
    for (int d = 0; d < DIM; ++d)
      for (int side = 0; side < 2; ++side) domain_edge_[d][side] = scene.block.at_domain_edge(d, side, scene.cells);
    if (NP == 2 && scene.exchange.pressure_relaxation) trace_.fill(scene.exchange.trace_alpha);
    if (NP == 2 && scene.exchange.dispersed) trace_[NP - 1] = 2.0;  // a trace everywhere (§2.8)
    set_initial_state<DIM, NP>(scene, g_, eos_, U_);
    if constexpr (NP == 2)
      if (gran_)  // at rest relative to its mean motion: all of E - u^2/2 is the material's
        for (std::size_t c = 0; c < g_.total; ++c) U_.var(Lay::heat)[c] = U_.var(Lay::energy(1))[c] - kinetic(U_, 1, c);
    U0_ = U_;  // U and U0 trade places each step: their cells outside the interior rows must agree
  }

  const FluidScene& scene() const override { return scene_; }
  double time() const override { return t_; }
  long steps() const override { return steps_; }
  std::size_t interior_cells() const override { return g_.interior_count(); }
  // The step's passes over the grid, in doubles per cell, each array read or written once per pass (rows of
  // edge states and face fluxes stay in cache, and so does a cell row between the sweeps that finish it; a write
  // counted once, as STREAM counts it; the primitives' sound-speed slots are never touched): stable_dt's
  // primitives (read U, write W) unless the last stage left them, and its wave rate (read W); per Runge-Kutta stage
  // the primitives unless the stage before computed them row by row, in 3D the z sweep (read W, write R), and the
  // y sweep with the x faces and the update of each row it completes (read W, U0, in 3D R; read U but in the first
  // stage; write R, U, and W where it computes the next primitives; the few rows whose primitives wait for the end
  // of the sweep are not counted); with drag or heat exchange one more pass (read and write U). Ghost layers,
  // boundary and embedded-body work are not counted.
  double traffic_bytes_per_cell_update() const override {
    const int stages = scene_.integrator == TimeIntegrator::RK2 ? 2 : 3;
    const double nc = ncons_, np = nprim_ - NP;
    const bool fuse = !emb_.active;
    double doubles = (fuse ? 0.0 : nc + np) + np;
    for (int s = 0; s < stages; ++s) {
      if (s > 0 && !fuse) doubles += nc + np;
      if (DIM == 3) doubles += np + nc;
      doubles += np + (DIM == 3 ? 2 * nc : nc) + nc + (s > 0 ? nc : 0.0) + nc + (fuse ? np : 0.0);
    }
    return 8.0 * doubles;
  }

  std::size_t state_bytes() const override {
    std::size_t b = (U_.data.size() + U0_.data.size() + R_.data.size() + W_.data.size()) * sizeof(double);
    for (const auto& sc : scratch_) b += sc.data.size() * sizeof(double);
    return b;
  }

  void set_embedded(EmbeddedState state, bool second_order) override {
    // After set_conserved_cells (a restart) the cells already hold the state of this geometry: nothing was covered or
    // uncovered, and their contents are contents.
    const bool restored = restored_cells_;
    restored_cells_ = false;
    const bool changed = !restored && emb_.active && state.active && state.kind.size() == emb_.kind.size();
    if (changed && !conservative_) {
      // The cells the body uncovered join the flow cells with their mass, those it covered leave with theirs (the
      // block's own cells: totals() counts no ghost layer).
      const double vol = g_.cell_volume();
      for (std::size_t c = 0; c < emb_.kind.size(); ++c) {
        const int change = int{is_flow_cell(state.kind[c])} - int{is_flow_cell(emb_.kind[c])};
        if (change != 0 && g_.owns(c))  // a block counts its own cells (another block counts its ghost layers')
          for (int k = 0; k < NP; ++k) mass_by_cells_[k] += change * vol * U_.var(Lay::mass(k))[c];
      }
    }
    // Sorted by the face's high cell, to find a face row's faces; also the order of the conservative boundary's
    // sums over the faces, the same on a block as on the whole mesh (padded indices keep the mesh's order).
    for (auto& faces : state.faces)
      std::sort(faces.begin(), faces.end(),
                [](const WallFace& a, const WallFace& b) { return high_cell(a) < high_cell(b); });
    if (conservative_ && state.active) {  // solver_conservative.h
      if (state.fluid_fraction.size() != state.kind.size())
        throw std::invalid_argument("embedded.conservative: the geometry gave no fluid fractions of the cells");
      const bool first = !emb_.active && !restored;
      const double elapsed = volumes_elapsed_;
      EmbeddedState old = std::move(emb_);
      vfrac_old_.swap(vfrac_);
      shares_old_.swap(shares_);
      emb_ = std::move(state);
      fluid_volumes();
      if (first) contents_from_densities();
      else if (changed) redistribute_changed_cells(old, elapsed);  // covered and uncovered cells
    } else {
      emb_ = std::move(state);
    }
    emb_.blocked_x = emb_.blocked_x || !emb_.blocked[0].empty();
    wall_second_order_ = second_order;
    for (auto& bf : emb_.blocked)
      std::sort(bf.begin(), bf.end(),
                [](const BlockedFace& a, const BlockedFace& b) { return a.high.fluid_cell < b.high.fluid_cell; });
    for (auto& sg : emb_.side_ghosts)  // by flow cell, low side first (thin-body edges, fix_side_edges)
      std::sort(sg.begin(), sg.end(), [](const SideGhost& a, const SideGhost& b) {
        return a.flow_cell != b.flow_cell ? a.flow_cell < b.flow_cell : a.across_high < b.across_high;
      });
    if (emb_.active && emb_.kind.size() != g_.total)
      throw std::invalid_argument("embedded state: kind array does not match the grid");
    if (emb_.far_cells > 0 && !links_)
      throw std::invalid_argument("embedded state: cells beyond the grid's ghost layers without other blocks");
    if (W_.cells < g_.total + emb_.far_cells) {  // room for the far cells' primitives after the padded cells
      FieldArray w;
      w.resize(nprim_, g_.total + emb_.far_cells + emb_.far_cells / 2);
      for (int v = 0; v < nprim_; ++v) std::copy(W_.var(v), W_.var(v) + g_.total, w.var(v));
      W_ = std::move(w);
    }
  }
  void set_embedded_walls(const std::vector<WallValue>& values) override {
    if (values.size() != emb_.wall_sources.size())
      throw std::invalid_argument(
          fmt::format("embedded state: {} wall values for {} wall sources", values.size(), emb_.wall_sources.size()));
    set_wall_values(emb_, values);
    primitives_valid_ = false;  // as after set_embedded
  }
  const EmbeddedState& embedded() const override { return emb_; }
  void set_embedded_elapsed(double elapsed) override {
    if (!conservative_ || !emb_.active) return;
    volumes_elapsed_ = elapsed;
    volumes_at(elapsed);
  }

  void set_pass_profiling(bool on) override {
    profiling_ = on;
    for (auto& sc : scratch_) sc.pass = {};
  }
  PassTimes pass_times() const override {
    PassTimes t;
    for (const auto& sc : scratch_)
      for (int p = 0; p < kPassCount; ++p) t.seconds[p] += sc.pass.seconds[p];
    return t;
  }
  std::vector<double> embedded_categories() const override {
    std::vector<double> out;
    out.reserve(g_.interior_count());
    for (int k = 0; k < g_.n[2]; ++k)
      for (int j = 0; j < g_.n[1]; ++j)
        for (int i = 0; i < g_.n[0]; ++i) out.push_back(emb_.active ? emb_.kind[g_.index(i, j, k)] : 0.0);
    return out;
  }

  double stable_dt() override {
    compute_primitives();
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
    if (links_) smax = links_->max_over_blocks(smax);  // exact: every block takes the same step
    return scene_.cfl / smax;
  }

  // max over the flow cells and phases of sum_d (|u_d| + c) / dx_d (solver_primitives.h).
  template <bool DISPERSED, bool GRAN, int B>
  double max_wave_rate();

  void advance(double dt) override {
    step_inflow_.fill(0.0);
    step_wall_mass_.fill(0.0);
    step_wall_.fill(0.0);
    // The stages compute the next stage's primitives row by row, but with an embedded boundary (whose wall
    // faces read the primitives of other rows during a sweep); the next step's stable_dt then finds them
    // ready. The last stage applies drag and heat exchange to each row it finishes, before its primitives.
    const bool fuse = !emb_.active;
    const double exchange_dt = NP == 2 && exchange_changes_state() ? dt : 0.0;
    // Each stage's state and the state it makes have their times (fractions of the step: the stage's input, its
    // output), for the fluid volumes of moving walls (embedded.conservative).
    if (scene_.integrator == TimeIntegrator::RK2) {
      stage(dt, 0.0, 1.0, fuse, 0.0, {0.0, 1.0});
      stage(dt, 0.5, 0.5, fuse, exchange_dt, {1.0, 1.0});
    } else {
      stage(dt, 0.0, 1.0, fuse, 0.0, {0.0, 1.0});
      stage(dt, 0.75, 0.25, fuse, 0.0, {1.0, 0.5});
      stage(dt, 1.0 / 3.0, 2.0 / 3.0, fuse, exchange_dt, {0.5, 1.0});
    }
    if (emb_.active) {
      PassClock clk(pass_acc(Pass::Boundaries));
      store_ghost_states();
    }
    volumes_elapsed_ += dt;
    for (std::size_t i = 0; i < inflow_.size(); ++i) inflow_[i] += step_inflow_[i];
    for (int k = 0; k < NP; ++k) mass_by_walls_[k] += step_wall_mass_[k];
    for (std::size_t i = 0; i < wall_.size(); ++i) wall_[i] += step_wall_[i];
    t_ += dt;
    ++steps_;
  }

  // The state as others read and set it (solver_state.h).
  PhaseFields phase_fields(int k) const override;
  void cell_states(const std::size_t* cells, std::size_t count, CellSample* out) const override;
  std::vector<PhaseTotals> boundary_inflow() const override;
  std::vector<EmbeddedMassAccount> embedded_mass_account() const override;
  std::vector<PhaseTotals> embedded_wall_exchange() const override;
  std::vector<PhaseTotals> totals() const override;
  void save_state(checkpoint::PartWriter& w) const override;
  void restore_state(const checkpoint::PartReader& r) override;
  CellRange cells_held() const { return CellRange::of(g_.mesh, g_.first, g_.n); }
  std::vector<double> account_values() const override;
  void restore_progress(double time, long steps, const std::vector<double>& accounts) override;
  int conserved_vars() const override { return ncons_; }
  std::vector<double> conserved_cells() const override;
  void set_conserved_cells(const std::vector<double>& values) override;
  void set_block_links(BlockLinks* links) override { links_ = links; }

 private:
  struct Scratch;  // per-thread row buffers (below)

  // This thread's clock of pass p when profiling, else null (PassClock then reads no clock).
  double* pass_acc(Pass p) {
    return profiling_ ? &scratch_[static_cast<std::size_t>(omp_get_thread_num())].pass[p] : nullptr;
  }

  // Calls f(base, len, acc) for every interior x-row in parallel, timed as pass p; acc is max-reduced into result.
  template <class F>
  void for_each_row(Pass p, F&& f, double& result) {
    const int rows = g_.n[1] * g_.n[2];
    double r = result;
#pragma omp parallel for schedule(static) reduction(max : r)
    for (int row = 0; row < rows; ++row) {
      const int j = row % g_.n[1], k = row / g_.n[1];
      PassClock clk(pass_acc(p));
      f(g_.index(0, j, k), g_.n[0], r);
    }
    result = r;
  }

  // solver_stage.h: one Runge-Kutta stage, the update of a finished row, the deferred primitives.
  struct StageTimes {
    double in = 0.0, out = 0.0;  // fractions of the step
  };
  void stage(double dt, double a, double b, bool fuse_primitives, double exchange_dt, StageTimes times);
  void exchange_far_cells();
  void update_row(Scratch& sc, std::size_t base, int len, double dt, double a, double b, bool fuse_primitives,
                  double exchange_dt);
  template <int D>
  int sweep_chunks() const;
  void deferred_primitives();

  // Drag, heat exchange or a granular temperature: exchange_cells changes U in the last stage's rows.
  bool exchange_changes_state() const {
    const auto& ex = scene_.exchange;
    return ex.velocity == VelocityRelaxation::Drag || ex.heat_transfer || gran_;
  }

  // Sweep along D with the scene's reconstruction; `rows` (Scratch&, base, len, primitives_now) gets each
  // finished cell row (sweep_impl).
  template <int D, class RowDone>
  void sweep(RowDone&& rows) {
    switch (mode_) {
      case ReconMode::First: sweep_impl<D, ReconMode::First>(rows); break;
      case ReconMode::Minmod: sweep_impl<D, ReconMode::Minmod>(rows); break;
      case ReconMode::VanLeer: sweep_impl<D, ReconMode::VanLeer>(rows); break;
      case ReconMode::MC: sweep_impl<D, ReconMode::MC>(rows); break;
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
    double* faces2 = nullptr;  // the transverse sweeps' face row below the current one
    double* xfaces = nullptr;  // the y sweep's x face row (x_row)
    double* xedges = nullptr;  // and its x edges
    double* edges[2] = {nullptr, nullptr};
    double* mini = nullptr;
    double* face1 = nullptr;
    double* exchange = nullptr;  // kExchangeScratch rows of cells: exchange_row's scratch, max_wave_rate's rates
    double* trace = nullptr;     // 2 + DIM rows of faces: trace_faces' fluxes
    std::array<double, NP*(2 + DIM)> boundary{};  // this residual's flux into the domain [per second]
    std::array<double, NP> flow_mass{};           // embedded runs: its mass rate into the flow cells [per second]
    std::array<double, NP*(2 + DIM)> wall{};      // and what the wall faces put into them [per second]
    double bad = 0.0;                             // 1 when update_row's primitives found an inadmissible cell
    PassTimes pass;                               // seconds per pass of this thread (profiling on)
  };
  std::size_t edge_row_len() const { return static_cast<std::size_t>(g_.n[0] + 2); }
  static std::size_t high_cell(const WallFace& f) { return f.solid_on_high_side ? f.solid_cell : f.fluid_cell; }
  void allocate_scratch() {
    const std::size_t flen = static_cast<std::size_t>(g_.n[0] + 1), elen = edge_row_len();
    const std::size_t fsize = static_cast<std::size_t>(kFaceVars) * flen, esize = 2 * Lay::kPrim * elen;
    scratch_.resize(static_cast<std::size_t>(omp_get_max_threads()));
    for (auto& sc : scratch_) {
      const std::size_t xsize = static_cast<std::size_t>(kExchangeScratch) * static_cast<std::size_t>(g_.n[0]);
      const std::size_t tsize = static_cast<std::size_t>(2 + DIM) * flen;
      sc.data.assign(3 * fsize + 4 * esize + kFaceVars + xsize + tsize, 0.0);
      sc.faces = sc.data.data();
      sc.faces2 = sc.faces + fsize;
      sc.xfaces = sc.faces2 + fsize;
      sc.xedges = sc.xfaces + fsize;
      sc.edges[0] = sc.xedges + esize;
      sc.edges[1] = sc.edges[0] + esize;
      sc.mini = sc.edges[1] + esize;
      sc.face1 = sc.mini + esize;
      sc.exchange = sc.face1 + kFaceVars;
      sc.trace = sc.exchange + xsize;
    }
  }

  // solver_primitives.h: conservative -> primitive, energy helpers, the admissibility report (and max_wave_rate).
  static double kinetic(const FieldArray& U, int k, std::size_t c);
  double material_energy(const FieldArray& U, int k, std::size_t c) const;
  double granular_energy(const FieldArray& U, std::size_t c) const;
  double granular_per_mass(const FieldArray& U, std::size_t c) const;
  void compute_primitives();
  double primitives_row(std::size_t base, int len);
  [[noreturn]] void report_bad_cell() const;

  // solver_reconstruction.h: MUSCL slopes and edge states.
  template <ReconMode RM>
  static double slope(double wm, double w0, double wp);
  static constexpr bool is_sound_var(int v);
  template <int D, ReconMode RM>
  void compute_edges(std::size_t first, int count, double* edges) const;
  PhaseState<DIM> edge_state(const double* edges, int side, int k, int e) const;
  double edge_alpha(const double* edges, int side, int e) const;

  // solver_sweep.h: directional sweeps, face-row fluxes, boundary inflow, residual application.
  template <int D, ReconMode RM, class RowDone>
  void sweep_impl(RowDone& row_done);
  template <ReconMode RM>
  void x_row(Scratch& sc, std::size_t base, double* edges, double* faces);
  template <int D, ReconMode RM>
  void compute_faces(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                     double* buf, std::size_t flen);
  template <int D>
  void add_boundary_flux(Scratch& sc, const double* buf, std::size_t flen, int f, std::size_t cell, int sign) const;
  template <int D, bool ASSIGN>
  void apply_cells(const double* low, const double* high, std::size_t flen, std::size_t base, int n, double inv_dx);
  template <int D, bool ASSIGN = false>
  void apply_right(const double* buf, std::size_t flen, std::size_t rbase, int f0, int f1, double inv_dx);
  template <int D>
  void apply_left(const double* buf, std::size_t flen, std::size_t lbase, int f0, int f1, double inv_dx);
  template <int D>
  void apply_lagrangian(const double* lag, std::size_t flen, std::size_t base, int f0, int f1, double inv_dx);

  // solver_two_phase_faces.h: cross contacts, intra-cell Lagrangian terms, trace phases, collision stress.
  template <int D, ReconMode RM>
  void cross_faces(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                   double* buf, std::size_t flen) const;
  template <int D>
  void add_particle_stress(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                           double* buf, std::size_t flen) const;
  template <int D, int B, bool GRAN>
  void particle_stress_row(int len, const double* left_edges, int left_off, const double* right_edges, int right_off,
                           double* buf, std::size_t flen) const;
  template <int D>
  void trace_faces(int k, int len, const double* const* lv, const double* const* rv, const double* al, const double* ar,
                   double* const* fv, double* tbuf, std::size_t flen) const;
  template <int D, ReconMode RM>
  Lagrangian add_intra_cell(const PhaseState<DIM> (&R)[NP], double aR, const double* right_edges, int e,
                            Lagrangian right) const;
  static void store_lagrangian(double* buf, std::size_t flen, int f, const Lagrangian& left, const Lagrangian& right);

  // solver_embedded_faces.h: ghost states, mirrored wall faces, blocked faces, thin bodies.
  void store_ghost_states();
  template <int D>
  void mirror_wall_faces(std::size_t base, int len, double* left_edges, int left_off, double* right_edges,
                         int right_off) const;
  void mirror_edge(const WallFace& wf, const double* from, double* to) const;
  // Eq. 25's extrapolation applies unless the gas converges over the four cells next to a wall face and their
  // pressures differ by more than this fraction of p + p_inf (a shock; solver_embedded_faces.h, methods.md §5.5).
  static constexpr double kWallSmoothPressureSpread = 0.2;
  bool smooth_next_to_wall(const WallFace& wf, int k) const;
  template <int D, ReconMode RM>
  void blocked_face_fluxes(bool high_side, std::size_t base, int len, const double* left_edges, int left_off,
                           const double* right_edges, int right_off, Scratch& sc, double* buf, std::size_t flen);
  template <int D, ReconMode RM>
  void fix_side_edges(std::size_t first, int count, double* edges) const;

  // solver_conservative.h: the wall faces' fluxes (conservative: without mass), the wall exchange account, and
  // the contents of the cells a moving body covers or uncovers.
  void content_per_mass(int k, std::size_t c, double* q) const;
  void wall_face_flux(Scratch& sc, const WallFace& wf, int D, double sign, double area, double* buf, std::size_t flen,
                      int f) const;
  template <int D>
  void wall_face_row(Scratch& sc, std::size_t base, int len, double* buf, std::size_t flen, bool count_low,
                     bool count_high) const;
  void redistribute_changed_cells(EmbeddedState& old, double elapsed);
  void redistribute_by_box(std::vector<std::uint8_t>& before);
  void fluid_volumes();
  void volumes_at(double elapsed);
  void halo_from_blocks(const std::vector<double*>& arrays);
  static constexpr double kMinFluidVolume = 0.5;  // a flow cell's centre is in the fluid: 1/2 for a plane
  void contents_from_densities();
  void contents_to_densities(std::size_t base, int len, bool to_density);
  // A cell's fluid volume over its volume (embedded.conservative), else 1.
  double fluid_volume(std::size_t c) const { return conservative_ && !vfrac_.empty() ? vfrac_[c] : 1.0; }

  // solver_exchange.h: instantaneous relaxations, drag and heat exchange.
  TwoPhaseRow<DIM> two_phase_row(std::size_t base);
  void relax_cells(std::size_t base, int len, bool vrelax, bool prelax);
  template <bool GRAN>
  void relax_cells_as(std::size_t base, int len, bool vrelax, bool prelax);
  void exchange_cells(Scratch& sc, std::size_t base, int len, double dt);
  template <bool DRAG>
  void exchange_row_as(Scratch& sc, std::size_t base, int len, double dt);
  CellState2 load_cell(std::size_t c) const;
  void store_cell(std::size_t c, const CellState2& s);

  FluidScene scene_;
  Grid<DIM> g_;
  eos::StiffenedGas eos_[NP];
  FieldArray U_, U0_, R_, W_;
  std::vector<Scratch> scratch_;
  BoundaryFiller<DIM, NP> bc_;
  BlockLinks* links_ = nullptr;                       // the other blocks of a split mesh (none: the whole mesh)
  std::array<std::array<bool, 2>, 3> domain_edge_{};  // per axis and side: the block's faces there are the domain's
  ReconMode mode_ = ReconMode::VanLeer;
  double t_ = 0.0;
  long steps_ = 0;
  bool primitives_valid_ = false;  // W holds the primitives of U's interior (and primitives_bad_ if one fails)
  bool primitives_bad_ = false;
  EmbeddedState emb_;
  std::array<double, NP*(2 + DIM)> inflow_{}, step_inflow_{};  // boundary_inflow(): since the start, this step
  // embedded_mass_account(): through the walls since the start and this step, with the cells covered or uncovered.
  std::array<double, NP> mass_by_walls_{}, step_wall_mass_{}, mass_by_cells_{};
  // embedded_wall_exchange(): what the wall faces put into the flow cells since the start and this step.
  std::array<double, NP*(2 + DIM)> wall_{}, step_wall_{};
  bool conservative_ = false;    // embedded.conservative (solver_conservative.h)
  bool restored_cells_ = false;  // set_conserved_cells since the last set_embedded
  // Per padded cell: the fluid volume a flow cell stands for over the cell's volume (its own fluid fraction and a
  // share of the fluid in the ghost cells next to it), and scratch for the shares.
  std::vector<double> vfrac_, shares_;
  std::vector<double> vraw_, vrate_;  // the fluid volumes at the geometry's time (unclamped) and their rates [1/s]
  double volumes_elapsed_ = 0.0;      // the time since that geometry's (the steps taken on it)
  // The last geometry's volumes and shares (how many flow cells held each ghost's fluid part); scratch of the
  // redistribution; on a block, the volumes and shares to exchange with the other blocks.
  std::vector<double> vfrac_old_, shares_old_, given_;
  FieldArray halo_;                      // on a block: arrays to take the other blocks' cells of (halo_from_blocks)
  std::vector<std::size_t> halo_cells_;  // and those cells, the other blocks' in the ghost layers
  // Marks of the redistribution in the last geometry's categories (not CellKind values).
  static constexpr std::uint8_t kTaking = 250, kGiven = 251;
  std::array<std::vector<double>, 3> side_values_;  // side ghosts' primitives, kPrim each (fill_side_ghosts)
  std::vector<double> far_send_, far_recv_;         // far cells' primitives to and from the other blocks
  bool wall_second_order_ = true;
  bool profiling_ = false;  // per-pass clocks (set_pass_profiling)
  // Per phase: below this volume fraction the phase is a trace (docs/methods.md §2.7); 2 for a dispersed phase.
  std::array<double, NP> trace_{};
  // A dispersed phase with a granular temperature (docs/methods.md §2.9): the last conservative slot holds its
  // material energy, the last primitive slot its granular energy per unit mass; ncons_ / nprim_ variables in use.
  const bool gran_;
  const int ncons_, nprim_;
};

}  // namespace cosim::fluid

// The member functions of the physics steps.
#include "fluid_solver/core/solver_conservative.h"
#include "fluid_solver/core/solver_embedded_faces.h"
#include "fluid_solver/core/solver_exchange.h"
#include "fluid_solver/core/solver_primitives.h"
#include "fluid_solver/core/solver_reconstruction.h"
#include "fluid_solver/core/solver_stage.h"
#include "fluid_solver/core/solver_state.h"
#include "fluid_solver/core/solver_sweep.h"
#include "fluid_solver/core/solver_two_phase_faces.h"
