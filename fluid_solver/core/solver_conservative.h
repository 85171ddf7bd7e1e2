// The conservative embedded boundary (`embedded.conservative`, docs/methods.md §5.8): at the grid faces between a
// flow cell and a ghost/solid-cut cell no phase's mass crosses, and the momentum and energy that the mass flux
// carried go back out of the face flux, so the face keeps only what the wall exchanges with the flow (the wall's
// pressure force and its work, eq. 5.8.1); the cells a moving body covers give their content to the flow cells
// around them, and those it uncovers take theirs from them (redistribution within kRedistributionReach, weighted by
// each phase's mass, after Chern & Colella 1987 and Pember et al. 1995). Also: the wall exchange account of every
// run, conservative or not.
#pragma once

#include "fluid_solver/core/solver.h"
#include "fluid_solver/embedded/reach.h"

namespace cosim::fluid {

// Phase k's momentum (DIM) and total energy per unit mass in flow cell c from the stage's primitives, into q[]
// (q[DIM + 1]: the material energy per mass of a dispersed phase with a granular temperature).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::content_per_mass(int k, std::size_t c, double* q) const {
  const double rho = W_.var(Lay::rho(k))[c], p = W_.var(Lay::pres(k))[c];
  double u2 = 0;
  for (int d = 0; d < DIM; ++d) {
    q[d] = W_.var(Lay::vel(k, d))[c];
    u2 += q[d] * q[d];
  }
  const double e = eos_[k].rho_e(rho, p) / rho;
  q[DIM] = e + 0.5 * u2;
  q[DIM + 1] = e;
  if constexpr (NP == 2)
    if (k == 1 && gran_) q[DIM] += W_.var(Lay::pgran)[c];
}

// One wall face's flux in buf (column f, stride flen; wf along D) as its flow cell receives it (sign +1: the flow
// cell is on the face's high side): conservative, no phase's mass crosses it and it keeps the wall's pressure force
// and work; either way the flux into the flow cell goes into this thread's wall exchange account (per second).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::wall_face_flux(Scratch& sc, const WallFace& wf, int D, double sign, double area,
                                                double* buf, std::size_t flen, int f) const {
  const std::size_t fc = wf.fluid_cell;
  for (int k = 0; k < NP; ++k) {
    double* mf = buf + fvar_flux(k, 0) * flen + f;
    if (conservative_) {
      double q[DIM + 2];
      content_per_mass(k, fc, q);
      const double m = *mf;
      // Eq. 5.8.1: the mass flux carried the flow's tangential velocity and the wall's normal one (the mirrored
      // problem's contact moves with the wall); less that, the face's momentum flux along D is the wall's pressure
      // force (alpha p* per phase), and the wall's work on the flow is that force times u_I.
      double qn = 0, un = 0;
      for (int d = 0; d < DIM; ++d) {
        qn += q[d] * wf.normal[d];
        un += wf.wall_velocity[d] * wf.normal[d];
      }
      for (int d = 0; d < DIM; ++d) buf[fvar_flux(k, 1 + d) * flen + f] -= m * (q[d] - (qn - un) * wf.normal[d]);
      buf[fvar_flux(k, 1 + DIM) * flen + f] = buf[fvar_flux(k, 1 + D) * flen + f] * wf.wall_velocity[D];
      if constexpr (NP == 2)
        if (k == 1 && gran_) buf[fvar_heat * flen + f] -= m * q[DIM + 1];
      *mf = 0.0;
    }
    for (int v = 0; v < 2 + DIM; ++v) sc.wall[fvar_flux(k, v)] += sign * area * buf[fvar_flux(k, v) * flen + f];
  }
}

