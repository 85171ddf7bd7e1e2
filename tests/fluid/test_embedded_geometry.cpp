// Geometry half of the embedded moving boundary (paper section 6, Table 1; docs/methods.md §5): interface
// segments, narrow-band signed distance, cell categories, image points, side images of thin bodies and the
// locality of the work.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "fluid_solver/embedded/geometry.h"
#include "fluid_solver/embedded/scene_bodies.h"
#include "fluid_solver/embedded/shapes.h"

namespace cosim::fluid::embedded {
namespace {

constexpr double kPi = std::numbers::pi;

// Oracle from the dense phi arrays (O(all cells), test only): Table 1 without the ghost layer rule; node values
// within 1e-10 dx of zero count as zero (categorize.h).
template <int DIM>
CellKind table1(const EmbeddedGeometry<DIM>& e, std::size_t cell) {
  const auto& C = e.centres.lattice;
  const auto& N = e.nodes.lattice;
  const auto I = C.ijk(cell);
  double zero = C.dx[0];
  for (int d = 1; d < DIM; ++d) zero = std::min(zero, C.dx[static_cast<std::size_t>(d)]);
  zero *= 1e-10;
  bool neg = false, pos = false;
  for (int c = 0; c < (DIM > 2 ? 2 : 1); ++c)
    for (int b = 0; b < (DIM > 1 ? 2 : 1); ++b)
      for (int a = 0; a < 2; ++a) {
        const double p = e.nodes.phi[N.index(I[0] + a, I[1] + b, I[2] + c)];
        neg = neg || p < -zero;
        pos = pos || p > zero;
      }
  if (e.centres.phi[cell] >= 0) return neg ? CellKind::FluidCut : CellKind::Fluid;
  return pos ? CellKind::SolidCut : CellKind::Solid;
}

bool is_cut(CellKind k) { return k == CellKind::FluidCut || k == CellKind::SolidCut; }

// Common checks of any closed body: segments, categories (Table 1, promotion, ghost layers),
// image-point stencils. Returns the number of cut cells.
template <int DIM>
std::size_t check_consistency(const Grid<DIM>& g, const Surface& s, const EmbeddedGeometry<DIM>& e) {
  // Segments: measure, closure (sum n A = 0) and enclosed volume (divergence theorem).
  double area = 0, vol = 0;
  Vec3 nA{0, 0, 0};
  for (const auto& seg : e.segments) {
    area += seg.area;
    nA = nA + seg.area * seg.normal;
    vol += dot(seg.center, seg.normal) * seg.area / DIM;
  }
  const double A = surface_measure(s), V = enclosed_volume(s);
  EXPECT_NEAR(area, A, 1e-12 * A);
  EXPECT_NEAR(norm(nA), 0.0, 1e-12 * A);
  EXPECT_NEAR(vol, V, 1e-11 * std::abs(V));
  // Categories: Table 1 (+ promotion of cells crossed between their nodes), cut == owners.
  std::set<std::size_t> owners;
  for (const auto& seg : e.segments) owners.insert(seg.cell);
  std::size_t cut = 0, promoted = 0;
  const auto& C = e.centres.lattice;
  for (std::size_t c = 0; c < g.total; ++c) {
    const CellKind k = e.kind(c), t = table1(e, c);
    cut += is_cut(k);
    EXPECT_EQ(is_cut(k), owners.count(c) == 1) << "cell " << c;
    if (is_cut(t)) {
      EXPECT_EQ(k, t);
    } else if (is_cut(k)) {
      ++promoted;
      EXPECT_EQ(e.centres.phi[c] >= 0, k == CellKind::FluidCut);
    }
    if (t == CellKind::Solid && !is_cut(k)) {  // ghost iff a flow centre within 2 cells along a grid line
      const auto I = C.ijk(c);
      bool near = false;
      for (int d = 0; d < DIM; ++d)
        for (int step : {-2, -1, 1, 2}) {
          auto J = I;
          J[static_cast<std::size_t>(d)] += step;
          if (C.inside(J[0], J[1], J[2]) && e.centres.phi[C.index(J[0], J[1], J[2])] >= 0) near = true;
        }
      EXPECT_EQ(k, near ? CellKind::Ghost : CellKind::Solid) << "cell " << c;
    }
  }
  EXPECT_EQ(promoted, e.counts.promoted);
  EXPECT_EQ(cut, e.counts.fluid_cut + e.counts.solid_cut);
  EXPECT_EQ(cut, owners.size());
  // Image points: one per ghost / solid-cut cell; weights sum to 1, vanish on non-flow nodes;
  // x_BI on the surface side at |phi|, x_IP the mirror of x_G (no pushes) or further out.
  std::size_t records = 0;
  for (std::size_t c = 0; c < g.total; ++c) records += e.kind(c) == CellKind::Ghost || e.kind(c) == CellKind::SolidCut;
  EXPECT_EQ(records, e.image_points.size());
  for (const auto& ip : e.image_points) {
    EXPECT_LT(ip.phi, 0);
    EXPECT_NEAR(norm(ip.x_boundary - ip.x_cell), -ip.phi, 1e-12);
    EXPECT_NEAR(norm(ip.normal), 1.0, 1e-12);
    EXPECT_NEAR(norm(ip.x_image - ip.x_cell), ip.image_distance, 1e-12);
    EXPECT_NEAR(ip.image_distance, -2 * ip.phi + ip.pushes * g.dx[0], 1e-12);
    double sum = 0;
    for (int k = 0; k < ip.stencil_size; ++k) {
      sum += ip.weights[static_cast<std::size_t>(k)];
      const bool flow = is_flow_cell(e.category[ip.stencil[static_cast<std::size_t>(k)]]);
      EXPECT_EQ(flow, !((ip.non_flow_mask >> k) & 1));
      if (!flow) { EXPECT_EQ(ip.weights[static_cast<std::size_t>(k)], 0.0); }
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // plain weights reproduce linear functions at x_IP (inside the hull of the padded centres)
    bool inside = true;
    for (int d = 0; d < DIM; ++d)
      inside = inside && ip.x_image[static_cast<std::size_t>(d)] >= C.coord(d, 0) &&
               ip.x_image[static_cast<std::size_t>(d)] <= C.coord(d, C.count[static_cast<std::size_t>(d)] - 1);
    if (!inside) continue;
    double f = 0;
    for (int k = 0; k < ip.stencil_size; ++k) {
      const auto J = C.ijk(ip.stencil[static_cast<std::size_t>(k)]);
      const Vec3 x = C.point(J[0], J[1], J[2]);
      f += ip.bilinear[static_cast<std::size_t>(k)] * (1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2]);
    }
    EXPECT_NEAR(f, 1 + 2 * ip.x_image[0] - 3 * ip.x_image[1] + 0.5 * ip.x_image[2], 1e-10);
  }
  return cut;
}

template <int DIM>
std::size_t count_pushed(const EmbeddedGeometry<DIM>& e) {
  std::size_t n = 0;
  for (const auto& ip : e.image_points) n += ip.pushes > 0;
  return n;
}

TEST(EmbeddedGeometry, CircleSegmentsDistanceCategoriesImagePoints) {
  const Grid<2> g({64, 64, 1}, {0, 0, 0}, {1, 1, 1});
  const Vec3 c{0.513, 0.493, 0};
  const double R = 0.27;
  const int N = 96;
  const Vec3 v{0.3, -0.2, 0};
  const Surface s = make_circle(c, R, N, v);
  const auto e = build_geometry(g, s, 3.0);
  // perimeter of the polygon
  double len = 0;
  for (const auto& seg : e.segments) {
    len += seg.area;
    EXPECT_NEAR(norm(seg.velocity - v), 0.0, 1e-14);
  }
  EXPECT_NEAR(len, N * 2 * R * std::sin(kPi / N), 1e-13);
  const std::size_t cut = check_consistency(g, s, e);
  // phi = |x - c| - R within the chordal error in the band; sign right everywhere
  const double chord = R * (1 - std::cos(kPi / N));
  std::size_t in_band = 0;
  for (const auto* ls : {&e.centres, &e.nodes}) {
    const auto& L = ls->lattice;
    for (std::size_t i = 0; i < L.size; ++i) {
      const auto I = L.ijk(i);
      const double exact = norm(L.point(I[0], I[1], I[2]) - c) - R;
      if (std::abs(exact) < ls->band_width - chord) {
        EXPECT_NEAR(ls->phi[i], exact, chord + 1e-13);
        ++in_band;
      } else if (std::abs(exact) > ls->band_width + chord) {
        EXPECT_EQ(ls->phi[i], exact > 0 ? ls->band_width : -ls->band_width);
      }
    }
  }
  // image points: in the fluid, at about |phi| from the wall (mirror) -- exact circle distance
  for (const auto& ip : e.image_points) {
    const double d_ip = norm(ip.x_image - c) - R;
    EXPECT_GT(d_ip, 0);
    EXPECT_NEAR(d_ip, ip.image_distance + ip.phi, 2 * chord + 1e-12);
    EXPECT_NEAR(norm(ip.wall_velocity - v), 0.0, 1e-14);
  }
  EXPECT_EQ(e.counts.ghost + e.counts.solid_cut, e.image_points.size());
  std::printf(
      "[ circle 64^2, R=%.2f, %d segments ] segments %zu, cut cells %zu (fluid-cut %zu, solid-cut %zu, promoted %zu), "
      "ghost %zu, pushed image points %zu, band centres %zu, band nodes %zu\n",
      R, N, e.segments.size(), cut, e.counts.fluid_cut, e.counts.solid_cut, e.counts.promoted, e.counts.ghost,
      count_pushed(e), e.work.band_centres, e.work.band_nodes);
  EXPECT_GT(in_band, 0u);
  EXPECT_TRUE(e.side_images.empty());
}

// Exact signed distance of the rectangle with half sizes (a, b) centred at m, rotated by th.
double box_sdf(const Vec3& x, const Vec3& m, double a, double b, double th) {
  const Vec3 r = x - m;
  const double u = std::abs(std::cos(th) * r[0] + std::sin(th) * r[1]) - a;
  const double w = std::abs(-std::sin(th) * r[0] + std::cos(th) * r[1]) - b;
  const double out = std::hypot(std::max(u, 0.0), std::max(w, 0.0));
  return out + std::min(std::max(u, w), 0.0);
}

void check_box_2d(double rotation_deg, bool walls_on_grid_lines) {
  const Grid<2> g({64, 64, 1}, {0, 0, 0}, {1, 1, 1});
  const Vec3 lo{0.25, 0.3125, 0}, hi{0.75, 0.5625, 0};  // on grid lines (multiples of 1/64)
  const Surface s = make_box(2, lo, hi, {0, 0, 0}, rotation_deg);
  const auto e = build_geometry(g, s, 3.0);
  const std::size_t cut = check_consistency(g, s, e);
  const Vec3 m = 0.5 * (lo + hi);
  const double th = rotation_deg * kPi / 180;
  for (const auto* ls : {&e.centres, &e.nodes}) {
    const auto& L = ls->lattice;
    for (std::size_t i = 0; i < L.size; ++i) {
      const auto I = L.ijk(i);
      const double exact = box_sdf(L.point(I[0], I[1], I[2]), m, 0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), th);
      if (std::abs(exact) < ls->band_width - 1e-12) {
        EXPECT_NEAR(ls->phi[i], exact, 1e-13);
      } else {
        EXPECT_EQ(ls->phi[i] > 0, exact > 0);
      }
    }
  }
  for (const auto& seg : e.segments) {  // normals: the four sides
    const double ang = std::atan2(seg.normal[1], seg.normal[0]) - th;
    EXPECT_NEAR(std::remainder(ang, kPi / 2), 0.0, 1e-12);
  }
  if (walls_on_grid_lines) {  // zero convention: only the cells on the solid side are cut (they own the pieces)
    EXPECT_EQ(e.counts.fluid_cut, 0u);
    EXPECT_EQ(e.counts.promoted, e.counts.solid_cut);
  }
  for (const auto& ip : e.image_points)
    EXPECT_GT(box_sdf(ip.x_image, m, 0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), th), 0);
  std::printf(
      "[ box %.0f deg ] segments %zu, cut %zu (fluid-cut %zu, solid-cut %zu, promoted %zu), ghost %zu, pushed %zu\n",
      rotation_deg, e.segments.size(), cut, e.counts.fluid_cut, e.counts.solid_cut, e.counts.promoted, e.counts.ghost,
      count_pushed(e));
}

