// Narrow-band signed distance phi (positive in the fluid, docs/methods.md §5.1) on a point lattice
// (cell centres or cell nodes; paper section 6: phi_C and phi_N).
//  * Band: every face scatters its exact point-face distance to the lattice points of its slab
//    (lattice.h), keeping the minimum: exact for |phi| < band_width, O(faces + band points) work.
//  * Sign in the band: pseudo-normal of the closest feature (Baerentzen & Aanaes 2005).
//  * Outside the band only the sign is known: phi = +-band_width. Along a grid row consecutive
//    out-of-band points cannot be separated by the surface (they are >= band_width >= dx from
//    it), so each gap of a row takes the sign of the band point next to it; a row without band
//    points takes the sign of the previous row, and only the very first such row asks the
//    winding number (O(faces), once).
//  * Next cycle, on the same lattice with every vertex moved by less than half the band width: a point
//    outside the new band cannot have changed sides (the signed distance moves by at most the surface's
//    displacement), so only the previous band's points that left the band are reset to +-band_width by
//    their old sign, and nothing else is touched: O(band) work instead of the dense row fill.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "fluid_solver/embedded/closest_point.h"
#include "fluid_solver/embedded/domain_wall_faces.h"
#include "fluid_solver/embedded/lattice.h"

namespace cosim::fluid::embedded {

struct BandPoint {
  std::size_t index = 0;                // lattice index
  int face = -1;                        // closest face
  Vec3 closest{0, 0, 0};                // closest surface point (boundary intercept)
  Vec3 normal{0, 0, 0};                 // unit, solid -> fluid: (x - closest)/phi, or the pseudo-normal when phi ~ 0
  std::array<double, 3> bary{0, 0, 0};  // of `closest` in `face`
  double d2 = 0;                        // squared distance (scatter minimum)
};

template <int DIM>
struct LevelSet {
  Lattice<DIM> lattice;
  std::vector<double> phi;  // per lattice point: exact in the band, +-band_width outside
  std::vector<int> slot;    // index into band, -1 outside the band
  std::vector<BandPoint> band;
  double band_width = 0;
  // What the dense fill of the previous cycle was made for (the incremental update needs the same).
  std::vector<Vec3> filled_vertices;
  std::array<int, 3> filled_count{0, 0, 0};
  std::array<double, 3> filled_lower{0, 0, 0}, filled_dx{0, 0, 0};
  const void* filled_category = nullptr;
  double filled_band_width = 0;
  std::vector<std::pair<std::size_t, bool>> previous;  // scratch: last band (index, phi >= 0)
  bool incremental = false;                            // scan_level_set -> finish_level_set
  const BandPoint* at(std::size_t idx) const {
    return slot[idx] < 0 ? nullptr : &band[static_cast<std::size_t>(slot[idx])];
  }
};

// Prisms instead of boxes. A point whose closest surface point lies inside face f, or on an edge or vertex of f
// where the surface is flat, lies on f's normal through that point: within f's prism (the face swept along its
// normal by the band). Where the surface bends at f's edges or vertices by at most theta_f (the angle between
// f's normal and every normal of the faces that share a vertex with f), the points closest to those edges and
// vertices lie within theta_f r of the prism at a distance r from the surface (the wedge between two prisms
// opens by r sin(angle)), so f's prism grown sideways by band_width * theta_f holds every point f is closest
// to. A solid mesh's boundary, flat or gently bent by its deformation (1e-4 to 1e-3 rad between faces of the
// tungsten target), therefore costs its area in the band, not its area plus a band-wide rim around each face.
// compute_face_bend: theta_f per face, from the spread delta_v of the face normals about each vertex's normal
// (theta_f <= max over f's vertices of angle(n_f, n_v) + delta_v); pi (the whole box) for points (1D), at an
// open edge or vertex of the surface (one face there: the points beyond it are closest to it from any side),
// and where the surface folds by more than 90 degrees (thin bodies). It depends on the surface alone: one per
// cycle serves both level sets.
struct FaceBend {
  std::vector<Vec3> vertex_normal;    // unit; zero where the sum of the normals vanishes
  std::vector<double> vertex_spread;  // delta_v; pi where the vertex normal vanishes
  std::vector<double> face;           // theta_f
};

inline void compute_face_bend(const Surface& s, const SurfaceTopology& topo, FaceBend& b) {
  const std::size_t nf = s.faces.size(), nv = s.vertices.size();
  b.face.assign(nf, M_PI);
  if (s.dim < 2) return;
  const std::size_t nid = static_cast<std::size_t>(s.dim);
  const auto angle = [](const Vec3& a, const Vec3& c) {  // between unit vectors, accurate for small angles
    const Vec3 d = a - c;
    return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(dot(d, d))));
  };
  b.vertex_normal.resize(nv);
  b.vertex_spread.assign(nv, 0.0);
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3& n = topo.vertex_normal[v];
    const double l = std::sqrt(dot(n, n));
    const bool ok = l > 1e-6;
    b.vertex_normal[v] = ok ? (1.0 / l) * n : Vec3{0, 0, 0};
    if (!ok) b.vertex_spread[v] = M_PI;
  }
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t k = 0; k < nid; ++k) {
      const auto v = static_cast<std::size_t>(s.faces[f][k]);
      if (b.vertex_spread[v] < M_PI)
        b.vertex_spread[v] = std::max(b.vertex_spread[v], angle(topo.face_normal[f], b.vertex_normal[v]));
    }
  // The sum of two unit normals at an edge (3D) or a vertex (2D) has |n1 + n2|^2 = 2 + 2 cos(angle) >= 2 up to
  // 90 degrees; one face alone gives 1.
  const auto folded = [](const Vec3& sum) { return dot(sum, sum) < 2.0; };
  for (std::size_t f = 0; f < nf; ++f) {
    double th = 0;
    if (s.dim == 3)
      for (const int e : topo.face_edges[f]) th = folded(topo.edge_normal[static_cast<std::size_t>(e)]) ? M_PI : th;
    else
      for (std::size_t k = 0; k < 2; ++k)
        th = folded(topo.vertex_normal[static_cast<std::size_t>(s.faces[f][k])]) ? M_PI : th;
    for (std::size_t k = 0; k < nid; ++k) {
      const auto v = static_cast<std::size_t>(s.faces[f][k]);
      const bool ok = b.vertex_spread[v] < M_PI;
      th = std::max(th, ok ? angle(topo.face_normal[f], b.vertex_normal[v]) + b.vertex_spread[v] : M_PI);
    }
    b.face[f] = std::min(th, M_PI);
  }
}

