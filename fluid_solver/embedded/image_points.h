// Boundary intercept, image point and interpolation stencil of every ghost and solid-cut cell
// (docs/methods.md §5.1-5.2; paper section 8 step 3):
//   x_BI = closest surface point,  n = (x_BI - x_G)/|phi_G| (= grad phi),  x_IP = x_G + 2|phi_G| n
// (mirror image, Ghias et al., JCP 225 (2007) 528), and the 2^DIM cell centres around x_IP with
// (bi/tri)linear weights. Stencil nodes that are not flow cells (fluid / fluid-cut) are flagged.
// Fallback (our choice, docs/methods.md §5.2): if the flow nodes carry at least
// `min_flow_weight` of the plain weights, their weights are renormalised (the others get 0);
// otherwise the image point is pushed out along n by one cell (max dx) and the stencil rebuilt,
// at most `max_pushes` times; the record then has image_distance = 2|phi| + pushes*dx and the
// ghost fill must use the general probe-length formula of docs/methods.md §5.3 (L = |x_IP - x_G|).
#pragma once

#include <sstream>
#include <stdexcept>
#include <vector>

#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/embedded/reach.h"
#include "fluid_solver/embedded/signed_distance.h"

namespace cosim::fluid::embedded {

struct ImagePoint {
  std::size_t cell = 0;                  // padded index (Grid::index)
  std::array<int, 3> ijk{0, 0, 0};       // interior-numbered cell
  CellKind kind = CellKind::Ghost;       // Ghost or SolidCut
  double phi = 0;                        // signed distance of the centre (< 0)
  Vec3 x_cell{0, 0, 0};                  // x_G
  Vec3 x_boundary{0, 0, 0};              // x_BI, the closest surface point
  Vec3 normal{0, 0, 0};                  // n at x_BI, unit, solid -> fluid
  Vec3 wall_velocity{0, 0, 0};           // interpolated from the face's vertex velocities at x_BI
  int face = -1;                         // face of x_BI
  Vec3 x_image{0, 0, 0};                 // x_IP
  double image_distance = 0;             // |x_IP - x_G|
  int pushes = 0;                        // fallback pushes of the image point (0 normally)
  int stencil_size = 0;                  // 2^DIM
  std::array<std::size_t, 8> stencil{};  // padded cell indices; node k has offsets (k&1, k>>1&1, k>>2&1)
  std::array<double, 8> bilinear{};      // plain (bi/tri)linear weights at x_IP
  std::array<double, 8> weights{};       // weights to use: 0 on non-flow nodes, sum 1
  std::uint8_t non_flow_mask = 0;        // bit k: stencil node k is not a fluid / fluid-cut cell
};

struct ImagePointOptions {
  double min_flow_weight = 0.5;  // re-weight when the flow nodes carry at least this much
  int max_pushes = kMaxImagePushes;
  // The padded cells (lattice indices, [lo, hi) per direction) whose records are wanted: a block builds its
  // geometry with a margin around its cells and needs the records of its own padded cells only.
  std::array<int, 3> want_lo{0, 0, 0}, want_hi{1 << 30, 1 << 30, 1 << 30};
  bool wanted(const std::array<int, 3>& I) const {
    return I[0] >= want_lo[0] && I[0] < want_hi[0] && I[1] >= want_lo[1] && I[1] < want_hi[1] && I[2] >= want_lo[2] &&
           I[2] < want_hi[2];
  }
};

namespace detail {

// The (bi/tri)linear stencil of cell centres around ip.x_image; `usable(index)` says which nodes may carry weight
// (flow cells; for a side image also only those on its side of the wall). flow_weight: the usable nodes' share.
template <int DIM, class Usable>
void build_stencil(const Lattice<DIM>& C, const Usable& usable, ImagePoint& ip, double& flow_weight) {
  std::array<int, 3> base{0, 0, 0};
  std::array<double, 3> t{0, 0, 0};
  for (int d = 0; d < DIM; ++d) {
    const auto ud = static_cast<std::size_t>(d);
    // In the whole mesh's lattice (clamped to its edges, its ghost layers), then this block's.
    const double u = (ip.x_image[ud] - C.origin(d)) / C.dx[ud];
    const int whole = std::clamp(static_cast<int>(std::floor(std::clamp(u, -1.0, 1e9))), 0, C.whole[ud] - 2);
    base[ud] = whole - C.first[ud];
    if (base[ud] < 0 || base[ud] > C.count[ud] - 2) {
      std::ostringstream msg;
      msg << "embedded geometry: the image point of cell (" << ip.ijk[0] + C.first[0] << ", " << ip.ijk[1] + C.first[1]
          << ", " << ip.ijk[2] + C.first[2] << ") reaches cell " << whole - 2 << " along axis " << d
          << ", beyond the cells [" << C.first[ud] - 2 << ", " << C.first[ud] + C.count[ud] - 2
          << ") this block's geometry holds (fluid_solver/embedded/reach.h)";
      throw ReachError(msg.str());
    }
    t[ud] = std::clamp((ip.x_image[ud] - C.coord(d, base[ud])) / C.dx[ud], 0.0, 1.0);
  }
  ip.stencil_size = 1 << DIM;
  ip.non_flow_mask = 0;
  flow_weight = 0;
  for (int k = 0; k < ip.stencil_size; ++k) {
    std::array<int, 3> o{k & 1, (k >> 1) & 1, (k >> 2) & 1};
    double w = 1;
    for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) w *= o[d] ? t[d] : 1 - t[d];
    const auto uk = static_cast<std::size_t>(k);
    ip.stencil[uk] = C.index(base[0] + o[0], base[1] + o[1], base[2] + o[2]);
    ip.bilinear[uk] = w;
    if (usable(ip.stencil[uk])) flow_weight += w;
    else ip.non_flow_mask = static_cast<std::uint8_t>(ip.non_flow_mask | (1u << k));
  }
}

// The image point of ip (x_cell, normal, phi set) at 2 |phi| along the normal, pushed out by a cell (hmax) while the
// usable nodes carry less than min_flow_weight of its stencil, at most max_pushes times; returns their weight.
template <int DIM, class Usable>
double place_image_point(const Lattice<DIM>& C, const Usable& usable, double hmax, const ImagePointOptions& opt,
                         ImagePoint& ip) {
  double flow_weight = 0;
  for (ip.pushes = 0;; ++ip.pushes) {
    ip.image_distance = 2 * std::abs(ip.phi) + ip.pushes * hmax;
    ip.x_image = ip.x_cell + ip.image_distance * ip.normal;
    build_stencil(C, usable, ip, flow_weight);
    if (flow_weight >= opt.min_flow_weight || ip.pushes >= opt.max_pushes) return flow_weight;
  }
}

// The weights to use: the plain ones of the usable nodes, renormalised by their share flow_weight (> 0).
inline void renormalise_weights(ImagePoint& ip, double flow_weight) {
  for (int k = 0; k < ip.stencil_size; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    ip.weights[uk] = (ip.non_flow_mask >> k) & 1u ? 0.0 : ip.bilinear[uk] / flow_weight;
  }
}

}  // namespace detail