TEST(EmbeddedGeometry, AlignedBoxWithWallsOnGridLines) { check_box_2d(0, true); }
TEST(EmbeddedGeometry, BoxRotatedBy30Degrees) { check_box_2d(30, false); }

// A box whose sides are made of many coplanar faces, as a solid mesh's boundary arrives from the coupler
// (make_subdivided_box). Faces inside a flat side scan only their prism (signed_distance.h): phi must still
// be the exact box distance everywhere in the band, in 2D and 3D, along the grid and rotated, on both lattices.
template <int DIM>
void check_subdivided_box(const Grid<DIM>& g, const Vec3& lo, const Vec3& hi, const std::array<int, 3>& n, double deg) {
  const Surface s = make_subdivided_box(DIM, lo, hi, n, deg);
  const auto e = build_geometry(g, s, 3.0);
  check_consistency(g, s, e);
  const Vec3 m = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double th = deg * kPi / 180;
  std::size_t in_band = 0;
  for (const auto* ls : {&e.centres, &e.nodes}) {
    const auto& L = ls->lattice;
    for (std::size_t i = 0; i < L.size; ++i) {
      const auto I = L.ijk(i);
      const Vec3 x = L.point(I[0], I[1], I[2]);
      double exact = box_sdf(x, m, half[0], half[1], th);  // 2D; in 3D combined with the z extent
      if (DIM == 3) {
        const double w = std::abs(x[2] - m[2]) - half[2];
        const double in_plane = exact;
        exact = std::hypot(std::max(in_plane, 0.0), std::max(w, 0.0)) + std::min(std::max(in_plane, w), 0.0);
      }
      if (std::abs(exact) < ls->band_width - 1e-12) {
        ++in_band;
        ASSERT_NEAR(ls->phi[i], exact, 1e-12) << "point " << x[0] << " " << x[1] << " " << x[2] << " deg " << deg;
      } else {
        ASSERT_EQ(ls->phi[i] > 0, exact > 0) << "point " << x[0] << " " << x[1] << " " << x[2] << " deg " << deg;
      }
    }
  }
  EXPECT_GT(in_band, 100u);
}

