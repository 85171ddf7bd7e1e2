#include "fluid_solver/coupled/coupled_boundary.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "common/coupling/wire.h"
#include "fluid_solver/core/block_geometry.h"
#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/embedded/geometry.h"
#include "fluid_solver/interface/interface_samples.h"
#include "fluid_solver/interface/interface_surface.h"

namespace cosim::fluid::coupled {

namespace {

using interface::InterfaceSurface;
using interface::sample_interface;
using interface::surface_from_faces;
using interface::wall_pressure_slots;

template <int DIM>
class CoupledBoundaryImpl final : public CoupledBoundary {
 public:
  explicit CoupledBoundaryImpl(FluidSimulation& sim)
      : sim_(sim),
        g_(sim.scene().cells, sim.scene().lower, sim.scene().upper),
        second_order_(sim.scene().embedded.second_order),
        ghost_wall_pressure_(sim.scene().embedded.ghost_pressure_from_interface) {
    const FluidScene& s = sim.scene();
    opt_.band_cells = s.embedded.band;
    opt_.periodic = periodic_directions(s);
    if (!block_grid().whole()) on_block_ = std::make_unique<BlockGeometry<DIM>>(block_grid(), opt_);
  }

  void set_block_links(BlockLinks* links) override {
    if (on_block_) on_block_->set_links(links);
  }

  coupling::FluidSamples receive_faces(const coupling::Faces& faces, double dt) override {
    build(faces, dt);
    // embedded.conservative: the cells hold contents, and a content's density is over the fluid volume of the
    // geometry it belongs to. The state is at t^n, where the new faces place the body, so the solver takes this
    // geometry's volumes (and the cells it covered or uncovered) before the samples read the cells; the states'
    // wall velocities follow in apply_states. Sampled over the last cycle's volumes, a wall cell's pressure lagged
    // by one step's wall motion (p dV / V: +1.8% at 15 m/s, 160 cells) and pumped energy into the piston.
    // On blocks the same from the block's geometry (its margin grid), every block together.
    if (sim_.scene().embedded.conservative) {
      set_state(nullptr, nullptr);
      state_set_ = true;
    }
    interface::SampleOptions so;
    so.extrapolate_velocity = wall_velocity_;
    // On blocks: each face sampled by the block holding its centre, the samples merged on every block.
    if (on_block_) samples_ = on_block_->merge_samples(on_block_->samples(sim_, so), owned_);
    else samples_ = sample_interface<DIM>(g_, geo_.category, sim_, faces, so);
    return samples_;
  }

  // The cycle's faces, samples and states, as protocol messages: enough to set the same embedded boundary again.
  void save(checkpoint::PartWriter& w) const override {
    coupling::pb::InterfaceFaces f;
    coupling::to_pb(faces_, f);
    coupling::pb::FluidSamples m;
    coupling::to_pb(samples_, m);
    coupling::pb::InterfaceStates st;
    coupling::to_pb(states_, st);
    w.put_text("boundary.faces", f.SerializeAsString());
    w.put_text("boundary.samples", m.SerializeAsString());
    w.put_text("boundary.states", st.SerializeAsString());
    w.put_scalar("boundary.dt", dt_);
  }

  void restore(const checkpoint::PartReader& r) override {
    coupling::pb::InterfaceFaces f;
    coupling::pb::FluidSamples m;
    coupling::pb::InterfaceStates st;
    if (!f.ParseFromString(r.text("boundary.faces")) || !m.ParseFromString(r.text("boundary.samples")) ||
        !st.ParseFromString(r.text("boundary.states")))
      throw std::runtime_error(r.path().string() + ": the embedded boundary's messages cannot be read");
    build(coupling::from_pb(f), r.scalar("boundary.dt"));
    samples_ = coupling::from_pb(m);
    apply_states(coupling::from_pb(st));
    sim_.set_embedded_elapsed(dt_);  // the saved cells are after the cycle's step on this geometry
  }

  // The embedded geometry of the faces at t^{n+1}, placed back at t^n.
  void build(const coupling::Faces& faces, double dt) {
    faces_ = faces;
    dt_ = dt;
    const auto t0 = std::chrono::steady_clock::now();
    surface_ = surface_from_faces(faces, DIM, dt);
    if (on_block_) {
      owned_ = on_block_->faces_centred_here(faces);
      on_block_->cut(surface_.surface, &faces, [&](const embedded::EmbeddedGeometry<DIM>&) { return owned_; });
    } else {
      embedded::build_geometry<DIM>(g_, surface_.surface, opt_, geo_);
    }
    geometry_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state_set_ = false;
  }

  // The solver's state of the geometry built last, with the wall speeds and pressures per surface face (null: the
  // surface's velocity, no wall pressure) and, for a conservative boundary, the cells' fluid fractions. On blocks
  // from the block's geometry (its margin grid), every block together.
  void set_state(const std::vector<double>* speed, const std::vector<double>* pressure) {
    const auto records = [&](const Grid<DIM>& g, const embedded::EmbeddedGeometry<DIM>& geo) {
      EmbeddedState es = to_embedded_state<DIM>(g, surface_.surface, geo, speed, pressure);
      if (sim_.scene().embedded.conservative) add_fluid_fractions<DIM>(g, surface_.surface, geo, es);
      return es;
    };
    sim_.set_embedded(on_block_ ? on_block_->state(records) : records(g_, geo_), second_order_);
  }