// Builds the records of all ghost and solid-cut cells of the band into `out`. Throws
// std::runtime_error when no flow cell can be found near an image point even after the pushes.
template <int DIM>
void build_image_points(const Grid<DIM>& g, const LevelSet<DIM>& centres, const Surface& s,
                        const std::vector<std::uint8_t>& category, std::vector<ImagePoint>& out,
                        const ImagePointOptions& opt = {}) {
  out.clear();
  const Lattice<DIM>& C = centres.lattice;
  double hmax = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) hmax = std::max(hmax, g.dx[d]);
  for (const auto& b : centres.band) {
    const auto kind = static_cast<CellKind>(category[b.index]);
    if (kind != CellKind::Ghost && kind != CellKind::SolidCut) continue;
    const auto I = C.ijk(b.index);
    if (!opt.wanted(I)) continue;
    ImagePoint ip;
    ip.cell = b.index;
    ip.ijk = {I[0] - Grid<DIM>::offset(0), I[1] - Grid<DIM>::offset(1), I[2] - Grid<DIM>::offset(2)};
    ip.kind = kind;
    ip.phi = centres.phi[b.index];
    ip.x_cell = C.point(I[0], I[1], I[2]);
    ip.x_boundary = b.closest;
    ip.normal = b.normal;
    ip.face = b.face;
    ip.wall_velocity = face_velocity(s, b.face, b.bary);
    const double flow_weight = detail::place_image_point(
        C, [&](std::size_t c) { return is_flow_cell(category[c]); }, hmax, opt, ip);
    bool outside = false;  // a ghost layer of the domain (not of a block): its boundary condition applies there
    for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d)
      outside = outside || ip.ijk[d] + g.first[d] < 0 || ip.ijk[d] + g.first[d] >= g.mesh[d];
    if (!(flow_weight > 0) && outside) {
      ip.stencil_size = 0;  // the ghost fill leaves the cell to the domain boundary condition
      out.push_back(ip);
      continue;
    }
    if (!(flow_weight > 0)) {
      std::ostringstream msg;
      msg << "embedded geometry: no fluid cell around the image point of cell (" << ip.ijk[0] + g.first[0] << ", "
          << ip.ijk[1] + g.first[1] << ", " << ip.ijk[2] + g.first[2] << ") at x = (" << ip.x_cell[0] << ", "
          << ip.x_cell[1] << ", " << ip.x_cell[2]
          << "): the body or the fluid gap there is thinner than the grid resolves; refine the grid";
      throw std::runtime_error(msg.str());
    }
    detail::renormalise_weights(ip, flow_weight);
    out.push_back(ip);
  }
}

}  // namespace cosim::fluid::embedded