TEST(EmbeddedGeometry, BoxOfManyCoplanarFacesHasTheExactDistance) {
  for (double deg : {0.0, 30.0}) {
    check_subdivided_box(Grid<2>({64, 64, 1}, {0, 0, 0}, {1, 1, 1}), {0.3, 0.33, 0}, {0.71, 0.58, 0}, {12, 7, 1}, deg);
    check_subdivided_box(Grid<3>({24, 24, 24}, {0, 0, 0}, {1, 1, 1}), {0.31, 0.29, 0.33}, {0.72, 0.61, 0.68}, {5, 4, 6},
                         deg);
  }
}

// A bent surface: the faces that share a vertex with a face at angles up to theta scan its prism widened by
// theta (signed_distance.h: compute_face_bend). A subdivided box whose vertices are moved at random (as a deforming
// solid mesh's boundary, angles between faces up to a few 1e-3 rad, and up to 0.1 rad for the larger moves), and the
// icosphere (0.2 rad between faces): the signed distance on both lattices equals the one from whole-box scans
// everywhere, and the widened prisms test fewer points.
TEST(EmbeddedGeometry, BentSurfacesHaveTheDistanceOfWholeBoxScans) {
  const auto compare = [](const Grid<3>& g, const Surface& s, const char* what) {
    GeometryOptions prisms, boxes;
    boxes.flat_face_prisms = false;
    const auto a = build_geometry(g, s, prisms), b = build_geometry(g, s, boxes);
    for (const auto* pair : {&a.centres, &a.nodes}) {
      const auto& other = pair == &a.centres ? b.centres : b.nodes;
      ASSERT_EQ(pair->phi.size(), other.phi.size());
      for (std::size_t i = 0; i < pair->phi.size(); ++i)
        ASSERT_NEAR(pair->phi[i], other.phi[i], 1e-14) << what << " point " << i;
    }
    EXPECT_EQ(a.category, b.category) << what;
    std::printf("%s: %zu distance tests with widened prisms, %zu with whole boxes\n", what, a.work.distance_tests,
                b.work.distance_tests);
    EXPECT_LT(a.work.distance_tests, b.work.distance_tests) << what;
  };
  const Grid<3> g({40, 40, 40}, {0, 0, 0}, {1, 1, 1});
  for (const double amplitude : {1e-5, 1e-4, 2e-3}) {
    Surface box = make_subdivided_box(3, {0.31, 0.29, 0.33}, {0.72, 0.61, 0.68}, {8, 10, 12}, 0.0);
    std::uint64_t state = 12345;
    const auto uniform = [&] {  // deterministic, in [-1, 1)
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 52) - 1.0;
    };
    for (auto& v : box.vertices)
      for (std::size_t d = 0; d < 3; ++d) v[d] += amplitude * uniform();
    compare(g, box, amplitude < 1e-4 ? "box, moves 1e-5" : amplitude < 1e-3 ? "box, moves 1e-4" : "box, moves 2e-3");
  }
  compare(g, make_sphere({0.507, 0.489, 0.512}, 0.3, 3, {0, 0, 0}), "icosphere");
}

