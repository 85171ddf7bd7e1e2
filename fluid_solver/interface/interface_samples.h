// The fluid state next to each interface face, per phase (paper section 8, step 2, fluid half; the
// input of the coupler's interface conditions, eqs. 21-22): alpha, rho, u . n, p and z = rho c.
//
// Sample point: the face centre moved out along the face normal by one cell (h = sum_d |n_d| dx_d),
// where the (bi/tri)linear stencil of the cell centres around it is evaluated over the flow cells
// (fluid / fluid-cut) only, their weights renormalised. A point whose flow cells carry less than half
// the weight is pushed out by another h (at most twice). The pressure is extrapolated linearly to the
// wall from that point and one more h out: next to a moving wall the gas accelerates, and its pressure
// gradient rho a would bias the load by rho a h (piston_2d: 0.27% -> 0.08% from the reference trajectory),
// and optionally the normal velocity (coupling.mode robin), kept between the point's and the wall's. The
// other values are the point's. A face is not wetted (no load, no state) when
// its sample point leaves the fluid domain or finds no flow cells: e.g. the parts of a solid that
// reach outside the background mesh.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "common/coupling/types.h"
#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/core/grid.h"
#include "fluid_solver/core/simulation.h"

namespace cosim::fluid::interface {

struct SampleOptions {
  double min_flow_weight = 0.5;
  int max_pushes = 2;                 // embedded::kMaxImagePushes (the reach of a block's geometry, embedded/reach.h)
  bool extrapolate_pressure = true;   // pressure extrapolated linearly to the wall from two points
  bool extrapolate_velocity = false;  // and the normal velocity with it (where the pressure's extrapolation holds)
};

// The (bi/tri)linear stencil of the interior cell centres of the whole mesh around x (clamped to its interior
// cells): global cell indices and plain weights. g: the mesh's origin, spacing and cell counts (Grid::mesh); a block's
// grid gives the same stencil as the whole mesh's.
template <int DIM>
void sample_stencil(const Grid<DIM>& g, const std::array<double, 3>& x, std::array<std::array<int, 3>, 1 << DIM>& cells,
                    std::array<double, 1 << DIM>& w) {
  std::array<int, 3> base{0, 0, 0};
  std::array<double, 3> t{0, 0, 0};
  for (int d = 0; d < DIM; ++d) {  // cell-centre lattice, clamped to the interior cells
    const double u = std::clamp((x[d] - g.lower[d]) / g.dx[d] - 0.5, 0.0, g.mesh[d] - 1.0);
    base[d] = std::min(static_cast<int>(u), std::max(g.mesh[d] - 2, 0));
    t[d] = g.mesh[d] > 1 ? u - base[d] : 0.0;
  }
  for (int k = 0; k < (1 << DIM); ++k) {
    std::array<int, 3> ijk{0, 0, 0};
    double wk = 1;
    for (int d = 0; d < DIM; ++d) {
      const int bit = (k >> d) & 1;
      ijk[d] = std::min(base[d] + bit, g.mesh[d] - 1);
      wk *= bit ? t[d] : 1.0 - t[d];
    }
    cells[k] = ijk;
    w[k] = wk;
  }
}

// The points a face's samples may be taken at (sample_faces below): the face centre out along the normal by
// (1 + push) h and one h more, while inside the mesh; visit(x) for each.
template <int DIM, class Visit>
void sample_points(const Grid<DIM>& g, const coupling::Faces& faces, int f, const SampleOptions& opt, Visit&& visit) {
  std::array<double, 3> c{0, 0, 0}, n{0, 0, 0};
  double h = 0;
  for (int d = 0; d < DIM; ++d) {
    c[d] = faces.centre[static_cast<std::size_t>(f) * DIM + d];
    n[d] = faces.normal[static_cast<std::size_t>(f) * DIM + d];
    h += std::abs(n[d]) * g.dx[d];
  }
  const auto inside = [&](const std::array<double, 3>& x) {
    for (int d = 0; d < DIM; ++d)
      if (x[d] < g.lower[d] || x[d] > g.lower[d] + g.mesh[d] * g.dx[d]) return false;
    return true;
  };
  for (int push = 0; push <= opt.max_pushes; ++push) {
    const double s1 = (1.0 + push) * h;
    std::array<double, 3> x{0, 0, 0}, x2{0, 0, 0};
    for (int d = 0; d < DIM; ++d) {
      x[d] = c[d] + s1 * n[d];
      x2[d] = c[d] + (s1 + h) * n[d];
    }
    if (!inside(x)) return;
    visit(x);
    if (inside(x2)) visit(x2);
  }
}

// The samples of the faces (those with only[f] != 0 when `only` is given; the others are not wetted), from the cells
// of the whole mesh: flow(ijk) says whether global cell ijk is a flow cell, states(ijk, count, out) gives the states
// of `count` global cells (np per cell). On a block these come from its own cells and those the other blocks sent.
template <int DIM, class Flow, class States>
coupling::FluidSamples sample_faces(const Grid<DIM>& g, const Flow& flow_cell, const States& cell_states,
                                    const FluidScene& scene, const coupling::Faces& faces,
                                    const std::vector<char>* only, const SampleOptions& opt = {}) {
  constexpr int NS = 1 << DIM;
  const int np = scene.num_phases();
  const bool dispersed = scene.exchange.dispersed;
  const ParticleStress& stress = scene.exchange.particle_stress;
  const GranularGas& granular = scene.exchange.granular;
  coupling::FluidSamples out;
  out.count = faces.count;
  out.phases = np;
  const std::size_t m = static_cast<std::size_t>(faces.count) * np;
  out.alpha.assign(m, 0.0);
  out.rho.assign(m, 0.0);
  out.normal_velocity.assign(m, 0.0);
  out.pressure.assign(m, 0.0);
  out.impedance.assign(m, 0.0);
  out.wetted.assign(faces.count, 0);
  std::array<std::array<int, 3>, NS> cells{};
  std::array<double, NS> w{};
  std::vector<CellSample> states(static_cast<std::size_t>(NS) * np);
  // Per phase at point x: alpha, rho, u . n, p, c from the flow cells of the stencil; false when they carry
  // less than min_flow_weight of it.
  struct Values {
    double a, rho, un, p, c, k;
  };
  std::vector<Values> vals(static_cast<std::size_t>(np)), far(static_cast<std::size_t>(np));
  const auto evaluate = [&](const std::array<double, 3>& x, const std::array<double, 3>& n, std::vector<Values>& v) {
    sample_stencil<DIM>(g, x, cells, w);
    double flow = 0;
    for (int k = 0; k < NS; ++k) {
      w[k] = flow_cell(cells[k]) ? w[k] : 0.0;
      flow += w[k];
    }
    if (flow < opt.min_flow_weight) return false;
    cell_states(cells.data(), NS, states.data());
    for (int k = 0; k < np; ++k) {
      Values s{0, 0, 0, 0, 0, 0};
      for (int q = 0; q < NS; ++q) {
        if (w[q] == 0) continue;
        const CellSample& cs = states[static_cast<std::size_t>(q) * np + k];
        const double wq = w[q] / flow;
        s.a += wq * cs.alpha;
        s.rho += wq * cs.rho;
        s.p += wq * cs.p;
        s.c += wq * cs.c;
        s.k += wq * cs.granular;
        for (int d = 0; d < DIM; ++d) s.un += wq * cs.velocity[d] * n[d];
      }
      v[static_cast<std::size_t>(k)] = s;
    }
    return true;
  };
  const auto inside = [&](const std::array<double, 3>& x) {
    for (int d = 0; d < DIM; ++d)
      if (x[d] < g.lower[d] || x[d] > g.lower[d] + g.mesh[d] * g.dx[d]) return false;
    return true;
  };
  for (int f = 0; f < faces.count; ++f) {
    if (only && !(*only)[static_cast<std::size_t>(f)]) continue;
    std::array<double, 3> c{0, 0, 0}, n{0, 0, 0};
    double h = 0, v_wall = 0;
    for (int d = 0; d < DIM; ++d) {
      c[d] = faces.centre[static_cast<std::size_t>(f) * DIM + d];
      n[d] = faces.normal[static_cast<std::size_t>(f) * DIM + d];
      h += std::abs(n[d]) * g.dx[d];
      if (!faces.velocity.empty()) v_wall += faces.velocity[static_cast<std::size_t>(f) * DIM + d] * n[d];
    }
    for (int push = 0; push <= opt.max_pushes; ++push) {
      const double s1 = (1.0 + push) * h;
      std::array<double, 3> x{0, 0, 0}, x2{0, 0, 0};
      for (int d = 0; d < DIM; ++d) {
        x[d] = c[d] + s1 * n[d];
        x2[d] = c[d] + (s1 + h) * n[d];
      }
      if (!inside(x)) break;  // left the fluid domain: not wetted
      if (!evaluate(x, n, vals)) continue;
      // Pressure at the wall: linear extrapolation from the points s1 and s1 + h out (an accelerating gas has a
      // pressure gradient rho a next to the wall; the point value alone would be first order in h).
      const bool second = opt.extrapolate_pressure && inside(x2) && evaluate(x2, n, far);
      for (int k = 0; k < np; ++k) {
        const Values& v = vals[static_cast<std::size_t>(k)];
        double p = v.p, un = v.un;
        if (second) {
          const Values& v2 = far[static_cast<std::size_t>(k)];
          const double pe = v.p + (s1 / h) * (v.p - v2.p);
          // Only where the extrapolation stays between half and twice the point value (smooth flow); there, with
          // extrapolate_velocity (coupling.mode robin), the normal velocity too: next to a wall the gas velocity
          // varies over the chamber (a piston's gas moves with it at the wall and not at the far end), and the
          // Robin condition weighs v_f - v_s by z_f, which the point value would bias by z_f h du/dn, a damping.
          if (pe > 0.5 * v.p && pe < 2.0 * v.p) {
            p = pe;
            // Kept between the point's value and the wall's: the fluid's velocity at the wall is the wall's.
            if (opt.extrapolate_velocity)
              un = std::clamp(v.un + (s1 / h) * (v.un - v2.un), std::min(v.un, v_wall), std::max(v.un, v_wall));
          }
        }
        const std::size_t i = static_cast<std::size_t>(f) * np + k;
        out.alpha[i] = v.a;
        out.rho[i] = v.rho;
        out.normal_velocity[i] = un;
        out.pressure[i] = p;
        out.impedance[i] = v.rho * v.c;
        if (k == 1 && dispersed) {
          // Its collision stress and granular pressure load the wall too; its waves are compaction waves and the
          // sound of its granular gas (§2.8-2.9).
          double pg = 0, cg = 0;
          if (granular.enabled) granular.pressure_and_speed(v.a, v.rho, v.k, pg, cg);
          out.pressure[i] += (stress.stress(v.a) + pg) / std::max(v.a, 1e-300);
          out.impedance[i] = v.rho * std::max(stress.wave_speed(v.a, v.rho), cg);
        }
      }
      out.wetted[f] = 1;
      break;
    }
  }
  return out;
}

template <int DIM>
coupling::FluidSamples sample_interface(const Grid<DIM>& g, const std::vector<std::uint8_t>& kind,
                                        const FluidSimulation& sim, const coupling::Faces& faces,
                                        const SampleOptions& opt = {}) {
  std::array<std::size_t, 1 << DIM> idx{};
  return sample_faces<DIM>(
      g, [&](const std::array<int, 3>& c) { return kind.empty() || is_flow_cell(kind[g.index(c[0], c[1], c[2])]); },
      [&](const std::array<int, 3>* c, int count, CellSample* out) {
        for (int k = 0; k < count; ++k) idx[k] = g.index(c[k][0], c[k][1], c[k][2]);
        sim.cell_states(idx.data(), static_cast<std::size_t>(count), out);
      },
      sim.scene(), faces, nullptr, opt);
}

// The wall pressure of each face for the ghost cells (to_embedded_state): two slots per face (phases 0 and 1),
// `pressure` per face and phase where the samples found fluid next to the face, NaN where not (no fluid, no wall
// pressure: its ghosts copy the image point's). A dispersed phase (`dispersed`, phase 1) gets none: its ghosts keep
// the image point's pressure, which is the carrier's, and its load on the wall is its collision stress (§2.8).
inline std::vector<double> wall_pressure_slots(const coupling::FluidSamples& s, const std::vector<double>& pressure,
                                               bool dispersed = false) {
  std::vector<double> out(2 * static_cast<std::size_t>(s.count), std::nan(""));
  const int phases = dispersed ? 1 : s.phases;
  for (int f = 0; f < s.count; ++f)
    if (s.wetted[static_cast<std::size_t>(f)])
      for (int k = 0; k < phases; ++k)
        out[2 * static_cast<std::size_t>(f) + k] = pressure[static_cast<std::size_t>(f) * s.phases + k];
  return out;
}

}  // namespace cosim::fluid::interface
