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

#include "fluid_solver/core/block_geometry.h"
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

// The wall velocity and wall pressure of each wall source (set_wall_values).
// `wall_normal_speed` (coupled runs): per Surface face, the interface normal velocity u_I . n of the
// coupler (paper eq. 22); it replaces the normal component of the surface velocity at the source. Null: the surface
// velocity as it is (prescribed motion).
// `wall_pressure`: per Surface face, 2 values (phase 0, phase 1; NaN: none) of p_I, the coupler's or, for the
// scene's bodies, the fluid's pressure extrapolated to the wall, from which the ghost pressures are
// extrapolated (ghost_fill.h). Null: ghosts copy the image point's pressure.
inline std::vector<WallValue> wall_values(const std::vector<WallSource>& sources,
                                          const std::vector<double>* wall_normal_speed = nullptr,
                                          const std::vector<double>* wall_pressure = nullptr) {
  std::vector<WallValue> out(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const WallSource& w = sources[i];
    WallValue& v = out[i];
    v.velocity = w.velocity;
    if (w.face < 0) continue;
    const auto f = static_cast<std::size_t>(w.face);
    if (wall_normal_speed) {
      const double un = (*wall_normal_speed)[f];
      const double vn = embedded::dot(w.velocity, w.normal);
      for (int d = 0; d < 3; ++d) v.velocity[d] += (un - vn) * w.normal[d];
    }
    if (wall_pressure) {
      for (int k = 0; k < 2; ++k) v.pressure[k] = (*wall_pressure)[2 * f + k];
      v.has_pressure = std::isfinite(v.pressure[0]);
    }
  }
  return out;
}