TEST(EmbeddedGeometry, SphereAreaVolumeDistance3D) {
  const Grid<3> g({32, 32, 32}, {0, 0, 0}, {1, 1, 1});
  const Vec3 c{0.507, 0.489, 0.512};
  const double R = 0.3;
  const Surface s = make_sphere(c, R, 3, {0.1, 0, 0});
  ASSERT_EQ(s.faces.size(), 1280u);
  const auto e = build_geometry(g, s, 3.0);
  const std::size_t cut = check_consistency(g, s, e);
  double area = 0, vol = 0;
  for (const auto& seg : e.segments) {
    area += seg.area;
    vol += dot(seg.center - c, seg.normal) * seg.area / 3;
  }
  EXPECT_NEAR(area, surface_measure(s), 1e-12);
  EXPECT_NEAR(vol, 4.0 / 3 * kPi * R * R * R, 0.02 * 4.0 / 3 * kPi * R * R * R);  // icosphere vs sphere
  // chordal error: the deepest point of the faces below the sphere
  double inner = R;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const Vec3 n = face_normal(s, static_cast<int>(f));
    inner = std::min(inner, dot(s.vertices[static_cast<std::size_t>(s.faces[f][0])] - c, n));
  }
  const double chord = R - inner;
  for (const auto& b : e.centres.band) {
    const auto I = e.centres.lattice.ijk(b.index);
    const double exact = norm(e.centres.lattice.point(I[0], I[1], I[2]) - c) - R;
    EXPECT_NEAR(e.centres.phi[b.index], exact, chord + 1e-12);
  }
  for (const auto& ip : e.image_points) {
    EXPECT_GT(norm(ip.x_image - c) - R, -chord);
    EXPECT_NEAR(ip.wall_velocity[0], 0.1, 1e-14);
  }
  std::printf(
      "[ sphere 32^3, 1280 faces ] segments %zu, cut %zu, ghost %zu, pushed %zu, clip tests %zu, distance tests %zu, "
      "volume %.6f vs sphere %.6f\n",
      e.segments.size(), cut, e.counts.ghost, count_pushed(e), e.work.clip_tests, e.work.distance_tests, vol,
      4.0 / 3 * kPi * R * R * R);
}

TEST(EmbeddedGeometry, RotatedBoxAndStep3D) {
  const Grid<3> g({24, 24, 24}, {0, 0, 0}, {1, 1, 1});
  const Surface box = make_box(3, {0.3, 0.3, 0.3}, {0.7, 0.6, 0.65}, {0, 0, 0}, 30);
  EXPECT_NEAR(enclosed_volume(box), 0.4 * 0.3 * 0.35, 1e-14);
  check_consistency(g, box, build_geometry(g, box, 3.0));
  // a step standing on the floor: its lower part lies outside the padded grid
  const Surface step = make_step(3, {0.5, -0.5, -0.5}, {1.5, 0.25, 1.5});
  const auto e = build_geometry(g, step, 3.0);
  EXPECT_GT(e.counts.solid_cut + e.counts.fluid_cut, 0u);
  EXPECT_EQ(e.kind(g.index(20, 2, 12)), CellKind::Solid);
  EXPECT_EQ(e.kind(g.index(3, 2, 12)), CellKind::Fluid);
}

TEST(EmbeddedGeometry, MovingCircleShiftsCategoriesByOneCell) {
  const int n = 64;
  const Grid<2> g({n, n, 1}, {0, 0, 0}, {1, 1, 1});
  const double h = 1.0 / n;
  Surface s = make_circle({0.4 + 0.003, 0.5 - 0.002, 0}, 0.2, 64, {2.0, 0, 0});
  const auto e0 = build_geometry(g, s, 3.0);
  move_surface(s, h / 2.0);  // one cell
  const auto e1 = build_geometry(g, s, 3.0);
  std::size_t changed = 0, mismatched = 0;
  for (int j = -2; j < n + 2; ++j)
    for (int i = -2; i < n + 2; ++i) {
      changed += e1.category[g.index(i, j)] != e0.category[g.index(i, j)];
      if (i + 1 < n + 2) mismatched += e1.category[g.index(i + 1, j)] != e0.category[g.index(i, j)];
    }
  EXPECT_GT(changed, 40u);    // the categories move with the body...
  EXPECT_EQ(mismatched, 0u);  // ...by exactly one cell
  // rebuilding into the previous cycle's buffers gives the same result
  GeometryOptions opt;
  EmbeddedGeometry<2> reused = e0;
  build_geometry(g, s, opt, reused);
  EXPECT_EQ(reused.category, e1.category);
  EXPECT_EQ(reused.centres.phi, e1.centres.phi);
  EXPECT_EQ(reused.nodes.phi, e1.nodes.phi);
  EXPECT_EQ(reused.image_points.size(), e1.image_points.size());
  EXPECT_EQ(e0.counts.ghost, e1.counts.ghost);
  EXPECT_EQ(e0.counts.solid_cut, e1.counts.solid_cut);
  check_consistency(g, s, e1);
}