// Growth of face f's bounding box that holds its prism of half-height `band_width`, widened by the bend
// (compute_face_bend) and by 1e-3 of the band (round-off of the normals); never more than the whole band in any
// direction (the box grown by the band holds every point within the band of the face).
inline Vec3 prism_growth(const Vec3& n, double band_width, double bend) {
  const double margin = std::max(1e-3, 1.01 * bend) * band_width;
  Vec3 g{0, 0, 0};
  for (std::size_t d = 0; d < 3; ++d) g[d] = std::min(band_width * std::abs(n[d]) + margin, band_width);
  return g;
}

// Computes phi on `ls.lattice` (set by the caller). `tests` counts point-face distance evaluations; `bend`
// (compute_face_bend) lets each face scan its widened prism over its own footprint, null its whole grown box.
// If `category` is given (centre lattice), the out-of-band cells are set to `fluid` / `solid` there.
// Reusing `ls` from the previous cycle (same lattice) clears only the previous band; the dense row fill
// of phi (and category) is skipped when the surface moved by less than half the band width.
// In two parts: scan_level_set finds the band (each point's closest face; it touches nothing but `ls`, so the
// scans of two level sets may run side by side), finish_level_set gives the band its signs and closest data and
// the points outside it their sign.
template <int DIM>
void scan_level_set(LevelSet<DIM>& ls, const Surface& s, const SurfaceTopology& topo, double band_width,
                    std::size_t& tests, const std::vector<std::uint8_t>* category = nullptr,
                    const DomainWallFaces* walls = nullptr, const FaceBend* bend = nullptr) {
  const Lattice<DIM>& L = ls.lattice;
  const double bw2 = band_width * band_width;
  bool& incremental = ls.incremental;
  incremental = ls.phi.size() == L.size && ls.slot.size() == L.size && ls.filled_count == L.count &&
                ls.filled_lower == L.lower && ls.filled_dx == L.dx && ls.filled_category == category &&
                ls.filled_band_width == band_width && (!category || category->size() == L.size) &&
                ls.filled_vertices.size() == s.vertices.size();
  for (std::size_t v = 0; incremental && v < s.vertices.size(); ++v) {
    const Vec3 dv = s.vertices[v] - ls.filled_vertices[v];
    incremental = dot(dv, dv) < 0.25 * bw2;
  }
  ls.previous.clear();
  if (incremental)
    for (const auto& b : ls.band) ls.previous.emplace_back(b.index, ls.phi[b.index] >= 0);
  ls.band_width = band_width;
  if (ls.slot.size() != L.size) {
    ls.slot.assign(L.size, -1);
  } else {
    for (const auto& b : ls.band) ls.slot[b.index] = -1;
  }
  ls.phi.resize(L.size);  // every entry is written below (band points, then the row fill)
  ls.band.clear();
  const Vec3 grow_all{band_width, band_width, band_width};
  const int nid = DIM == 1 ? 1 : DIM;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const Vec3 grow = bend && DIM > 1 ? prism_growth(topo.face_normal[f], band_width, bend->face[f]) : grow_all;
    const bool wall_face = walls && walls->skips(f);  // on the domain wall: reaches only the ghost layers
    const auto& fc = s.faces[f];
    Vec3 lo = s.vertices[static_cast<std::size_t>(fc[0])], hi = lo;
    for (int k = 1; k < nid; ++k)
      for (std::size_t d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], s.vertices[static_cast<std::size_t>(fc[static_cast<std::size_t>(k)])][d]);
        hi[d] = std::max(hi[d], s.vertices[static_cast<std::size_t>(fc[static_cast<std::size_t>(k)])][d]);
      }
    const Vec3& n = topo.face_normal[f];
    const double plane = dot(n, s.vertices[static_cast<std::size_t>(fc[0])]);
    // A face on the domain wall reaches only its outer side (its normal points out of the domain): half the slab.
    const double centre = wall_face ? plane + 0.5 * band_width : plane;
    const double half_width = wall_face ? 0.5 * band_width + 1e-9 * band_width : band_width;
    std::array<Vec3, 3> tri{};
    if constexpr (DIM == 3)
      for (std::size_t k = 0; k < 3; ++k) tri[k] = s.vertices[static_cast<std::size_t>(fc[k])];
    for_each_in_slab(
        L, lo, hi, grow, n, centre, half_width,
        [&](int I, int J, int K) {
          const std::size_t idx = L.index(I, J, K);
          const Vec3 x = L.point(I, J, K);
          if (wall_face && !walls->reaches(f, x)) return;
          const int sl = ls.slot[idx];
          const double best = sl < 0 ? bw2 : ls.band[static_cast<std::size_t>(sl)].d2;
          // The distances to the face's plane and to its bounding box bound the distance to the face from
          // below: a point already closer to another face (or outside the band) needs no exact test.
          const double pd = dot(n, x) - plane;
          if (pd * pd >= best) return;
          double lb = 0;
          for (std::size_t d = 0; d < 3; ++d) {
            const double out = std::max({lo[d] - x[d], 0.0, x[d] - hi[d]});
            lb += out * out;
          }
          if (lb >= best) return;
          ++tests;
          const ClosestPoint cp = closest_on_face(s, static_cast<int>(f), x);
          if (cp.d2 >= best) return;
          if (sl < 0) {
            ls.slot[idx] = static_cast<int>(ls.band.size());
            ls.band.push_back(BandPoint{idx, static_cast<int>(f), {}, {}, {}, cp.d2});
          } else {
            ls.band[static_cast<std::size_t>(sl)].face = static_cast<int>(f);
            ls.band[static_cast<std::size_t>(sl)].d2 = cp.d2;
          }
        },
        DIM == 3 && bend ? &tri : nullptr);
  }
}