// The wall faces of one face row (face f's high cell is base + f, as in mirror_wall_faces) after their fluxes.
// A face row that two sweep chunks compute gives each of them one of its cell rows: a face counts in the account
// where its flow cell's row is this chunk's (count_low: the row below the faces, count_high: the row above), and on a
// block of a split mesh where its flow cell is the block's own: the blocks' sum is one rank's account.
template <int DIM, int NP, FluxKind FK>
template <int D>
inline void Solver<DIM, NP, FK>::wall_face_row(Scratch& sc, std::size_t base, int len, double* buf, std::size_t flen,
                                               bool count_low, bool count_high) const {
  const auto& faces = emb_.faces[D];
  auto it = std::lower_bound(faces.begin(), faces.end(), base,
                             [](const WallFace& f, std::size_t b) { return high_cell(f) < b; });
  const double area = g_.cell_volume() / g_.dx[D];
  for (; it != faces.end() && high_cell(*it) < base + static_cast<std::size_t>(len); ++it) {
    // On a block of a split mesh the face of a flow cell in a ghost layer is its owner's (Grid::owns).
    const bool counted = (it->solid_on_high_side ? count_low : count_high) && g_.owns(it->fluid_cell);
    wall_face_flux(sc, *it, D, it->solid_on_high_side ? -1.0 : 1.0, counted ? area : 0.0, buf, flen,
                   static_cast<int>(high_cell(*it) - base));
  }
}

// The `len` cells of a row from `base`: contents to densities (U / V, to_density) or back (U V); alpha stays.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::contents_to_densities(std::size_t base, int len, bool to_density) {
  const double* v = vfrac_.data() + base;
  for (int q = 0; q < ncons_; ++q) {
    if (NP == 2 && q == Lay::alpha) continue;
    double* u = U_.var(q) + base;
    if (to_density)
      for (int i = 0; i < len; ++i) u[i] /= v[i];
    else
      for (int i = 0; i < len; ++i) u[i] *= v[i];
  }
}

// The fluid volume each flow cell stands for (vfrac_, in cell volumes; eq. 5.8.2): its own fluid fraction and, of
// every ghost or solid-cut cell next to it across a wall face, that cell's fluid fraction shared equally among its
// flow neighbours; at least kMinFluidVolume. The other cells hold densities (ghost states): 1. Where walls move, the
// same sum of the fractions' rates (vrate_): a step's stages see the volumes of their own times (volumes_at).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::fluid_volumes() {
  const std::vector<double>& ff = emb_.fluid_fraction;
  const std::vector<double>& rate = emb_.fluid_fraction_rate;
  const bool moving = !rate.empty();
  vraw_.resize(g_.total);
  vfrac_.resize(g_.total);
  shares_.resize(g_.total);
  if (moving) vrate_.assign(g_.total, 0.0);
  else vrate_.clear();
  for (std::size_t c = 0; c < g_.total; ++c) {
    const bool flow = is_flow_cell(emb_.kind[c]);
    vraw_[c] = flow ? ff[c] : 1.0;
    if (moving && flow) vrate_[c] = rate[c];
  }
  for (const GhostRecord& gr : emb_.ghosts) shares_[gr.cell] = 0.0;
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : emb_.faces[D]) shares_[f.solid_cell] = 0.0;
  // (A wall face of a ghost layer's cell, where a body meets the domain's edge, holds no fluid: the layer is not
  // the flow's.)
  // On a block, another block's cell in a ghost layer is a flow cell like any other (Grid::in_mesh). Its own cells'
  // sums are complete (their neighbours' neighbours are in the ghost layers); those of the ghost layers come from
  // their owners.
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : emb_.faces[D])
      if (g_.in_mesh(f.fluid_cell)) shares_[f.solid_cell] += 1.0;
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : emb_.faces[D]) {
      if (!g_.in_mesh(f.fluid_cell)) continue;
      vraw_[f.fluid_cell] += ff[f.solid_cell] / shares_[f.solid_cell];
      if (moving) vrate_[f.fluid_cell] += rate[f.solid_cell] / shares_[f.solid_cell];
    }
  if (links_) {
    if (moving) halo_from_blocks({vraw_.data(), vrate_.data(), shares_.data()});
    else halo_from_blocks({vraw_.data(), shares_.data()});
  }
  volumes_elapsed_ = 0.0;
  volumes_at(0.0);
}