// Thin bodies are accepted: every flow cell next to a cell that serves the other side of the body (or next to a
// flow cell across a plate thinner than a cell) gets its own side image, built on its side of the body only.
TEST(EmbeddedGeometry, ThinBodiesGetSideImagesOnTheirOwnSide) {
  const Grid<2> g({64, 64, 1}, {0, 0, 0}, {1, 1, 1});
  const double h = 1.0 / 64;
  struct Count {
    std::size_t shared = 0, blocked = 0;
  };
  auto check = [&](double y0, double thickness) {
    const auto e = build_geometry(g, make_box(2, {0.3, y0, 0}, {0.7, y0 + thickness, 0}), GeometryOptions{});
    Count n;
    for (const auto& si : e.side_images) {
      (si.blocked ? n.blocked : n.shared) += 1;
      const auto& ip = si.image;
      EXPECT_EQ(si.direction, 1);  // along y only: the plate's ends are thick along x
      EXPECT_NEAR(std::abs(ip.normal[1]), 1.0, 1e-12);
      // F in front of its wall, X behind it, the image point in front, and only cells in front carry weight
      const auto F = e.centres.lattice.ijk(si.flow_cell);
      const Vec3 xF = e.centres.lattice.point(F[0], F[1], F[2]);
      EXPECT_GE(dot(xF - ip.x_boundary, ip.normal), 0.0);
      EXPECT_LT(dot(ip.x_cell - ip.x_boundary, ip.normal), 0.0);
      EXPECT_GE(dot(ip.x_image - ip.x_boundary, ip.normal), 0.0);
      double wsum = 0;
      for (int k = 0; k < ip.stencil_size; ++k) {
        const auto uk = static_cast<std::size_t>(k);
        if (ip.weights[uk] == 0) continue;
        wsum += ip.weights[uk];
        const auto J = e.centres.lattice.ijk(ip.stencil[uk]);
        EXPECT_TRUE(is_flow_cell(e.category[ip.stencil[uk]]));
        EXPECT_GT(dot(e.centres.lattice.point(J[0], J[1], J[2]) - ip.x_boundary, ip.normal), -1e-12);
      }
      EXPECT_NEAR(wsum, 1.0, 1e-12);
      EXPECT_GE(si.face_distance, 0.0);  // 0: F's centre on its wall
      EXPECT_LE(si.face_distance, 1.0);
    }
    return n;
  };
  const std::size_t columns = 26;  // cell centres with 0.3 < x < 0.7 on 64 cells: 19.5 ... 44.5 (x 1/64)
  // one cell thick at offsets against the grid: one solid row, whose ghost serves its nearer side; the cells on
  // the other side see it through side images (offset 0: both walls on grid lines, a tie, still one side)
  for (double off : {0.0, 0.3, 0.77}) {
    const Count n = check(0.5 + off * h, h);
    EXPECT_EQ(n.blocked, 0u) << off;
    EXPECT_GE(n.shared, columns - 2) << off;  // the end columns' ghosts may see the plate's ends
    EXPECT_LE(n.shared, 2 * columns + 4) << off;
  }
  // thinner than a cell between two centres: blocked faces, seen from both sides
  for (double t : {0.3, 0.6}) {
    const Count n = check(0.5 - 0.45 * h, t * h);  // between the centres 0.5 -+ h/2
    EXPECT_EQ(n.blocked, 2 * columns) << t;
  }
  // both walls through cell centres (those are flow cells by the zero convention): one solid row left
  EXPECT_GE(check(0.5 + 0.5 * h, 2 * h).shared, columns - 2);
  // 1.6 cells with both centres near the top: the lower flow cells see the plate through side images
  EXPECT_GE(check(0.5 + 0.6 * h, 1.6 * h).shared, columns - 2);
  // two cells or more: each side has its own ghosts, nothing two-sided
  for (double off : {0.0, 0.3, 0.77}) EXPECT_EQ(check(0.5 + off * h, 2 * h).shared, 0u) << off;
  EXPECT_EQ(check(0.5 + 0.3 * h, 4 * h).shared, 0u);
  // 1D: an interval one cell wide is accepted, with one side image
  const Grid<1> g1({40, 1, 1}, {0, 0, 0}, {1, 1, 1});
  const auto e1 = build_geometry(g1, make_interval(0.5 + 0.01, 0.5 + 0.01 + 1.0 / 40), 3.0);
  EXPECT_EQ(e1.side_images.size(), 1u);
}

TEST(EmbeddedGeometry, WorkFollowsTheSurfaceNotTheGrid) {
  // Same body in physical units on 512^2 and 1024^2; segments span ~13 / 26 cells.
  auto run = [](int n, double R, int segments) {
    const Grid<2> g({n, n, 1}, {0, 0, 0}, {1, 1, 1});
    return build_geometry(g, make_circle({0.503, 0.497, 0}, R, segments), 3.0);
  };
  const auto a = run(512, 0.3, 64), b = run(1024, 0.3, 64), small = run(512, 0.15, 32);
  {  // a second cycle reusing the buffers (the way a solver calls it)
    const Grid<2> g({1024, 1024, 1}, {0, 0, 0}, {1, 1, 1});
    EmbeddedGeometry<2> again = b;
    build_geometry(g, make_circle({0.503 + 0.3 / 1024, 0.497, 0}, 0.3, 64), GeometryOptions{}, again);
    const auto& t = again.timing;
    std::printf(
        "[ timing 1024^2, reused buffers ] surface %.3f ms, clip %.3f ms, distance %.3f ms, categories %.3f ms, "
        "image points %.3f ms, side images %.3f ms, total %.3f ms\n",
        1e3 * t.surface, 1e3 * t.clip, 1e3 * t.distance, 1e3 * t.categories, 1e3 * t.image_points, 1e3 * t.side_images,
        1e3 * t.total);
  }
  auto cut = [](const auto& e) { return static_cast<double>(e.counts.fluid_cut + e.counts.solid_cut); };
  const double r_cut = cut(b) / cut(a), r_clip = double(b.work.clip_tests) / double(a.work.clip_tests),
               r_dist = double(b.work.distance_tests) / double(a.work.distance_tests);
  std::printf(
      "[ locality ] 512^2: cut %.0f, clip tests %zu, distance tests %zu, band %zu; 1024^2: cut %.0f, clip tests %zu, "
      "distance tests %zu, band %zu; ratios cut %.2f clip %.2f distance %.2f (all cells: 4)\n",
      cut(a), a.work.clip_tests, a.work.distance_tests, a.work.band_centres, cut(b), b.work.clip_tests,
      b.work.distance_tests, b.work.band_centres, r_cut, r_clip, r_dist);
  for (const auto* e : {&a, &b})
    std::printf(
        "[ timing %s ] surface %.3f ms, clip %.3f ms, distance %.3f ms, categories %.3f ms, image points %.3f ms, "
        "side images %.3f ms, total %.3f ms\n",
        e == &a ? "512^2" : "1024^2", 1e3 * e->timing.surface, 1e3 * e->timing.clip, 1e3 * e->timing.distance,
        1e3 * e->timing.categories, 1e3 * e->timing.image_points, 1e3 * e->timing.side_images, 1e3 * e->timing.total);
  EXPECT_NEAR(r_cut, 2.0, 0.1);
  EXPECT_GT(r_clip, 1.7);
  EXPECT_LT(r_clip, 2.3);
  EXPECT_GT(r_dist, 1.6);
  EXPECT_LT(r_dist, 2.4);
  // and with the body size at a fixed grid (same segment length)
  const double r_size = double(a.work.distance_tests) / double(small.work.distance_tests);
  std::printf("[ locality ] 512^2 R=0.15: distance tests %zu; R=0.3 / R=0.15: %.2f\n", small.work.distance_tests,
              r_size);
  EXPECT_GT(r_size, 1.6);
  EXPECT_LT(r_size, 2.4);
}

