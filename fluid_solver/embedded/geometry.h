// One cycle of the embedded-boundary geometry (paper section 6 and section 8 step 2; docs/methods.md
// §5.1-5.2): interface segments, narrow-band signed distance at cell centres and nodes, cell
// categories (Table 1), ghost / solid-cut image points, side images of thin bodies, with a timing breakdown.
// Independent of the flow solver's state arrays: input is a Grid and a Surface, output plain arrays.
// Work is O(faces + cells near the surface); the only O(all cells) part is filling the dense
// output arrays (phi, category) with std::fill spans.
#pragma once

#include <chrono>
#include <stdexcept>
#include <vector>

#include "fluid_solver/core/embedded_state.h"
#include "fluid_solver/embedded/categorize.h"
#include "fluid_solver/embedded/clip.h"
#include "fluid_solver/embedded/domain_wall_faces.h"
#include "fluid_solver/embedded/image_points.h"
#include "fluid_solver/embedded/signed_distance.h"
#include "fluid_solver/embedded/thin_body.h"

namespace cosim::fluid::embedded {

struct GeometryOptions {
  double band_cells =
      3;  // narrow band half-width at centres [cells of the largest dx]; raised to cover the ghost layers
  double node_band_cells = 1.5;  // band at nodes: Table 1 needs only their sign (exact |phi_N| below it); >= 1.5
  int ghost_layers = 2;          // MUSCL reach: ghosts are solid cells within this many cells of a flow cell
  double opposite_cos = -0.9;    // thin-body test (thin_body.h)
  ImagePointOptions image{};
  // Directions whose domain boundary is periodic: there a body face on the boundary plane has fluid behind
  // it. On other sides a face that lies in the boundary plane with its solid inside the domain is the domain
  // wall already: it gives no segments and no closest face inside the domain (domain_wall_faces()).
  std::array<bool, 3> periodic{false, false, false};
  bool flat_face_prisms =
      true;  // faces inside a flat region scan only their prism (signed_distance.h); off: for benchmarks
};

// Seconds spent per part in one build_geometry call.
struct GeometryTiming {
  double surface = 0;       // topology and normals of the surface
  double clip = 0;          // interface segments
  double distance = 0;      // phi at centres and nodes
  double categories = 0;    // Table 1 and ghost layers
  double image_points = 0;  // intercepts, image points, stencils
  double side_images = 0;   // two-sided ghost states of thin bodies
  double total = 0;
};

// Work counters: they show that the work follows the surface, not the grid.
struct GeometryWork {
  std::size_t clip_tests = 0;      // face-vs-cell clip tests
  std::size_t distance_tests = 0;  // point-vs-face distance evaluations (centres + nodes)
  std::size_t band_centres = 0, band_nodes = 0;
};

template <int DIM>
struct EmbeddedGeometry {
  double band_width = 0;                   // [m]; |phi_C| is exact below it, clamped to it above
  LevelSet<DIM> centres;                   // phi_C per padded cell (index == Grid::index)
  LevelSet<DIM> nodes;                     // phi_N per cell node (node (I,J,K) = lower corner of padded cell (I,J,K));
                                           // exact below nodes.band_width, +-nodes.band_width above
  std::vector<std::uint8_t> category;      // CellKind per padded cell
  std::vector<InterfaceSegment> segments;  // sorted by owning cell
  std::vector<Vec3> segment_points;        // polygons of the segments (2 points in 2D)
  std::vector<ImagePoint> image_points;    // every ghost and solid-cut cell
  std::vector<SideImage> side_images;      // thin bodies: flow cells' own views across them (thin_body.h)
  SurfaceTopology topology;                // the surface's normals; its connectivity is kept from cycle to cycle
  FaceBend bend;                           // the prisms' widening per face (signed_distance.h), this cycle's
  CategoryCounts counts;
  GeometryWork work;
  GeometryTiming timing;

