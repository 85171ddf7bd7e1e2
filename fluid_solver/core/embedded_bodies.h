// Embedded bodies with prescribed rigid motion (the scene's `fluid.embedded.bodies`): each cycle
// the surface is placed at the current time, the geometry is rebuilt (paper section 6), converted
// to the solver's EmbeddedState and handed over; after the step the surface moves by dt. The wall
// pressure of each face (a rigid body's p_I: the fluid's pressure extrapolated to the wall, as the samples
// of a coupled run) goes with it, for the ghost pressures (ghost_fill.h).
// A decorator around the flow solver: in coupled runs the coupler feeds set_embedded instead.
#pragma once

#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "fluid_solver/core/block_links.h"
#include "fluid_solver/core/embedded_block.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/simulation.h"
#include "fluid_solver/core/wall_faces.h"
#include "fluid_solver/embedded/geometry.h"
#include "fluid_solver/embedded/scene_bodies.h"
#include "fluid_solver/interface/interface_samples.h"
#include "fluid_solver/interface/interface_surface.h"

namespace cosim::fluid {

// The directions in which the scene's domain is periodic (the geometry keeps body faces on those boundaries).
inline std::array<bool, 3> periodic_directions(const FluidScene& s) {
  std::array<bool, 3> p{false, false, false};
  for (int d = 0; d < 3; ++d) p[static_cast<std::size_t>(d)] = s.boundaries[d][0].kind == BoundaryKind::Periodic;
  return p;
}

// The solver's view of one cycle's geometry.
// `wall_normal_speed` (coupled runs): per Surface face, the interface normal velocity u_I . n of the
// coupler (paper eq. 22); it replaces the normal component of the surface velocity at the ghosts'
// boundary intercepts. Null: the surface velocity as it is (prescribed motion).
// `wall_pressure`: per Surface face, 2 values (phase 0, phase 1; NaN: none) of p_I, the coupler's or, for the
// scene's bodies, the fluid's pressure extrapolated to the wall, from which the ghost pressures are
// extrapolated (ghost_fill.h). Null: ghosts copy the image point's pressure.
template <int DIM>
EmbeddedState to_embedded_state(const Grid<DIM>& g, const embedded::Surface& s,
                                const embedded::EmbeddedGeometry<DIM>& geo,
                                const std::vector<double>* wall_normal_speed = nullptr,
                                const std::vector<double>* wall_pressure = nullptr) {
  EmbeddedState e;
  e.active = true;
  e.kind = geo.category;
  // The wall velocity at a point of Surface face `face` with normal n: the surface's, its normal part replaced
  // by the coupler's interface speed when there is one.
  const auto wall_velocity = [&](int face, const embedded::Vec3& n, embedded::Vec3 v) {
    if (wall_normal_speed && face >= 0) {
      const double un = (*wall_normal_speed)[static_cast<std::size_t>(face)];
      const double vn = embedded::dot(v, n);
      for (int d = 0; d < 3; ++d) v[d] += (un - vn) * n[d];
    }
    return v;
  };
  const auto record = [&](const embedded::ImagePoint& ip) {
    GhostRecord r;
    r.cell = ip.cell;
    r.normal = ip.normal;
    r.wall_velocity = wall_velocity(ip.face, ip.normal, ip.wall_velocity);
    if (wall_pressure && ip.face >= 0) {
      for (int k = 0; k < 2; ++k) r.wall_pressure[k] = (*wall_pressure)[2 * static_cast<std::size_t>(ip.face) + k];
      r.has_wall_pressure = std::isfinite(r.wall_pressure[0]);
    }
    r.distance = -ip.phi;
    r.image_distance = ip.image_distance;
    r.stencil_size = ip.stencil_size;
    r.stencil = ip.stencil;
    r.weights = ip.weights;
    return r;
  };
  e.ghosts.reserve(geo.image_points.size());
  for (const auto& ip : geo.image_points) e.ghosts.push_back(record(ip));
  for (const auto& si : geo.side_images)  // sorted by direction, flow cell, side
    e.side_ghosts[static_cast<std::size_t>(si.direction)].push_back(
        SideGhost{record(si.image), si.flow_cell, si.across_high, si.blocked, si.face_distance});
  build_wall_faces<DIM>(g, geo.centres.phi, e);
  orient_wall_faces<DIM>(e, [&](std::size_t cell, std::array<double, 3>& n, std::array<double, 3>& v) {
    const embedded::BandPoint* bp = geo.centres.at(cell);
    if (!bp || bp->face < 0) return false;
    n = bp->normal;
    v = wall_velocity(bp->face, bp->normal, embedded::face_velocity(s, bp->face, bp->bary));
    return true;
  });
  build_thin_body_faces<DIM>(g, e);
  e.blocked_x = !e.blocked[0].empty();
  for (const auto& v : s.velocities) {
    double q = 0;
    for (int d = 0; d < DIM; ++d) q += v[d] * v[d];
    e.max_wall_speed = std::max(e.max_wall_speed, std::sqrt(q));
  }
  return e;
}

// embedded.conservative (docs/methods.md §5.8): e.fluid_fraction per padded cell of g. The fluid fraction of a cell
// whose centre is less than its width along the normal from the surface: that of the plane (1/2 + phi / sum_d |n_d|
// dx_d, exact for a plane along a grid axis); the others are wholly on one side. A pass over every cell: only for a
// conservative boundary.
template <int DIM>
void add_fluid_fractions(const Grid<DIM>& g, const embedded::EmbeddedGeometry<DIM>& geo, EmbeddedState& e) {
  e.fluid_fraction.resize(g.total);
  for (std::size_t c = 0; c < g.total; ++c) {
    const double phi = geo.centres.phi[c];
    double f = phi > 0 ? 1.0 : 0.0;
    if (const embedded::BandPoint* bp = geo.centres.at(c)) {
      double width = 0;
      for (int d = 0; d < DIM; ++d) width += std::abs(bp->normal[d]) * g.dx[d];
      if (width > 0 && std::abs(phi) < width) f = std::clamp(0.5 + phi / width, 0.0, 1.0);
    }
    e.fluid_fraction[c] = f;
  }
}

// The interface segments of one cycle as CSV (FluidSimulation::interface_segments_csv), cells by global index.
// On a block (geometry built on the margin grid E): only the segments of the block's own cells (Grid::owns), in the
// whole mesh's order; the blocks' rows merged by cell are one rank's file (block_io.cpp).
template <int DIM>
std::string segments_csv(const embedded::EmbeddedGeometry<DIM>& geo, const Grid<DIM>* E = nullptr,
                         const Grid<DIM>* block = nullptr) {
  std::string out = "i,j,k,cx,cy,cz,nx,ny,nz,area,vx,vy,vz\n";
  for (const auto& sg : geo.segments) {
    std::array<int, 3> ijk = sg.ijk;
    if (E && block) {
      ijk = E->global_ijk(sg.cell);
      std::size_t p = 0;
      if (!block_cell(*block, ijk, p) || !block->owns(p)) continue;
    }
    out += fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", ijk[0],
                       ijk[1], ijk[2], sg.center[0], sg.center[1], sg.center[2], sg.normal[0], sg.normal[1],
                       sg.normal[2], sg.area, sg.velocity[0], sg.velocity[1], sg.velocity[2]);
  }
  return out;
}