TEST(EmbeddedGeometry, Interval1D) {
  const Grid<1> g({40, 1, 1}, {0, 0, 0}, {1, 1, 1});
  const double a = 0.5 + 0.013, b = 0.8 - 0.004;
  const Surface s = make_interval(a, b, 1.5);
  const auto e = build_geometry(g, s, 3.0);
  check_consistency(g, s, e);
  for (int i = -2; i < 42; ++i) {
    const double x = g.center(0, i), exact = std::max(a - x, x - b);
    if (std::abs(exact) < e.band_width) { EXPECT_NEAR(e.centres.phi[g.index(i)], exact, 1e-14); }
  }
  // a = 0.513 lies in cell 20 (centre 0.5125 < a): fluid-cut; cell 21 ghost... the body's left end
  EXPECT_EQ(e.kind(g.index(20)), CellKind::FluidCut);
  EXPECT_EQ(e.kind(g.index(21)), CellKind::Ghost);
  EXPECT_EQ(e.kind(g.index(22)), CellKind::Ghost);
  EXPECT_EQ(e.kind(g.index(23)), CellKind::Solid);
  for (const auto& ip : e.image_points) {
    EXPECT_EQ(ip.stencil_size, 2);
    EXPECT_EQ(ip.wall_velocity[0], 1.5);
  }
}

TEST(EmbeddedGeometry, OpenOrInconsistentSurfacesAreRejected) {
  Surface open = make_circle({0.5, 0.5, 0}, 0.2, 16);
  open.faces.pop_back();
  EXPECT_THROW(build_topology(open), std::runtime_error);
  Surface flipped = make_sphere({0.5, 0.5, 0.5}, 0.2, 1);
  std::swap(flipped.faces[3][1], flipped.faces[3][2]);
  EXPECT_THROW(build_topology(flipped), std::runtime_error);
  Surface holed = make_sphere({0.5, 0.5, 0.5}, 0.2, 1);
  holed.faces.erase(holed.faces.begin());
  EXPECT_THROW(build_topology(holed), std::runtime_error);
  const Grid<2> g({16, 16, 1}, {0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(build_geometry(g, make_sphere({0.5, 0.5, 0.5}, 0.2, 0), 3.0),
               std::runtime_error);  // 3D surface, 2D grid
}

// A body that moves and deforms keeps its faces: the topology of the cycle before is reused and only its normals
// are recomputed, to the same bits as a topology built anew; new faces are checked again.
TEST(EmbeddedGeometry, ADeformedSurfaceReusesItsTopologyWithTheSameNormals) {
  for (const Surface& start : {make_sphere({0.5, 0.5, 0.5}, 0.2, 2), make_circle({0.5, 0.5, 0}, 0.2, 24)}) {
    SurfaceTopology reused = build_topology(start);
    Surface moved = start;
    for (std::size_t v = 0; v < moved.vertices.size(); ++v)  // a squeeze and a shift
      for (int d = 0; d < start.dim; ++d)
        moved.vertices[v][static_cast<std::size_t>(d)] +=
            0.01 * std::sin(3.0 * static_cast<double>(v) + d) + (d == 0 ? 0.003 : 0.0);
    update_topology(moved, reused);
    const SurfaceTopology fresh = build_topology(moved);
    ASSERT_EQ(reused.face_normal.size(), fresh.face_normal.size());
    for (std::size_t f = 0; f < fresh.face_normal.size(); ++f) {
      EXPECT_EQ(reused.face_normal[f], fresh.face_normal[f]);
      EXPECT_EQ(reused.face_measure[f], fresh.face_measure[f]);
    }
    for (std::size_t v = 0; v < fresh.vertex_normal.size(); ++v)
      EXPECT_EQ(reused.vertex_normal[v], fresh.vertex_normal[v]);
    EXPECT_EQ(reused.edge_normal, fresh.edge_normal);
    EXPECT_EQ(reused.face_edges, fresh.face_edges);
    Surface flipped = moved;  // other faces: the connectivity is checked again
    std::swap(flipped.faces[3][0], flipped.faces[3][1]);
    EXPECT_THROW(update_topology(flipped, reused), std::runtime_error);
  }
}

TEST(EmbeddedGeometry, SceneBodiesBecomeClosedSurfaces) {
  EmbeddedSettings set2;
  EmbeddedBody box;
  box.shape = EmbeddedBody::Shape::Box;
  box.lower = {0.1, 0.1, 0}, box.upper = {0.3, 0.2, 0}, box.rotation_deg = 15;
  EmbeddedBody circle;
  circle.shape = EmbeddedBody::Shape::Circle;
  circle.center = {0.6, 0.6, 0}, circle.radius = 0.1, circle.segments = 32, circle.velocity = {1, 0, 0};
  EmbeddedBody poly;
  poly.shape = EmbeddedBody::Shape::Polygon;
  poly.vertices = {{0.7, 0.1}, {0.9, 0.1}, {0.8, 0.3}};  // counter-clockwise
  EmbeddedBody step;
  step.shape = EmbeddedBody::Shape::Step;
  step.lower = {0.45, -0.02, 0}, step.upper = {0.6, 0.05, 0};  // below the floor, inside the ghost layers
  set2.bodies = {box, circle, poly, step};
  const Surface s2 = surface_of(set2, 2);
  EXPECT_NO_THROW(build_topology(s2));
  EXPECT_NEAR(enclosed_volume(s2), 0.02 + 32 * 0.5 * 0.01 * std::sin(2 * kPi / 32) + 0.02 + 0.15 * 0.07, 1e-13);
  const Grid<2> g({64, 64, 1}, {0, 0, 0}, {1, 1, 1});
  check_consistency(g, s2, build_geometry(g, s2, 3.0));
  EmbeddedBody sphere;
  sphere.shape = EmbeddedBody::Shape::Sphere;
  sphere.center = {0.5, 0.5, 0.5}, sphere.radius = 0.25, sphere.segments = 2;
  const Surface s3 = surface_of(sphere, 3);
  EXPECT_EQ(s3.faces.size(), 320u);
  EXPECT_NO_THROW(build_topology(s3));
  EXPECT_GT(enclosed_volume(s3), 0);
}

}  // namespace
}  // namespace cosim::fluid::embedded

