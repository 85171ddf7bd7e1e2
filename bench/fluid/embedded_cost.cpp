// Cost of the embedded boundary per cycle: a circle moving through a 512 x 512 background, two
// body sizes, against the same run without the body (measured side by side in one process).
// Prints a markdown table: the geometry time per cycle (clip, distance, categories, image points)
// as a fraction of the cycle. The solver-side work (ghost fill, mirrored wall faces) is O(ghost
// cells) and below the timing noise of a cycle on this machine.
// Then the geometry alone for 3D bodies made of many coplanar faces (the boundary of a structured solid mesh,
// as the coupler sends it): build time per cycle of a box moving through the grid, with the flat faces
// scanning only their prisms and without (GeometryOptions::flat_face_prisms), side by side.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <omp.h>

#include <chrono>
#include <vector>

#include "fluid_solver/embedded/geometry.h"
#include "fluid_solver/embedded/shapes.h"

#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/core/simulation.h"

using namespace cosim::fluid;

namespace {
std::string scene(int n, double radius, int segments) {
  std::string s = fmt::format(R"(
fluid:
  mesh: {{cells: [{0}, {0}], lower: [0.0, 0.0], upper: [1.0, 1.0]}}
  phases: [{{name: gas, eos: {{type: ideal_gas, gamma: 1.4}}}}]
  time: {{end: 1.0}}
  threads: 1
  initial:
    state: {{rho: 1.0, velocity: [0.5, 0.2], p: 1.0}}
)",
                              n);
  if (radius > 0)
    s += fmt::format(
        "  embedded:\n    bodies:\n      - {{shape: circle, center: [0.45, 0.45], radius: {}, segments: {}, "
        "velocity: [0.3, 0.1]}}\n",
        radius, segments);
  return s;
}

// Geometry build time per cycle [s] of `s` moving by a fraction of a cell per cycle (incremental level sets);
// jitter > 0: every vertex also moves by up to `jitter` [m] at random each cycle about its rigid place, a mesh that
// deforms as well (angles between its faces of jitter / face size).
double geometry_seconds_3d(const Grid<3>& g, embedded::Surface s, const embedded::Vec3& cells_per_cycle, bool prisms,
                           int cycles, embedded::GeometryTiming* parts = nullptr, double jitter = 0.0) {
  embedded::GeometryOptions opt;
  opt.flat_face_prisms = prisms;
  embedded::EmbeddedGeometry<3> e;
  embedded::set_rigid_velocity(
      s, {cells_per_cycle[0] * g.dx[0], cells_per_cycle[1] * g.dx[1], cells_per_cycle[2] * g.dx[2]});
  embedded::build_geometry(g, s, opt, e);  // warm-up
  double total = 0;
  std::uint64_t state = 2024;
  const auto uniform = [&] {  // deterministic, in [-1, 1)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 52) - 1.0;
  };
  std::vector<embedded::Vec3> rigid = s.vertices;
  for (int c = 0; c < cycles; ++c) {
    embedded::move_surface(s, 1.0);
    if (jitter > 0) {
      for (std::size_t v = 0; v < s.vertices.size(); ++v)
        for (std::size_t d = 0; d < 3; ++d) {
          rigid[v][d] += cells_per_cycle[d] * g.dx[d];
          s.vertices[v][d] = rigid[v][d] + jitter * uniform();
        }
    }
    embedded::build_geometry(g, s, opt, e);
    total += e.timing.total;
    if (parts) {
      parts->surface += e.timing.surface / cycles;
      parts->clip += e.timing.clip / cycles;
      parts->distance += e.timing.distance / cycles;
      parts->categories += e.timing.categories / cycles;
      parts->image_points += e.timing.image_points / cycles;
      parts->side_images += e.timing.side_images / cycles;
    }
  }
  return total / cycles;
}