template <int DIM>
void finish_level_set(LevelSet<DIM>& ls, const Surface& s, const SurfaceTopology& topo, double band_width,
                      std::vector<std::uint8_t>* category = nullptr, std::uint8_t fluid = 0, std::uint8_t solid = 0) {
  const Lattice<DIM>& L = ls.lattice;
  const bool incremental = ls.incremental;
  // Sign and closest data in the band.
  double hmin = L.dx[0];
  for (std::size_t d = 1; d < static_cast<std::size_t>(DIM); ++d) hmin = std::min(hmin, L.dx[d]);
  const long nband = static_cast<long>(ls.band.size());
#pragma omp parallel for schedule(static) if (nband > 4096)
  for (long k = 0; k < nband; ++k) {  // each point on its own: threads write disjoint entries
    BandPoint& b = ls.band[static_cast<std::size_t>(k)];
    const auto ijk = L.ijk(b.index);
    const Vec3 x = L.point(ijk[0], ijk[1], ijk[2]);
    const ClosestPoint cp = closest_on_face(s, b.face, x);
    const Vec3 pn = pseudo_normal(s, topo, b.face, cp.feature);
    const double d = std::sqrt(cp.d2);
    const double phi = d == 0 ? 0.0 : (dot(x - cp.point, pn) >= 0 ? d : -d);
    ls.phi[b.index] = phi;
    b.closest = cp.point;
    b.bary = cp.bary;
    b.normal = std::abs(phi) > 1e-9 * hmin ? (1.0 / phi) * (x - cp.point) : normalized(pn);
  }
  ls.filled_vertices = s.vertices;
  ls.filled_count = L.count;
  ls.filled_lower = L.lower;
  ls.filled_dx = L.dx;
  ls.filled_category = category;
  ls.filled_band_width = band_width;
  if (incremental) {  // the previous band's points that left the band keep their side
    for (const auto& [idx, positive] : ls.previous) {
      if (ls.slot[idx] >= 0) continue;
      ls.phi[idx] = positive ? band_width : -band_width;
      if (category) (*category)[idx] = positive ? fluid : solid;
    }
    return;
  }
  // Sign outside the band, row by row.
  std::vector<std::size_t> sorted(ls.band.size());
  for (std::size_t k = 0; k < sorted.size(); ++k) sorted[k] = ls.band[k].index;
  std::sort(sorted.begin(), sorted.end());
  auto fill = [&](std::size_t b, std::size_t e, bool positive) {
    if (b >= e) return;
    std::fill(ls.phi.begin() + static_cast<std::ptrdiff_t>(b), ls.phi.begin() + static_cast<std::ptrdiff_t>(e),
              positive ? band_width : -band_width);
    if (category)
      std::fill(category->begin() + static_cast<std::ptrdiff_t>(b), category->begin() + static_cast<std::ptrdiff_t>(e),
                positive ? fluid : solid);
  };
  std::size_t pos = 0;
  const auto row = static_cast<std::size_t>(L.count[0]);
  for (int K = 0; K < L.count[2]; ++K) {
    for (int J = 0; J < L.count[1]; ++J) {
      const std::size_t rb = L.index(0, J, K), re = rb + row;
      if (pos < sorted.size() && sorted[pos] < re) {
        std::size_t q = pos;
        while (q < sorted.size() && sorted[q] < re) ++q;
        fill(rb, sorted[pos], ls.phi[sorted[pos]] >= 0);
        for (std::size_t m = pos; m + 1 < q; ++m) fill(sorted[m] + 1, sorted[m + 1], ls.phi[sorted[m]] >= 0);
        fill(sorted[q - 1] + 1, re, ls.phi[sorted[q - 1]] >= 0);
        pos = q;
      } else {
        bool positive = true;
        if (J > 0) positive = ls.phi[L.index(0, J - 1, K)] >= 0;
        else if (K > 0) positive = ls.phi[L.index(0, 0, K - 1)] >= 0;
        else positive = winding_number(s, L.point(0, 0, 0)) < 0.5;
        fill(rb, re, positive);
      }
    }
  }
}

}  // namespace cosim::fluid::embedded
