// Thin bodies: two-sided ghost states (docs/methods.md §5.7). A body thinner than about two cells puts
// both of its walls next to the same cells, and one ghost value cannot serve both sides. Two cases,
// found along every grid line from every flow cell F to its neighbour X ("opposite" means unit normals
// with n_F . n_X < opposite_cos, default -0.9, ~154 degrees):
//   shared ghost  X is a ghost or solid-cut cell whose closest wall faces away from F (n_X opposite to
//                 n_F): a plate one to two cells thick, or a wedge tip. X's own record serves the other
//                 side; F reads X's value for its MUSCL slope only (the face state itself is the
//                 mirror of F's edge, steps 5-6), so F gets its own value of X: a side image.
//   blocked face  X is a flow cell too, and both closest walls lie between the two centres with opposite
//                 normals: a plate thinner than one cell passes between them. The grid face F|X is a
//                 wall for both cells: each gets the flux of its own mirrored state (the solver), and
//                 each reads its own side image of the other for its slope.
// The side image of X seen from F: the mirror of X's centre about F's wall plane (through F's closest
// surface point x_BI,F with F's normal n_F), x_IP = x_X + 2 d_X n_F, d_X = (x_BI,F - x_X) . n_F, with a
// stencil of the flow cells in front of that plane only (the other side of the plate never contributes),
// pushed out by a cell when they carry less than min_flow_weight; F alone if nothing else is found.
#pragma once

#include <omp.h>

#include <algorithm>
#include <vector>

#include "fluid_solver/embedded/image_points.h"
#include "fluid_solver/embedded/signed_distance.h"

namespace cosim::fluid::embedded {

struct SideImage {
  ImagePoint image;            // of X as seen from F: cell = X, phi = -d_X, normal/wall data of F's wall
  std::size_t flow_cell = 0;   // F (padded index)
  int direction = 0;           // grid direction of the line F -> X
  bool across_high = true;     // X = F + e_direction
  bool blocked = false;        // X is a flow cell: the face between them is a wall for both
  double face_distance = 0.5;  // F's centre to its wall along the line, in cells (the d of the wall face)
};

template <int DIM>
std::vector<SideImage> find_side_images(const Grid<DIM>& g, const LevelSet<DIM>& centres, const Surface& s,
                                        const std::vector<std::uint8_t>& category, double opposite_cos,
                                        const ImagePointOptions& opt = {}) {
  std::vector<SideImage> out;
  const Lattice<DIM>& C = centres.lattice;
  double hmax = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) hmax = std::max(hmax, g.dx[d]);
  // The band's points on the threads, each with its own list (the lists are joined and sorted by a total order,
  // so that the result is the same for any number of threads).
  const long nband = static_cast<long>(centres.band.size());
  const int nthreads = nband < 4096 ? 1 : omp_get_max_threads();
  std::vector<std::vector<SideImage>> found(static_cast<std::size_t>(nthreads));
#pragma omp parallel for schedule(static) num_threads(nthreads)
  for (long b = 0; b < nband; ++b) {
    const BandPoint& f = centres.band[static_cast<std::size_t>(b)];
    std::vector<SideImage>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
    if (!is_flow_cell(category[f.index])) continue;
    const auto I = C.ijk(f.index);
    for (int d = 0; d < DIM; ++d)
      for (int dir = -1; dir <= 1; dir += 2) {
        std::array<int, 3> J = I;
        J[static_cast<std::size_t>(d)] += dir;
        if (!C.inside(J[0], J[1], J[2]) || !opt.wanted(I) || !opt.wanted(J)) continue;
        const std::size_t xidx = C.index(J[0], J[1], J[2]);
        const BandPoint* x = centres.at(xidx);
        if (!x || !(dot(x->normal, f.normal) < opposite_cos)) continue;
        const auto ud = static_cast<std::size_t>(d);
        const bool across_flow = is_flow_cell(category[xidx]);
        const bool blocked = across_flow && dir * f.normal[ud] < 0 && dir * x->normal[ud] > 0;
        if (across_flow && !blocked) continue;
        SideImage si;
        si.flow_cell = f.index;
        si.direction = d;
        si.across_high = dir > 0;
        si.blocked = blocked;
        ImagePoint& ip = si.image;
        ip.cell = xidx;
        ip.ijk = {J[0] - Grid<DIM>::offset(0), J[1] - Grid<DIM>::offset(1), J[2] - Grid<DIM>::offset(2)};
        ip.kind = static_cast<CellKind>(category[xidx]);
        ip.x_cell = C.point(J[0], J[1], J[2]);
        ip.x_boundary = f.closest;
        ip.normal = f.normal;
        ip.face = f.face;
        ip.wall_velocity = face_velocity(s, f.face, f.bary);
        const double dX = std::max(dot(f.closest - ip.x_cell, f.normal), 1e-6 * hmax);  // X behind F's wall plane
        ip.phi = -dX;
        const double dF = std::max(centres.phi[f.index], 0.0);
        si.face_distance = std::clamp(dF / (dF + dX), 0.0, 1.0);
        const auto in_front = [&](std::size_t c) {
          const auto K = C.ijk(c);
          return is_flow_cell(category[c]) && dot(C.point(K[0], K[1], K[2]) - f.closest, f.normal) > -1e-9 * hmax;
        };
        const double flow_weight = detail::place_image_point(C, in_front, hmax, opt, ip);  // |phi| = d_X
        if (flow_weight > 0) {
          detail::renormalise_weights(ip, flow_weight);
        } else {  // nothing in front but F itself (a plate tip in a one-cell gap): F's own state
          ip.stencil_size = 1;
          ip.stencil[0] = f.index;
          ip.weights[0] = 1.0;
        }
        mine.push_back(si);
      }
  }
  for (const auto& part : found) out.insert(out.end(), part.begin(), part.end());
  std::sort(out.begin(), out.end(), [](const SideImage& a, const SideImage& b) {
    if (a.direction != b.direction) return a.direction < b.direction;
    if (a.flow_cell != b.flow_cell) return a.flow_cell < b.flow_cell;
    return a.across_high < b.across_high;
  });
  return out;
}

}  // namespace cosim::fluid::embedded