double seconds_for(FluidSimulation& sim, int steps) {
  sim.advance(sim.stable_dt());  // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) sim.advance(sim.stable_dt());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"embedded-boundary cost per cycle"};
  int n = 512, steps = 20, threads = omp_get_max_threads();
  app.add_option("--cells", n);
  app.add_option("--steps", steps);
  app.add_option("--threads", threads, "threads of the 3D geometry (the 2D cycles run on one)");
  CLI11_PARSE(app, argc, argv);
  auto plain = make_simulation(parse_fluid_scene(scene(n, 0, 0)));
  const double t_plain = seconds_for(*plain, steps);
  fmt::print("| body | faces | cut cells | ghost+solid-cut | cycle [ms] | geometry [ms] | geometry share |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  fmt::print("| none | 0 | 0 | 0 | {:.2f} | - | - |\n", 1e3 * t_plain);
  for (double radius : {0.1, 0.3}) {
    const int segments = radius > 0.2 ? 1000 : 333;  // about the same face size
    auto sim = make_simulation(parse_fluid_scene(scene(n, radius, segments)));
    auto* run = dynamic_cast<EmbeddedBodiesRun<2>*>(sim.get());
    const double geo0 = run->geometry_seconds();
    const double t = seconds_for(*sim, steps);
    const double geo = (run->geometry_seconds() - geo0) / (steps + 1);
    std::size_t cut = 0;
    for (double k : sim->embedded_categories()) cut += (k == 1.0 || k == 2.0) ? 1 : 0;
    fmt::print("| circle R = {} | {} | {} | {} | {:.2f} | {:.2f} | {:.1f}% |\n", radius, segments, cut,
               sim->embedded().ghosts.size(), 1e3 * t, 1e3 * geo, 100 * geo / t);
  }

  fmt::print(
      "\n| 3D grid | solid mesh of the box | faces | geometry, prisms [ms] | geometry, full boxes [ms] | ratio |\n");
  fmt::print("|---|---|---|---|---|---|\n");
  struct Case {
    std::array<int, 3> grid;
    std::array<double, 3> domain_lo, domain_hi;
    embedded::Vec3 lo, hi;
    std::array<int, 3> mesh;
    embedded::Vec3 cells_per_cycle;
    const char* name;
    double jitter = 0.0;
  };
  std::vector<Case> cases = {
      {{40, 8, 8},
       {-2, 0, 0},
       {2, 0.8, 0.8},
       {-1.0, 0.0, 0.0},
       {0.0, 0.8, 0.8},
       {2, 4, 4},
       {0.05, 0, 0},
       "piston_3d's piston, 2 x 4 x 4"},
      {{64, 64, 64},
       {0, 0, 0},
       {1, 1, 1},
       {0.3, 0.3, 0.3},
       {0.7, 0.7, 0.7},
       {8, 8, 8},
       {0.3, 0.1, 0.2},
       "box 0.4^3, 8^3 cells"},
      {{64, 64, 64},
       {0, 0, 0},
       {1, 1, 1},
       {0.3, 0.3, 0.3},
       {0.7, 0.7, 0.7},
       {16, 16, 16},
       {0.3, 0.1, 0.2},
       "box 0.4^3, 16^3 cells"},
      {{120, 120, 120},
       {0, 0, 0},
       {1, 1, 1},
       {0.45, 0.25, 0.25},
       {0.55, 0.75, 0.75},
       {10, 40, 40},
       {0.002, 0.001, 0.001},
       "tungsten_blast_3d's target, 10 x 40 x 40"},
  };
  Case deforming = cases.back();  // the tungsten target, deforming as well
  deforming.name = "the same target deforming (vertex jitter 5 um: 1e-4 to 1e-3 rad between faces)";
  deforming.jitter = 5e-6;
  cases.push_back(deforming);
  omp_set_num_threads(threads);
  std::vector<embedded::GeometryTiming> parts;
  for (const Case& c : cases) {
    const Grid<3> g(c.grid, c.domain_lo, c.domain_hi);
    const embedded::Surface box = embedded::make_subdivided_box(3, c.lo, c.hi, c.mesh);
    parts.emplace_back();
    const double on = geometry_seconds_3d(g, box, c.cells_per_cycle, true, steps, &parts.back(), c.jitter),
                 off = geometry_seconds_3d(g, box, c.cells_per_cycle, false, steps, nullptr, c.jitter);
    fmt::print("| {} x {} x {} | {} | {} | {:.3f} | {:.3f} | {:.2f} |\n", c.grid[0], c.grid[1], c.grid[2], c.name,
               box.faces.size(), 1e3 * on, 1e3 * off, off / on);
  }
  fmt::print(
      "\nWith prisms, per part [ms]:\n\n| body | surface | clip | distance | categories | image points | side "
      "images |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto& t = parts[i];
    fmt::print("| {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n", cases[i].name, 1e3 * t.surface,
               1e3 * t.clip, 1e3 * t.distance, 1e3 * t.categories, 1e3 * t.image_points, 1e3 * t.side_images);
  }
}