  void apply_states(const coupling::InterfaceStates& st) override {
    states_ = st;
    const int np = samples_.phases;
    if (st.count != samples_.count)
      throw std::invalid_argument(
          fmt::format("InterfaceStates.count = {} but this cycle has {} faces", st.count, samples_.count));
    if (st.phases != np)
      throw std::invalid_argument(fmt::format("InterfaceStates.phases = {} but the fluid has {}", st.phases, np));
    const std::size_t m = static_cast<std::size_t>(st.count) * np;
    if (st.normal_velocity.size() != m || st.pressure.size() != m)
      throw std::invalid_argument(fmt::format("InterfaceStates: {} pressures and {} normal velocities, expected {}",
                                              st.pressure.size(), st.normal_velocity.size(), m));
    // One wall velocity per face: the phases' interface velocities weighted by their volume fractions.
    face_speed_.assign(static_cast<std::size_t>(st.count), 0.0);
    for (int f = 0; f < st.count; ++f) {
      double a = 0, u = 0;
      for (int k = 0; k < np; ++k) {
        const std::size_t i = static_cast<std::size_t>(f) * np + k;
        const double ak = samples_.wetted[f] ? samples_.alpha[i] : 1.0;
        a += ak;
        u += ak * st.normal_velocity[i];
      }
      face_speed_[f] = a > 0 ? u / a : 0.0;
    }
    const std::vector<double> face_pressure =
        wall_pressure_slots(samples_, st.pressure, sim_.scene().exchange.dispersed);
    surface_speed_.resize(surface_.source_face.size());
    surface_pressure_.resize(2 * surface_.source_face.size());
    for (std::size_t sf = 0; sf < surface_.source_face.size(); ++sf) {
      const auto f = static_cast<std::size_t>(surface_.source_face[sf]);
      surface_speed_[sf] = face_speed_[f];
      surface_pressure_[2 * sf] = face_pressure[2 * f];
      surface_pressure_[2 * sf + 1] = face_pressure[2 * f + 1];
    }
    const std::vector<double>* pressure = ghost_wall_pressure_ ? &surface_pressure_ : nullptr;
    // The geometry's state set in receive_faces (conservative): only its wall velocities and pressures change, in
    // place (the same values as a new state's); otherwise (a non-conservative cycle, a restored one) the state with
    // them.
    if (state_set_) sim_.set_embedded_walls(wall_values(sim_.embedded().wall_sources, &surface_speed_, pressure));
    else set_state(&surface_speed_, pressure);
  }

  std::string segments_csv() const override {
    if (!on_block_) return fluid::segments_csv<DIM>(geo_);
    const Grid<DIM> block = block_grid();
    return fluid::segments_csv<DIM>(on_block_->geometry(), &on_block_->grid(), &block);
  }
  double geometry_seconds() const override { return geometry_seconds_; }

 private:
  Grid<DIM> block_grid() const {
    const FluidScene& s = sim_.scene();
    return Grid<DIM>(s.cells, s.lower, s.upper, s.block.first, s.block.whole() ? s.cells : s.block.count);
  }
  FluidSimulation& sim_;
  Grid<DIM> g_;
  bool second_order_;
  bool ghost_wall_pressure_;
  embedded::GeometryOptions opt_;
  embedded::EmbeddedGeometry<DIM> geo_;           // on the whole mesh
  std::unique_ptr<BlockGeometry<DIM>> on_block_;  // on a block of a split mesh: the geometry there
  std::vector<char> owned_;                       // and the faces centred in the block (those it samples)
  InterfaceSurface surface_;
  coupling::FluidSamples samples_;
  coupling::Faces faces_;  // of this cycle, with its step and states: what a checkpoint keeps
  coupling::InterfaceStates states_;
  double dt_ = 0;
  bool state_set_ = false;  // receive_faces gave the solver the state of the geometry built last
  std::vector<double> face_speed_, surface_speed_, surface_pressure_;
  double geometry_seconds_ = 0;
};

}  // namespace

void check_structure_inside_domain(const FluidScene& sc, const coupling::Faces& faces) {
  const int d = faces.dim;
  const bool vertices = faces.nodes_per_face > 0;
  const std::size_t n = vertices ? faces.vertex_position.size() / d : static_cast<std::size_t>(faces.count);
  for (std::size_t v = 0; v < n; ++v)
    for (int c = 0; c < std::min(d, sc.dim); ++c) {
      const double x = vertices ? faces.vertex_position[v * d + c] : faces.centre[v * d + c];
      const double lo = sc.lower[c], hi = sc.upper[c], tol = 1e-9 * (hi - lo);
      if (x < lo - tol || x > hi + tol)
        throw std::invalid_argument(fmt::format(
            "the structure reaches outside the fluid domain: {} {} of the solid's interface is at {} = {:.9g} m, "
            "outside fluid.mesh [{:.9g}, {:.9g}] m (place solid.mesh inside fluid.mesh.lower/upper; faces on the "
            "domain boundary are fine)",
            vertices ? "vertex" : "face", v, "xyz"[c], x, lo, hi));
    }
}

std::unique_ptr<CoupledBoundary> make_coupled_boundary(FluidSimulation& sim) {
  switch (sim.scene().dim) {
    case 1: return std::make_unique<CoupledBoundaryImpl<1>>(sim);
    case 2: return std::make_unique<CoupledBoundaryImpl<2>>(sim);
    case 3: return std::make_unique<CoupledBoundaryImpl<3>>(sim);
    default: throw std::invalid_argument(fmt::format("a fluid grid of dimension {}", sim.scene().dim));
  }
}

}  // namespace cosim::fluid::coupled