// The solver's view of one cycle's geometry, its wall velocities and pressures those of wall_values (one wall source
// per surface point they are taken at: e.wall_sources, which set_embedded_walls sets again in place).
template <int DIM>
EmbeddedState to_embedded_state(const Grid<DIM>& g, const embedded::Surface& s,
                                const embedded::EmbeddedGeometry<DIM>& geo,
                                const std::vector<double>* wall_normal_speed = nullptr,
                                const std::vector<double>* wall_pressure = nullptr) {
  EmbeddedState e;
  e.active = true;
  e.kind = geo.category;
  const auto source = [&](int face, const embedded::Vec3& n, const embedded::Vec3& v) {
    e.wall_sources.push_back(WallSource{face, n, v});
    return static_cast<int>(e.wall_sources.size() - 1);
  };
  const auto record = [&](const embedded::ImagePoint& ip) {
    GhostRecord r;
    r.cell = ip.cell;
    r.normal = ip.normal;
    r.wall = source(ip.face, ip.normal, ip.wall_velocity);
    r.distance = -ip.phi;
    r.image_distance = ip.image_distance;
    r.stencil_size = ip.stencil_size;
    r.stencil = ip.stencil;
    r.weights = ip.weights;
    return r;
  };
  e.wall_sources.reserve(geo.image_points.size() + geo.side_images.size());
  e.ghosts.reserve(geo.image_points.size());
  for (const auto& ip : geo.image_points) e.ghosts.push_back(record(ip));
  for (const auto& si : geo.side_images)  // sorted by direction, flow cell, side
    e.side_ghosts[static_cast<std::size_t>(si.direction)].push_back(
        SideGhost{record(si.image), si.flow_cell, si.across_high, si.blocked, si.face_distance});
  build_wall_faces<DIM>(g, geo.centres.phi, e);
  orient_wall_faces<DIM>(
      e,
      [&](std::size_t cell, std::array<double, 3>& n) {
        const embedded::BandPoint* bp = geo.centres.at(cell);
        if (!bp || bp->face < 0) return false;
        n = bp->normal;
        return true;
      },
      [&](std::size_t cell) {
        const embedded::BandPoint* bp = geo.centres.at(cell);
        return source(bp->face, bp->normal, embedded::face_velocity(s, bp->face, bp->bary));
      });
  build_thin_body_faces<DIM>(g, e);
  set_wall_values(e, wall_values(e.wall_sources, wall_normal_speed, wall_pressure));
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
// dx_d, exact for a plane along a grid axis); the others are wholly on one side. With it the rate at which the
// surface's motion changes it (e.fluid_fraction_rate, only where a wall moves). A pass over every cell: only for a
// conservative boundary.
template <int DIM>
void add_fluid_fractions(const Grid<DIM>& g, const embedded::Surface& s, const embedded::EmbeddedGeometry<DIM>& geo,
                         EmbeddedState& e) {
  e.fluid_fraction.resize(g.total);
  bool moving = false;
  for (const embedded::Vec3& v : s.velocities) moving = moving || v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0;
  if (moving) e.fluid_fraction_rate.assign(g.total, 0.0);
  else e.fluid_fraction_rate.clear();
  for (std::size_t c = 0; c < g.total; ++c) {
    const double phi = geo.centres.phi[c];
    double f = phi > 0 ? 1.0 : 0.0;
    if (const embedded::BandPoint* bp = geo.centres.at(c)) {
      double width = 0;
      for (int d = 0; d < DIM; ++d) width += std::abs(bp->normal[d]) * g.dx[d];
      if (width > 0 && std::abs(phi) < width) {
        const double plane = 0.5 + phi / width;
        f = std::clamp(plane, 0.0, 1.0);
        // d phi / dt = -u . n at a fixed point (n: solid -> fluid), while the plane cuts the cell.
        if (moving && plane > 0.0 && plane < 1.0 && bp->face >= 0)
          e.fluid_fraction_rate[c] = -embedded::dot(embedded::face_velocity(s, bp->face, bp->bary), bp->normal) / width;
      }
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
        g_(block_),
        surface_(embedded::surface_of(s.embedded, DIM)),
        second_order_(s.embedded.second_order),
        ghost_wall_pressure_(s.embedded.ghost_pressure_from_interface),
        conservative_(s.embedded.conservative),
        at_rest_(std::all_of(surface_.velocities.begin(), surface_.velocities.end(),
                             [](const embedded::Vec3& v) { return v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0; })) {
    opt_.band_cells = s.embedded.band;
    opt_.periodic = periodic_directions(s);
    if (block_.whole()) update();
    else on_block_ = std::make_unique<BlockGeometry<DIM>>(block_, opt_);
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
    if (on_block_) on_block_->set_links(links);
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
  std::vector<double> embedded_wall_pressure() const override {
    return conservative_ && ghost_wall_pressure_ ? wall_pressure_ : std::vector<double>{};
  }
  void set_embedded_wall_pressure(const std::vector<double>& slots) override {
    if (!conservative_ || !ghost_wall_pressure_) return;
    if (slots.size() != 2 * surface_.faces.size())
      throw std::invalid_argument(
          fmt::format("{} embedded wall pressure values for {} surface faces", slots.size(), surface_.faces.size()));
    wall_pressure_ = slots;
    restored_wall_pressure_ = true;  // for the next geometry (set_body_state's)
  }
  void set_embedded(EmbeddedState st, bool second_order) override { inner_->set_embedded(std::move(st), second_order); }
  void set_embedded_walls(const std::vector<WallValue>& values) override { inner_->set_embedded_walls(values); }
  void set_embedded_elapsed(double elapsed) override { inner_->set_embedded_elapsed(elapsed); }
  const EmbeddedState& embedded() const override { return inner_->embedded(); }
  std::vector<double> embedded_categories() const override { return inner_->embedded_categories(); }
  double geometry_seconds() const { return geometry_seconds_; }
  std::string interface_segments_csv() const override {
    return on_block_ ? segments_csv(on_block_->geometry(), &on_block_->grid(), &block_) : segments_csv(geo_);
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
      if (conservative_) add_fluid_fractions<DIM>(g_, surface_, geo_, st);
      st.own_ghosts = st.ghosts.size();
      inner_->set_embedded(std::move(st), second_order_);
    }
    restored_wall_pressure_ = false;  // a restart's first geometry took them
    geometry_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  // The same on a block: the geometry over the margin grid, the wall pressure samples of the faces the block's records
  // name, with the cells of other blocks they read, the records restricted to the block with its far cells.
  void update_block() {
    if (ghost_wall_pressure_) faces_ = interface::faces_of_surface(surface_);
    on_block_->cut(surface_, ghost_wall_pressure_ ? &faces_ : nullptr, [&](const embedded::EmbeddedGeometry<DIM>& geo) {
      std::vector<char> named(static_cast<std::size_t>(faces_.count), 0);
      for (const auto& ip : geo.image_points)
        if (ip.face >= 0) named[static_cast<std::size_t>(ip.face)] = 1;
      for (const auto& si : geo.side_images)
        if (si.image.face >= 0) named[static_cast<std::size_t>(si.image.face)] = 1;
      return named;
    });
    if (ghost_wall_pressure_ && !restored_wall_pressure_) {
      coupling::FluidSamples smp = on_block_->samples(*inner_);
      // Conservative: every block's samples on every block, the whole surface's wall pressures as one rank's for a
      // checkpoint (a face that two blocks sample has the same sample on both).
      if (conservative_) smp = on_block_->merge_samples(smp, on_block_->sampled());
      wall_pressure_ = interface::wall_pressure_slots(smp, smp.pressure, inner_->scene().exchange.dispersed);
    }
    inner_->set_embedded(on_block_->state([&](const Grid<DIM>& g, const embedded::EmbeddedGeometry<DIM>& geo) {
      EmbeddedState st =
          to_embedded_state<DIM>(g, surface_, geo, nullptr, ghost_wall_pressure_ ? &wall_pressure_ : nullptr);
      if (conservative_) add_fluid_fractions<DIM>(g, surface_, geo, st);  // over the margin grid
      return st;
    }),
                         second_order_);
  }

  std::unique_ptr<FluidSimulation> inner_;
  Grid<DIM> block_;                               // the solver's cells (the whole mesh on one rank)
  Grid<DIM> g_;                                   // the geometry's on the whole mesh
  std::unique_ptr<BlockGeometry<DIM>> on_block_;  // on a block of a split mesh: the geometry there
  coupling::Faces faces_;                         // a block's: the surface's faces
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