// On a block of a split mesh: the padded arrays' values at the other blocks' cells in the ghost layers (corners
// too) from their owners, through the ghost exchange of every axis; the mesh edge's ghost layers keep this block's
// values (a periodic neighbour's would differ from the whole mesh's). Every block calls it together.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::halo_from_blocks(const std::vector<double*>& arrays) {
  if (halo_cells_.empty())
    for (std::size_t c = 0; c < g_.total; ++c)
      if (g_.in_mesh(c) && !g_.interior(c)) halo_cells_.push_back(c);
  if (halo_.vars != static_cast<int>(arrays.size()) || halo_.cells != g_.total)
    halo_.resize(static_cast<int>(arrays.size()), g_.total);
  int v = 0;
  for (double* a : arrays) std::copy(a, a + g_.total, halo_.var(v++));
  for (int d = 0; d < DIM; ++d) links_->exchange_ghosts(halo_, d);
  v = 0;
  for (double* a : arrays) {
    const double* h = halo_.var(v++);
    for (std::size_t c : halo_cells_) a[c] = h[c];
  }
}

// The flow cells' fluid volumes a time `elapsed` after the geometry's (the geometric conservation of a moving wall:
// a Runge-Kutta stage's state is that of its own time, a content over the volume the wall has swept by then).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::volumes_at(double elapsed) {
  const bool moving = !vrate_.empty();
  for (std::size_t c = 0; c < g_.total; ++c)
    vfrac_[c] =
        is_flow_cell(emb_.kind[c]) ? std::max(vraw_[c] + (moving ? elapsed * vrate_[c] : 0.0), kMinFluidVolume) : 1.0;
  primitives_valid_ = false;
}

// The first geometry: the initial state's densities become contents, U <- U vfrac in the flow cells (all but the
// volume fraction alpha).
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::contents_from_densities() {
  for (int v = 0; v < ncons_; ++v) {
    if (NP == 2 && v == Lay::alpha) continue;
    double* u = U_.var(v);
    for (std::size_t c = 0; c < g_.total; ++c)
      if (is_flow_cell(emb_.kind[c])) u[c] *= vfrac_[c];
  }
  U0_ = U_;
}