namespace cosim::fluid::embedded {
namespace {

// The bodies of the issue-4 scenes (configs/*.yaml) build without refusal on their meshes.
TEST(EmbeddedGeometry, SceneBodiesOnTheirMeshes) {
  {  // low_mach_step: 640x320, the step reaching below the floor; also one running past the outlet
    const Grid<2> g({640, 320, 1}, {0, 0, 0}, {2, 1, 1});
    const auto long_step = build_geometry(g, make_step(2, {0.5, -0.1, 0}, {2.1, 0.35, 0}), 3.0);
    EXPECT_EQ(long_step.kind(g.index(300, 50)), CellKind::Solid);
    EXPECT_EQ(long_step.kind(g.index(600, 50)), CellKind::Solid);
    const auto e = build_geometry(g, make_step(2, {0.5, -0.1, 0}, {0.8, 0.35, 0}), 3.0);
    EXPECT_EQ(e.kind(g.index(200, 50)), CellKind::Solid);
    EXPECT_EQ(e.kind(g.index(100, 50)), CellKind::Fluid);
    EXPECT_EQ(e.kind(g.index(300, 50)), CellKind::Fluid);
    EXPECT_GT(e.counts.solid_cut, 0u);
    std::printf("[ low_mach_step 640x320 ] segments %zu, cut %zu, ghost %zu, total %.3f ms\n", e.segments.size(),
                e.counts.fluid_cut + e.counts.solid_cut, e.counts.ghost, 1e3 * e.timing.total);
  }
  {  // supersonic_cylinder: 240^2, 256 segments
    const Grid<2> g({240, 240, 1}, {0, 0, 0}, {2, 2, 1});
    const Surface s = make_circle({1.2, 1.0, 0}, 0.25, 256);
    check_consistency(g, s, build_geometry(g, s, 3.0));
  }
  {  // embedded_advection: a 4.2 x 3.3 cell box on 13x13, moving diagonally by a fraction of a cell per cycle
    const Grid<2> g({13, 13, 1}, {0, 0, 0}, {1, 1, 1});
    Surface s = make_box(2, {0.3, 0.3, 0}, {0.62, 0.55, 0}, {0.1, 0.1, 0});
    EmbeddedGeometry<2> e;
    for (int cycle = 0; cycle < 40; ++cycle) {
      ASSERT_NO_THROW(build_geometry(g, s, GeometryOptions{}, e)) << "cycle " << cycle;
      check_consistency(g, s, e);
      move_surface(s, 0.05);
    }
  }
}

TEST(EmbeddedGeometry, ThinPlate3DGetsSideImages) {
  const Grid<3> g({24, 24, 24}, {0, 0, 0}, {1, 1, 1});
  const double h = 1.0 / 24;
  const auto thin = build_geometry(g, make_box(3, {0.3, 0.3, 0.5 + 0.4 * h}, {0.7, 0.7, 0.5 + 1.4 * h}), 3.0);
  std::size_t along_z = 0;
  for (const auto& si : thin.side_images) along_z += si.direction == 2 && !si.blocked;
  EXPECT_GE(along_z, 8u * 8u);  // about one per column of the 9.6 x 9.6 cell plate
  EXPECT_TRUE(
      build_geometry(g, make_box(3, {0.3, 0.3, 0.5 + 0.4 * h}, {0.7, 0.7, 0.5 + 5.4 * h}), 3.0).side_images.empty());
}

}  // namespace
}  // namespace cosim::fluid::embedded

namespace cosim::fluid::embedded {
namespace {

// Total measure of the segments of a consistent geometry whose normal points to -x (the box's left face).
template <int DIM>
double left_face_measure(const Grid<DIM>& g, const Surface& s) {
  const auto e = build_geometry(g, s, 3.0);
  check_consistency(g, s, e);
  double m = 0;
  for (const auto& seg : e.segments)
    if (seg.normal[0] < -0.99) m += seg.area;
  return m;
}

// A moving wall arrives on a grid line up to round-off (x = 0.4 - 2e-15 after summing steps): its pieces lie in
// the cell face shared by two cells and must belong to one of them, in 2D and 3D, on either side of the line.
TEST(EmbeddedGeometry, WallOnAGridLineUpToRoundOffKeepsItsSegments) {
  for (double eps : {-2e-15, 0.0, 2e-15}) {
    EXPECT_NEAR(left_face_measure(Grid<2>({20, 20}, {0, 0}, {1, 1}), make_box(2, {0.4 + eps, 0.3, 0}, {0.75, 0.7, 0})),
                0.4, 1e-12)
        << eps;
    EXPECT_NEAR(left_face_measure(Grid<3>({10, 10, 10}, {0, 0, 0}, {1, 1, 1}),
                                  make_box(3, {0.4 + eps, 0.3, 0.3}, {0.75, 0.7, 0.7})),
                0.16, 1e-12)
        << eps;
  }
}

}  // namespace
}  // namespace cosim::fluid::embedded