template <int DIM>
class EmbeddedBodiesRun final : public FluidSimulation {
 public:
  // On a block of a split mesh the geometry is built over the block and its margin (embedded_block.h) when every
  // block has its links to the others (start_on_blocks): its far cells come from them.
  EmbeddedBodiesRun(std::unique_ptr<FluidSimulation> inner, const FluidScene& s)
      : inner_(std::move(inner)),
        block_(s.cells, s.lower, s.upper, s.block.first, s.block.whole() ? s.cells : s.block.count),
        g_(block_.whole() ? block_ : margin_grid(block_)),
        surface_(embedded::surface_of(s.embedded, DIM)),
        second_order_(s.embedded.second_order),
        ghost_wall_pressure_(s.embedded.ghost_pressure_from_interface),
        conservative_(s.embedded.conservative),
        at_rest_(std::all_of(surface_.velocities.begin(), surface_.velocities.end(),
                             [](const embedded::Vec3& v) { return v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0; })) {
    opt_.band_cells = s.embedded.band;
    opt_.periodic = periodic_directions(s);
    if (block_.whole()) update();
    else want_block_records(g_, block_, opt_.image);
  }

  const FluidScene& scene() const override { return inner_->scene(); }
  double time() const override { return inner_->time(); }
  long steps() const override { return inner_->steps(); }
  double stable_dt() override { return inner_->stable_dt(); }
  void advance(double dt) override {
    inner_->advance(dt);
    // Bodies at rest without an interface pressure: the geometry, the records and the far cells' plan stay as cut.
    if (at_rest_ && !ghost_wall_pressure_) return;
    embedded::move_surface(surface_, dt);
    update();
  }
  PhaseFields phase_fields(int k) const override { return inner_->phase_fields(k); }
  std::vector<PhaseTotals> totals() const override { return inner_->totals(); }
  std::vector<PhaseTotals> boundary_inflow() const override { return inner_->boundary_inflow(); }
  std::vector<EmbeddedMassAccount> embedded_mass_account() const override { return inner_->embedded_mass_account(); }
  std::vector<PhaseTotals> embedded_wall_exchange() const override { return inner_->embedded_wall_exchange(); }
  void cell_states(const std::size_t* cells, std::size_t count, CellSample* out) const override {
    inner_->cell_states(cells, count, out);
  }
  std::size_t interior_cells() const override { return inner_->interior_cells(); }
  std::vector<double> conserved_cells() const override { return inner_->conserved_cells(); }
  void set_conserved_cells(const std::vector<double>& v) override { inner_->set_conserved_cells(v); }
  int conserved_vars() const override { return inner_->conserved_vars(); }
  std::vector<double> account_values() const override { return inner_->account_values(); }
  void restore_progress(double time, long steps, const std::vector<double>& accounts) override {
    inner_->restore_progress(time, steps, accounts);
  }
  void set_block_links(BlockLinks* links) override {
    inner_->set_block_links(links);
    links_ = links;
  }
  void start_on_blocks() override {
    if (!block_.whole()) update();
  }
  std::size_t state_bytes() const override { return inner_->state_bytes(); }
  double traffic_bytes_per_cell_update() const override { return inner_->traffic_bytes_per_cell_update(); }
  void set_pass_profiling(bool on) override { inner_->set_pass_profiling(on); }
  PassTimes pass_times() const override { return inner_->pass_times(); }
  // The bodies move with the flow's steps: their vertices belong to the state.
  // A conservative boundary's wall pressures too: they were sampled before the step's redistribution, which the
  // saved cells no longer show (without them a restart differs in the last digits).
  void save_state(checkpoint::PartWriter& w) const override {
    inner_->save_state(w);
    w.put("fluid.embedded_vertices", body_state());
    if (conservative_ && ghost_wall_pressure_) w.put("fluid.embedded_wall_pressure", wall_pressure_);
  }
  void restore_state(const checkpoint::PartReader& r) override {
    inner_->restore_state(r);
    restored_wall_pressure_ = conservative_ && ghost_wall_pressure_ && r.has("fluid.embedded_wall_pressure");
    if (restored_wall_pressure_) wall_pressure_ = r.doubles("fluid.embedded_wall_pressure", 2 * surface_.faces.size());
    set_body_state(r.doubles("fluid.embedded_vertices", 3 * surface_.vertices.size()));
    restored_wall_pressure_ = false;
  }
  std::vector<double> body_state() const override {
    std::vector<double> x;
    for (const auto& v : surface_.vertices) x.insert(x.end(), v.begin(), v.end());
    return x;
  }
  void set_body_state(const std::vector<double>& x) override {
    if (x.size() != 3 * surface_.vertices.size())
      throw std::invalid_argument(
          fmt::format("{} body vertex values for {} vertices", x.size(), surface_.vertices.size()));
    for (std::size_t i = 0; i < surface_.vertices.size(); ++i)
      surface_.vertices[i] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    update();
  }
  void set_embedded(EmbeddedState st, bool second_order) override { inner_->set_embedded(std::move(st), second_order); }
  const EmbeddedState& embedded() const override { return inner_->embedded(); }
  std::vector<double> embedded_categories() const override { return inner_->embedded_categories(); }
  double geometry_seconds() const { return geometry_seconds_; }
  std::string interface_segments_csv() const override {
    return block_.whole() ? segments_csv(geo_) : segments_csv(geo_, &g_, &block_);
  }