// The cells whose category changed from the last geometry `old` to emb_ (eq. 5.8.3). A cell the body uncovered was
// a ghost whose fluid part its flow neighbours across wall faces held (eq. 5.8.2, their share of it at the time
// `elapsed` the state has reached): each gives it back, that share of its content over its fluid volume, so the
// fluid keeps its density where it was. A cell the body covered gives its content to the flow cells that now hold
// its fluid part, equally (the shares of eq. 5.8.2). Cells with no such neighbour (a corner) go to redistribute_by_box.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::redistribute_changed_cells(EmbeddedState& old, double elapsed) {
  std::vector<std::uint8_t>& before = old.kind;  // marks the uncovered cells that hold their content
  const auto content_vars = [&](auto each) {
    for (int v = 0; v < ncons_; ++v)
      if (NP == 1 || v != Lay::alpha) each(U_.var(v));
  };
  const auto uncovered = [&](std::size_t c) { return !is_flow_cell(before[c]) && is_flow_cell(emb_.kind[c]); };
  const auto covered = [&](std::size_t c) { return is_flow_cell(before[c]) && !is_flow_cell(emb_.kind[c]); };
  bool any = false;
  for (std::size_t c = 0; c < g_.total && !any; ++c) any = uncovered(c) || covered(c);
  if (links_) any = links_->any(any);  // every block together: the contents' halo below
  if (!any) return;
  // On a block the cells of the other blocks in the ghost layers give and take as on the whole mesh: their contents
  // as they are now (a ghost layer's U is stale), with the old volumes and shares, which fluid_volumes took from
  // their owners. Each block then reduces and fills its own cells itself, the sums over the faces in the mesh's order.
  if (links_) {
    std::vector<double*> u;
    for (int v = 0; v < ncons_; ++v) u.push_back(U_.var(v));
    halo_from_blocks(u);
  }
  // The old shares (shares_old_: how many flow cells held each old ghost's fluid part), and that part at `elapsed`.
  given_.assign(g_.total, 0.0);
  const std::vector<double>& held_by = shares_old_;
  const auto holds = [&](const WallFace& f) { return g_.in_mesh(f.fluid_cell); };
  const auto part = [&](std::size_t G) {
    const double rate = old.fluid_fraction_rate.empty() ? 0.0 : old.fluid_fraction_rate[G];
    return std::max(old.fluid_fraction[G] + elapsed * rate, 0.0) / held_by[G];
  };
  // Uncovered: from the original contents of the cells that held them, then those cells keep the rest.
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : old.faces[D])
      if (holds(f) && uncovered(f.solid_cell)) given_[f.fluid_cell] += part(f.solid_cell) / vfrac_old_[f.fluid_cell];
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : old.faces[D])
      if (holds(f) && uncovered(f.solid_cell) && before[f.solid_cell] != kTaking) {
        content_vars([&](double* u) { u[f.solid_cell] = 0.0; });
        before[f.solid_cell] = kTaking;
      }
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : old.faces[D]) {
      if (!holds(f) || before[f.solid_cell] != kTaking) continue;
      const double w = part(f.solid_cell) / vfrac_old_[f.fluid_cell] / std::max(given_[f.fluid_cell], 1.0);
      content_vars([&](double* u) { u[f.solid_cell] += w * u[f.fluid_cell]; });
    }
  for (std::size_t c = 0; c < g_.total; ++c)
    if (given_[c] > 0.0) {
      const double keep = 1.0 - std::min(given_[c], 1.0);
      content_vars([&](double* u) { u[c] *= keep; });
    }
  for (std::size_t c = 0; c < g_.total; ++c)
    if (before[c] == kTaking) before[c] = static_cast<std::uint8_t>(CellKind::Fluid);
  // Covered: to the flow cells across the new wall faces, equally (shares_: their count, from fluid_volumes).
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : emb_.faces[D])
      if (holds(f) && covered(f.solid_cell)) {
        const double w = 1.0 / shares_[f.solid_cell];
        content_vars([&](double* u) { u[f.fluid_cell] += w * u[f.solid_cell]; });
      }
  for (int D = 0; D < DIM; ++D)
    for (const WallFace& f : emb_.faces[D])
      if (holds(f) && covered(f.solid_cell)) before[f.solid_cell] = kGiven;
  redistribute_by_box(before);
}

// The cells whose category changed from `before` to emb_.kind that redistribute_changed_cells left (kGiven: done),
// within kRedistributionReach: an