namespace cosim::fluid::embedded {
namespace {

// A body moving a fraction of a cell per cycle, rebuilt into the same buffers: the level sets skip the dense
// fill and only reset the previous band (signed_distance.h); phi and categories must equal a fresh build's,
// also after a jump longer than half the band (which takes the full fill again).
template <int DIM>
void check_incremental(const Grid<DIM>& g, Surface s) {
  GeometryOptions opt;
  EmbeddedGeometry<DIM> reused;
  build_geometry(g, s, opt, reused);
  for (int step = 0; step < 8; ++step) {
    move_surface(s, step == 5 ? 4.0 : 0.3);  // velocity h per unit time: 0.3 cells, once 4 cells
    build_geometry(g, s, opt, reused);
    const EmbeddedGeometry<DIM> fresh = build_geometry(g, s, opt);
    ASSERT_EQ(reused.category, fresh.category) << step;
    ASSERT_EQ(reused.centres.phi, fresh.centres.phi) << step;
    ASSERT_EQ(reused.nodes.phi, fresh.nodes.phi) << step;
    ASSERT_EQ(reused.image_points.size(), fresh.image_points.size()) << step;
  }
}

TEST(EmbeddedGeometry, IncrementalLevelSetEqualsAFreshBuild) {
  const int n = 48;
  const double h = 1.0 / n;
  check_incremental(Grid<2>({n, n, 1}, {0, 0, 0}, {1, 1, 1}), make_circle({0.31, 0.52, 0}, 0.2, 64, {h, 0.4 * h, 0}));
  const int m = 20;
  check_incremental(Grid<3>({m, m, m}, {0, 0, 0}, {1, 1, 1}),
                    make_sphere({0.33, 0.48, 0.51}, 0.22, 2, {1.0 / m, 0, 0.5 / m}));
}

}  // namespace
}  // namespace cosim::fluid::embedded

namespace cosim::fluid::embedded {
namespace {

// A piston filling a channel: its side faces lie on the channel walls. Inside the domain every ghost takes its
// image point from an end face (normal +-x), also in the corner rows, where it is as close to the side face;
// the side faces give no segments. With periodic walls the side faces are real interfaces and are kept.
TEST(EmbeddedGeometry, FacesOnTheDomainWallLeaveTheCornerGhostsToTheEndFaces) {
  const Grid<2> g({20, 8}, {0, 0, 0}, {2.0, 0.8, 0});
  const Surface s = make_box(2, {0.5, 0.0, 0}, {1.0, 0.8, 0});
  const auto e = build_geometry(g, s, 3.0);
  std::size_t inside = 0;
  for (const auto& ip : e.image_points) {
    if (ip.x_cell[1] < 0 || ip.x_cell[1] > 0.8) continue;  // ghost layers outside the channel
    ++inside;
    EXPECT_NEAR(std::abs(ip.normal[0]), 1.0, 1e-12) << ip.x_cell[0] << " " << ip.x_cell[1];
  }
  EXPECT_GE(inside, 2u * 2u * 8u);  // two ghost columns at either end in every row (and a few near the walls)
  for (const auto& seg : e.segments) EXPECT_NEAR(std::abs(seg.normal[0]), 1.0, 1e-12);
  double length = 0;
  for (const auto& seg : e.segments) length += seg.area;
  EXPECT_NEAR(length, 1.6, 1e-12);  // the two end faces only
  GeometryOptions periodic;
  periodic.periodic = {false, true, false};
  const auto ep = build_geometry(g, s, periodic);
  double plength = 0;
  for (const auto& seg : ep.segments) plength += seg.area;
  EXPECT_NEAR(plength, 2.6, 1e-12);  // all four faces
}

}  // namespace
}  // namespace cosim::fluid::embedded

namespace cosim::fluid::embedded {
namespace {

// The geometry's parallel parts (the clip over faces, the band's signs) give the same geometry on two threads as
// on one: the same pieces in the same order, the same distances, categories and image points. (The test suite
// runs on one thread, so this is where the threaded paths are checked.)
TEST(EmbeddedGeometry, TwoThreadsBuildTheSameGeometryAsOne) {
  const int n = 48;
  const Grid<3> g({n, n, n}, {0, 0, 0}, {1, 1, 1});
  const Surface target = make_subdivided_box(3, {0.45, 0.25, 0.25}, {0.55, 0.75, 0.75}, {4, 16, 16});
  ASSERT_GT(target.faces.size(), 256u);  // above the clip's one-thread size
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const EmbeddedGeometry<3> one = build_geometry<3>(g, target, GeometryOptions{});
  omp_set_num_threads(2);
  const EmbeddedGeometry<3> two = build_geometry<3>(g, target, GeometryOptions{});
  omp_set_num_threads(saved);
  ASSERT_EQ(one.segments.size(), two.segments.size());
  ASSERT_GT(one.segments.size(), 1000u);
  for (std::size_t i = 0; i < one.segments.size(); ++i) {
    const InterfaceSegment &a = one.segments[i], &b = two.segments[i];
    ASSERT_TRUE(a.cell == b.cell && a.face == b.face && a.area == b.area && a.center == b.center &&
                a.first_point == b.first_point && a.point_count == b.point_count)
        << "segment " << i;
  }
  EXPECT_EQ(one.segment_points, two.segment_points);
  EXPECT_EQ(one.centres.phi, two.centres.phi);
  EXPECT_EQ(one.nodes.phi, two.nodes.phi);
  EXPECT_EQ(one.category, two.category);
  ASSERT_EQ(one.image_points.size(), two.image_points.size());
  for (std::size_t i = 0; i < one.image_points.size(); ++i)
    ASSERT_TRUE(one.image_points[i].cell == two.image_points[i].cell &&
                one.image_points[i].x_boundary == two.image_points[i].x_boundary)
        << "image point " << i;
}

}  // namespace
}  // namespace cosim::fluid::embedded