 private:
  // Geometry of the surface at the current time -> the solver (throws for thin bodies etc.).
  void update() {
    const auto t0 = std::chrono::steady_clock::now();
    if (!block_.whole()) {
      update_block();
    } else {
      embedded::build_geometry<DIM>(g_, surface_, opt_, geo_);
      if (ghost_wall_pressure_ && !restored_wall_pressure_) {  // a rigid body's p_I: the fluid's pressure at its wall
        const coupling::FluidSamples smp =
            interface::sample_interface<DIM>(g_, geo_.category, *inner_, interface::faces_of_surface(surface_));
        wall_pressure_ = interface::wall_pressure_slots(smp, smp.pressure, inner_->scene().exchange.dispersed);
      }
      EmbeddedState st =
          to_embedded_state<DIM>(g_, surface_, geo_, nullptr, ghost_wall_pressure_ ? &wall_pressure_ : nullptr);
      if (conservative_) add_fluid_fractions<DIM>(g_, geo_, st);
      st.own_ghosts = st.ghosts.size();
      inner_->set_embedded(std::move(st), second_order_);
    }
    geometry_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  // The same on a block: the geometry over the margin grid, the wall pressure samples with the cells of other blocks
  // they read, the records restricted to the block with its far cells. The blocks agree on a failure before each
  // exchange (no block waits in one for a block that failed).
  void update_block() {
    const auto agree = [&](const std::string& error) {
      if (links_->any(!error.empty()))
        throw std::runtime_error(error.empty() ? "another block could not build its embedded geometry" : error);
    };
    std::string error;
    try {
      embedded::build_geometry<DIM>(g_, surface_, opt_, geo_);
      if (ghost_wall_pressure_) plan_samples();
    } catch (const std::exception& e) { error = e.what(); }
    agree(error);
    if (ghost_wall_pressure_) exchange_samples();
    std::vector<std::array<int, 3>> far;
    EmbeddedState st;
    try {
      if (ghost_wall_pressure_) {
        const coupling::FluidSamples smp = interface::sample_faces<DIM>(
            block_, [&](const std::array<int, 3>& c) { return is_flow_cell(geo_.category[margin_index(c)]); },
            [&](const std::array<int, 3>* c, int count, CellSample* out) { sample_states(c, count, out); },
            inner_->scene(), faces_, &sampled_faces_);
        wall_pressure_ = interface::wall_pressure_slots(smp, smp.pressure, inner_->scene().exchange.dispersed);
      }
      const EmbeddedState ext =
          to_embedded_state<DIM>(g_, surface_, geo_, nullptr, ghost_wall_pressure_ ? &wall_pressure_ : nullptr);
      st = restrict_to_block<DIM>(ext, g_, block_, far);
    } catch (const std::exception& e) { error = e.what(); }
    agree(error);
    // The x rows take the blocked-face path wherever the whole mesh has a blocked face along x (solver_sweep.h):
    // the same sums in the same order as on one rank, also on a block that has none.
    st.blocked_x = links_->any(!st.blocked[0].empty());
    links_->plan_far(0, far);
    inner_->set_embedded(std::move(st), second_order_);
  }

  // The padded index in the margin grid of global cell c; a cell beyond it is an error (embedded/reach.h).
  std::size_t margin_index(const std::array<int, 3>& c) const {
    std::array<int, 3> l{0, 0, 0};
    for (int d = 0; d < DIM; ++d) {
      l[d] = c[d] - g_.first[d];
      if (l[d] < -Grid<DIM>::NG || l[d] >= g_.n[d] + Grid<DIM>::NG)
        throw embedded::ReachError(fmt::format(
            "embedded geometry: a wall pressure sample reads cell {} along axis {}, beyond the cells [{}, {}) this "
            "block's geometry holds (fluid_solver/embedded/reach.h)",
            c[d], d, g_.first[d] - Grid<DIM>::NG, g_.first[d] + g_.n[d] + Grid<DIM>::NG));
    }
    return g_.index(l[0], l[1], l[2]);
  }
  bool interior(const std::array<int, 3>& c) const {
    for (int d = 0; d < DIM; ++d)
      if (c[d] < block_.first[d] || c[d] >= block_.first[d] + block_.n[d]) return false;
    return true;
  }
  static bool mesh_order(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return a[2] != b[2] ? a[2] < b[2] : a[1] != b[1] ? a[1] < b[1] : a[0] < b[0];
  }

  // The faces the block's records name and every cell their samples may read beyond the block's cells.
  void plan_samples() {
    faces_ = interface::faces_of_surface(surface_);
    sampled_faces_.assign(static_cast<std::size_t>(faces_.count), 0);
    for (const auto& ip : geo_.image_points)
      if (ip.face >= 0) sampled_faces_[static_cast<std::size_t>(ip.face)] = 1;
    for (const auto& si : geo_.side_images)
      if (si.image.face >= 0) sampled_faces_[static_cast<std::size_t>(si.image.face)] = 1;
    sample_far_.clear();
    std::array<std::array<int, 3>, 1 << DIM> cells{};
    std::array<double, 1 << DIM> w{};
    for (int f = 0; f < faces_.count; ++f)
      if (sampled_faces_[static_cast<std::size_t>(f)])
        interface::sample_points<DIM>(block_, faces_, f, interface::SampleOptions{},
                                      [&](const std::array<double, 3>& x) {
                                        interface::sample_stencil<DIM>(block_, x, cells, w);
                                        for (const auto& c : cells)
                                          if (!interior(c)) sample_far_.push_back(c);
                                      });
    std::sort(sample_far_.begin(), sample_far_.end(), mesh_order);
    sample_far_.erase(std::unique(sample_far_.begin(), sample_far_.end()), sample_far_.end());
  }

  // The states of the sampled cells of other blocks (channel 1), and those of this block's cells they asked for.
  void exchange_samples() {
    const std::vector<std::size_t>& send = links_->plan_far(1, sample_far_);
    const int np = inner_->scene().num_phases();
    constexpr int kPerPhase = 8;  // CellSample: alpha, rho, p, c, velocity[3], granular
    std::vector<CellSample> st(static_cast<std::size_t>(np));
    std::vector<double> out(send.size() * kPerPhase * np);
    for (std::size_t i = 0; i < send.size(); ++i) {
      inner_->cell_states(&send[i], 1, st.data());
      for (int k = 0; k < np; ++k) {
        const CellSample& c = st[static_cast<std::size_t>(k)];
        double* o = out.data() + (i * np + k) * kPerPhase;
        o[0] = c.alpha, o[1] = c.rho, o[2] = c.p, o[3] = c.c;
        o[4] = c.velocity[0], o[5] = c.velocity[1], o[6] = c.velocity[2], o[7] = c.granular;
      }
    }
    sample_values_.resize(sample_far_.size() * kPerPhase * np);
    links_->exchange_far(1, out.data(), sample_values_.data(), kPerPhase * np);
  }

  // States of global cells for the samples: the block's own, or those exchange_samples brought.
  void sample_states(const std::array<int, 3>* c, int count, CellSample* out) const {
    const int np = inner_->scene().num_phases();
    for (int q = 0; q < count; ++q) {
      CellSample* o = out + static_cast<std::ptrdiff_t>(q) * np;
      if (interior(c[q])) {
        const std::size_t idx =
            block_.index(c[q][0] - block_.first[0], c[q][1] - block_.first[1], c[q][2] - block_.first[2]);
        inner_->cell_states(&idx, 1, o);
        continue;
      }
      const auto it = std::lower_bound(sample_far_.begin(), sample_far_.end(), c[q], mesh_order);
      if (it == sample_far_.end() || *it != c[q])
        throw std::logic_error("embedded geometry: a wall pressure sample reads a cell it did not ask for");
      const double* v = sample_values_.data() + static_cast<std::size_t>(it - sample_far_.begin()) * 8 * np;
      for (int k = 0; k < np; ++k, v += 8) {
        o[k].alpha = v[0], o[k].rho = v[1], o[k].p = v[2], o[k].c = v[3];
        o[k].velocity = {v[4], v[5], v[6]};
        o[k].granular = v[7];
      }
    }
  }

  std::unique_ptr<FluidSimulation> inner_;
  Grid<DIM> block_;  // the solver's cells (the whole mesh on one rank)
  Grid<DIM> g_;      // the geometry's: the whole mesh, or the block and its margin (margin_grid)
  BlockLinks* links_ = nullptr;
  coupling::Faces faces_;                       // a block's: the surface's faces, those it samples
  std::vector<char> sampled_faces_;             // and which of them its records name
  std::vector<std::array<int, 3>> sample_far_;  // cells of other blocks their samples read (mesh order)
  std::vector<double> sample_values_;           // and their states (8 values per phase)
  embedded::Surface surface_;
  embedded::GeometryOptions opt_;
  embedded::EmbeddedGeometry<DIM> geo_;
  bool second_order_;
  bool ghost_wall_pressure_;
  bool conservative_;                    // embedded.conservative: the cells' fluid fractions with each geometry
  bool at_rest_;                         // every vertex at rest: the geometry is cut once
  bool restored_wall_pressure_ = false;  // wall_pressure_ from a checkpoint set, for the restart's first geometry
  std::vector<double> wall_pressure_;    // per Surface face, 2 slots (phases); NaN: not wetted
  double geometry_seconds_ = 0;
};

}  // namespace cosim::fluid