// uncovered cell takes the mean density of itself and the flow cells around it times its fluid volume, each of
// them giving the same fraction of every variable (so their velocities, temperatures and phase ratios stay); then
// a covered cell gives its content to the flow cells around it in proportion to their fluid volumes. What cannot
// be placed (no flow cell in reach) goes into the cells account. `before` is scratch: the uncovered cells are
// marked as flow cells once they hold their content.
template <int DIM, int NP, FluxKind FK>
inline void Solver<DIM, NP, FK>::redistribute_by_box(std::vector<std::uint8_t>& before) {
  constexpr int r = embedded::kRedistributionReach;
  constexpr int side = 2 * r + 1;
  constexpr int box = DIM == 1 ? side : DIM == 2 ? side * side : side * side * side;
  const double vol = g_.cell_volume();
  const int nz = DIM == 3 ? r : 0, ny = DIM >= 2 ? r : 0;
  const auto fluid = static_cast<std::uint8_t>(CellKind::Fluid);
  std::size_t nb[box];
  // The cells of the block around (i, j, k), but itself, for which take(n) holds, into nb; their count.
  const auto around = [&](int i, int j, int k, auto take) {
    int count = 0;
    for (int dk = -nz; dk <= nz; ++dk)
      for (int dj = -ny; dj <= ny; ++dj)
        for (int di = -r; di <= r; ++di) {
          const int a = i + di, b = j + dj, e = k + dk;
          if ((di == 0 && dj == 0 && dk == 0) || a < 0 || a >= g_.n[0] || b < 0 || b >= g_.n[1] || e < 0 ||
              e >= g_.n[2])
            continue;
          const std::size_t n = g_.index(a, b, e);
          if (take(n)) nb[count++] = n;
        }
    return count;
  };
  const auto content_vars = [&](auto each) {
    for (int v = 0; v < ncons_; ++v)
      if (NP == 1 || v != Lay::alpha) each(U_.var(v));
  };
  const auto left = [&](std::size_t c) {
    return before[c] != kGiven && is_flow_cell(emb_.kind[c]) != is_flow_cell(before[c]);
  };
  if (links_) {
    // On a block a cell's box ends at the block's cells: the same as on the whole mesh where it ends at the mesh's
    // edge or inside the block (no two such boxes of two blocks overlap, so the blocks' orders agree). One that
    // reaches across a seam between blocks would differ: an error, agreed by every block, rather than another result.
    std::string seam;
    for (int k = 0; k < g_.n[2] && seam.empty(); ++k)
      for (int j = 0; j < g_.n[1] && seam.empty(); ++j)
        for (int i = 0; i < g_.n[0] && seam.empty(); ++i) {
          if (!left(g_.index(i, j, k))) continue;
          const std::array<int, 3> at{i, j, k};
          for (int d = 0; d < DIM; ++d)
            if ((at[d] < r && g_.first[d] > 0) || (at[d] + r >= g_.n[d] && g_.first[d] + g_.n[d] < g_.mesh[d]))
              seam = fmt::format(
                  "embedded.conservative on several ranks: the cell ({}, {}, {}) the body covered or uncovered has no "
                  "flow cell across a wall face, and the box of cells it shares its content with "
                  "(kRedistributionReach {}) crosses a block seam along axis {}; run it on one rank or with "
                  "fluid.parallel.ranks placing the seams away from the body's corners",
                  g_.first[0] + i, g_.first[1] + j, g_.first[2] + k, r, d);
        }
    if (links_->any(!seam.empty()))
      throw std::runtime_error(seam.empty() ? "embedded.conservative on several ranks: another block's covered or "
                                              "uncovered cell shares its content across a block seam"
                                            : seam);
  }
  for (int pass = 0; pass < 2; ++pass)  // uncovered cells first: a covered cell's content may go to them
    for (int k = 0; k < g_.n[2]; ++k)
      for (int j = 0; j < g_.n[1]; ++j)
        for (int i = 0; i < g_.n[0]; ++i) {
          const std::size_t c = g_.index(i, j, k);
          const bool now = is_flow_cell(emb_.kind[c]);
          if (!left(c) || now != (pass == 0)) continue;
          if (now) {  // uncovered: U holds its last ghost state (densities)
            const int count = around(i, j, k, [&](std::size_t n) { return is_flow_cell(before[n]); });
            double vsum = vfrac_[c];
            for (int s = 0; s < count; ++s) vsum += vfrac_[nb[s]];
            if (count == 0) {  // nothing to take it from: its ghost state, unaccounted for
              content_vars([&](double* u) { u[c] *= vfrac_[c]; });
              for (int p = 0; p < NP; ++p) mass_by_cells_[p] += vol * U_.var(Lay::mass(p))[c];
            } else {
              const double share = vfrac_[c] / vsum;
              content_vars([&](double* u) {
                double t = 0;
                for (int s = 0; s < count; ++s) {
                  t += share * u[nb[s]];
                  u[nb[s]] -= share * u[nb[s]];
                }
                u[c] = t;
              });
            }
            before[c] = fluid;
          } else {  // covered
            const int count = around(i, j, k, [&](std::size_t n) { return is_flow_cell(emb_.kind[n]); });
            double vsum = 0;
            for (int s = 0; s < count; ++s) vsum += vfrac_[nb[s]];
            if (count == 0) {
              for (int p = 0; p < NP; ++p) mass_by_cells_[p] -= vol * U_.var(Lay::mass(p))[c];
              continue;
            }
            content_vars([&](double* u) {
              for (int s = 0; s < count; ++s) u[nb[s]] += u[c] * (vfrac_[nb[s]] / vsum);
            });
          }
        }
  primitives_valid_ = false;
}

}  // namespace cosim::fluid