  const std::vector<double>& phi_center() const { return centres.phi; }
  const std::vector<double>& phi_node() const { return nodes.phi; }
  CellKind kind(std::size_t cell) const { return static_cast<CellKind>(category[cell]); }
};

// Rebuilds `e` for this cycle, reusing its buffers (pass the previous cycle's geometry on the same
// grid: then no dense array is allocated or cleared, only the band of the previous cycle).
template <int DIM>
void build_geometry(const Grid<DIM>& g, const Surface& s, const GeometryOptions& opt, EmbeddedGeometry<DIM>& e) {
  using clock = std::chrono::steady_clock;
  auto seconds = [](clock::time_point a, clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  if (s.dim != DIM) throw std::runtime_error("embedded geometry: the surface dimension does not match the grid");
  const auto t0 = clock::now();
  e.work = {};
  update_topology(s, e.topology);
  const SurfaceTopology& topo = e.topology;
  const DomainWallFaces skip = domain_wall_faces(g, s, topo, opt.periodic);
  const auto t1 = clock::now();
  clip_surface(g, s, topo, e.segments, e.segment_points, e.work.clip_tests, &skip);
  const auto t2 = clock::now();
  // Band: at least the ghost reach (ghost centres are up to ghost_layers * dx_max from the surface).
  double hmax = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(DIM); ++d) hmax = std::max(hmax, g.dx[d]);
  e.band_width = std::max(opt.band_cells, opt.ghost_layers + 0.25) * hmax;
  // Node band >= 1.5 dx keeps the row-fill sign robust (band points next to a gap are >= dx/2 away).
  const double node_band = std::min(e.band_width, std::max(opt.node_band_cells, 1.5) * hmax);
  e.category.resize(g.total);
  e.centres.lattice = centre_lattice(g);
  e.nodes.lattice = node_lattice(g);
  // The two level sets side by side (each writes its own only): the centres' band, twice as wide, is found on one
  // thread while the other finds and finishes the nodes' band; then the centres are finished on the threads.
  std::size_t centre_tests = 0, node_tests = 0;
  const FaceBend* bend = nullptr;  // null: whole grown boxes (GeometryOptions::flat_face_prisms off)
  if (opt.flat_face_prisms) {
    compute_face_bend(s, topo, e.bend);
    bend = &e.bend;
  }
#pragma omp parallel sections num_threads(2) if (omp_get_max_threads() > 1 && s.faces.size() >= 256)
  {
#pragma omp section
    scan_level_set(e.centres, s, topo, e.band_width, centre_tests, &e.category, &skip, bend);
#pragma omp section
    {
      scan_level_set(e.nodes, s, topo, node_band, node_tests, nullptr, &skip, bend);
      finish_level_set(e.nodes, s, topo, node_band);
    }
  }
  e.work.distance_tests += centre_tests + node_tests;
  finish_level_set(e.centres, s, topo, e.band_width, &e.category, static_cast<std::uint8_t>(CellKind::Fluid),
                   static_cast<std::uint8_t>(CellKind::Solid));
  e.work.band_centres = e.centres.band.size();
  e.work.band_nodes = e.nodes.band.size();
  const auto t3 = clock::now();
  e.counts = categorize(e.centres, e.nodes, e.segments, opt.ghost_layers, e.category);
  const auto t4 = clock::now();
  build_image_points(g, e.centres, s, e.category, e.image_points, opt.image);
  const auto t5 = clock::now();
  e.side_images = find_side_images(g, e.centres, s, e.category, opt.opposite_cos, opt.image);
  const auto t6 = clock::now();
  e.timing = {seconds(t0, t1), seconds(t1, t2), seconds(t2, t3), seconds(t3, t4),
              seconds(t4, t5), seconds(t5, t6), seconds(t0, t6)};
}

template <int DIM>
EmbeddedGeometry<DIM> build_geometry(const Grid<DIM>& g, const Surface& s, const GeometryOptions& opt) {
  EmbeddedGeometry<DIM> e;
  build_geometry(g, s, opt, e);
  return e;
}

template <int DIM>
EmbeddedGeometry<DIM> build_geometry(const Grid<DIM>& g, const Surface& s, double band_cells = 3) {
  GeometryOptions opt;
  opt.band_cells = band_cells;
  return build_geometry(g, s, opt);
}

}  // namespace cosim::fluid::embedded
