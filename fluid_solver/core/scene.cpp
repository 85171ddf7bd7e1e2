#include "fluid_solver/core/scene.h"

#include "common/util/memory.h"
#include "fluid_solver/core/memory_estimate.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/parallel/launch_env.h"
#include "common/config/output_times.h"
#include "common/eos/materials.h"
#include "fluid_solver/core/scene_readers.h"

namespace cosim::fluid {

using config::Node;

namespace {

using scene_readers::read_phase;
using scene_readers::read_point;
using scene_readers::read_state;

const std::vector<std::string> kAxes = {"x", "y", "z"};

Boundary read_boundary(Node& n, const std::string& key, const std::vector<Phase>& phases, int dim) {
  Boundary b;
  n.skip(key);
  if (!n.has(key)) return b;
  // Either a plain word or a section {type: inflow, state: {...}}.
  std::string type;
  std::optional<Node> sec;
  auto choices = config::one_of({"transmissive", "wall", "inflow", "periodic"});
  if (n.child_is_map(key)) {
    sec = n.child(key);
    type = sec->require<std::string>("type", choices);
  } else {
    type = n.get<std::string>(key, "transmissive", choices);
  }
  if (type == "transmissive") b.kind = BoundaryKind::Transmissive;
  else if (type == "wall") b.kind = BoundaryKind::Wall;
  else if (type == "periodic") b.kind = BoundaryKind::Periodic;
  else {
    b.kind = BoundaryKind::Inflow;
    if (!sec) n.fail(key, "a section {type: inflow, state: {...}} for an inflow boundary");
    Node st = sec->child("state");
    b.inflow = read_state(st, phases, dim, true);
  }
  if (sec) sec->finish();
  return b;
}

Region read_region(Node& n, const std::vector<Phase>& phases, int dim) {
  Region r;
  int shapes = 0;
  if (auto box = n.optional_child("box")) {
    r.shape = Region::Shape::Box;
    r.a = read_point(*box, "lower", dim);
    r.b = read_point(*box, "upper", dim);
    for (int d = 0; d < dim; ++d)
      if (!(r.b[d] >= r.a[d])) box->fail("upper", "upper >= lower in every direction");
    box->finish();
    ++shapes;
  }
  if (auto sph = n.optional_child("sphere")) {
    r.shape = Region::Shape::Sphere;
    r.a = read_point(*sph, "center", dim);
    r.radius = sph->require<double>("radius", config::positive());
    sph->finish();
    ++shapes;
  }
  if (auto hs = n.optional_child("half_space")) {
    r.shape = Region::Shape::HalfSpace;
    r.a = read_point(*hs, "point", dim);
    r.b = read_point(*hs, "normal", dim);
    if (std::all_of(r.b.begin(), r.b.end(), [](double c) { return c == 0.0; }))
      hs->fail("normal", "a normal that is not zero (it points into the region)");
    hs->finish();
    ++shapes;
  }
  if (shapes != 1) n.fail("box", "exactly one shape per region: box, sphere or half_space");
  Node st = n.child("state");
  r.value = read_state(st, phases, dim);
  n.finish();
  return r;
}

// Whether the region contains the centre of at least one cell of the mesh (initial_state.h tests the centres).
// Per axis the candidates are both end cells and the three cells nearest the region's centre, box middle or
// half-space point: they hold the centre nearest a sphere's centre or a box's middle (a box or sphere holds a centre
// if it holds that one), and every corner of the lattice (the farthest a half-space reaches).
bool covers_a_cell(const Region& r, const FluidScene& s) {
  std::array<std::vector<int>, 3> cand;
  std::array<double, 3> dx{1, 1, 1};
  for (int d = 0; d < 3; ++d) {
    if (d >= s.dim) {
      cand[d] = {0};
      continue;
    }
    const int n = s.cells[d];
    dx[d] = (s.upper[d] - s.lower[d]) / n;  // as Grid
    const double target = r.shape == Region::Shape::Box ? 0.5 * (r.a[d] + r.b[d]) : r.a[d];
    const double at = std::clamp((target - s.lower[d]) / dx[d] - 0.5, -1.0, static_cast<double>(n));
    const int i = static_cast<int>(std::lround(at));
    for (int c : {0, n - 1, i - 1, i, i + 1}) cand[d].push_back(std::clamp(c, 0, n - 1));
  }
  for (int i : cand[0])
    for (int j : cand[1])
      for (int k : cand[2]) {
        const std::array<int, 3> ijk{i, j, k};
        std::array<double, 3> x{0, 0, 0};
        for (int d = 0; d < s.dim; ++d) x[d] = s.lower[d] + (ijk[d] + 0.5) * dx[d];
        if (r.contains(x, s.dim)) return true;
      }
  return false;
}

std::string region_box(const Region& r, int dim) {
  const auto vec = [dim](const std::array<double, 3>& v) {
    return fmt::format("[{:g}]", fmt::join(v.begin(), v.begin() + dim, ", "));
  };
  switch (r.shape) {
    case Region::Shape::Box: return fmt::format("box from {} to {}", vec(r.a), vec(r.b));
    case Region::Shape::Sphere: return fmt::format("sphere of radius {:g} at {}", r.radius, vec(r.a));
    case Region::Shape::HalfSpace: return fmt::format("half-space through {} with normal {}", vec(r.a), vec(r.b));
  }
  return "region";
}

Profile read_profile(Node& n, int dim) {
  Profile p;
  std::string type = n.require<std::string>("type", config::one_of({"density_wave", "gresho_vortex"}));
  if (type == "density_wave") {
    p.kind = Profile::Kind::DensityWave;
    p.rho0 = n.get<double>("rho", 1.0, config::positive());
    p.amplitude = n.get<double>("amplitude", 0.2, config::in_range(0.0, 0.99));
    p.p0 = n.get<double>("p", 1.0, config::positive());
    p.wave_number = read_point(n, "wave_number", dim, std::vector<double>(dim, 1.0));
    p.velocity = read_point(n, "velocity", dim, std::vector<double>(dim, 1.0));
  } else {
    if (dim < 2) n.fail("type", "gresho_vortex needs a 2D or 3D mesh");
    p.kind = Profile::Kind::GreshoVortex;
    p.center = read_point(n, "center", dim);
    p.radius_scale = n.get<double>("radius_scale", 1.0, config::positive());
    p.speed = n.get<double>("speed", 1.0, config::positive());
    p.mach = n.get<double>("mach", 0.1, config::in_open_closed(0.0, 10.0));
    p.rho0 = n.get<double>("rho", 1.0, config::positive());
  }
  n.finish();
  return p;
}

EmbeddedBody read_body(Node& n, int dim) {
  EmbeddedBody b;
  const std::string shape =
      n.require<std::string>("shape", config::one_of({"box", "circle", "sphere", "polygon", "step"}));
  if ((shape == "circle" || shape == "polygon") && dim != 2) n.fail("shape", shape + " needs a 2D mesh");
  if (shape == "sphere" && dim != 3) n.fail("shape", "sphere needs a 3D mesh");
  if (dim == 1) n.fail("shape", "embedded bodies in a 2D or 3D mesh");
  if (shape == "box" || shape == "step") {
    b.shape = shape == "box" ? EmbeddedBody::Shape::Box : EmbeddedBody::Shape::Step;
    b.lower = read_point(n, "lower", dim);
    b.upper = read_point(n, "upper", dim);
    for (int d = 0; d < dim; ++d)
      if (!(b.upper[d] > b.lower[d])) n.fail("upper", "upper > lower in every direction");
    if (shape == "box" && dim == 2) b.rotation_deg = n.get<double>("rotation", 0.0, config::in_range(-360, 360));
  } else if (shape == "circle" || shape == "sphere") {
    b.shape = shape == "circle" ? EmbeddedBody::Shape::Circle : EmbeddedBody::Shape::Sphere;
    b.center = read_point(n, "center", dim);
    b.radius = n.require<double>("radius", config::positive());
    b.segments = n.get<int>("segments", shape == "circle" ? 128 : 3, config::int_at_least(shape == "circle" ? 8 : 0));
  } else {
    b.shape = EmbeddedBody::Shape::Polygon;
    for (auto& v : n.list("vertices")) {
      auto p = v.elements();
      if (p.size() != 2) n.fail("vertices", "a list of [x, y] points");
      b.vertices.push_back({p[0].as<double>(), p[1].as<double>()});
    }
    if (b.vertices.size() < 3) n.fail("vertices", "at least 3 vertices");
  }
  b.velocity = read_point(n, "velocity", dim, std::vector<double>(dim, 0.0));
  n.finish();
  return b;
}

}  // namespace

bool Region::contains(const std::array<double, 3>& x, int dim) const {
  switch (shape) {
    case Shape::Box:
      for (int d = 0; d < dim; ++d)
        if (x[d] < a[d] || x[d] > b[d]) return false;
      return true;
    case Shape::Sphere: {
      double r2 = 0;
      for (int d = 0; d < dim; ++d) r2 += (x[d] - a[d]) * (x[d] - a[d]);
      return r2 <= radius * radius;
    }
    case Shape::HalfSpace: {
      double s = 0;
      for (int d = 0; d < dim; ++d) s += (x[d] - a[d]) * b[d];
      return s >= 0;
    }
  }
  return false;
}

FluidScene read_fluid_scene(Node& root, double coupled_end) {
  FluidScene s;
  Node f = root.child("fluid");

  // mesh
  Node mesh = f.child("mesh");
  auto cells = mesh.get_vector("cells", 1, 3);
  s.dim = static_cast<int>(cells.size());
  for (int d = 0; d < s.dim; ++d) {
    if (cells[d] < 1 || cells[d] != std::floor(cells[d]) || cells[d] > 1e8)
      mesh.fail("cells", "positive whole numbers of cells per direction");
    s.cells[d] = static_cast<int>(cells[d]);
  }
  s.lower = read_point(mesh, "lower", s.dim, std::vector<double>(s.dim, 0.0));
  s.upper = read_point(mesh, "upper", s.dim);
  for (int d = 0; d < s.dim; ++d)
    if (!(s.upper[d] > s.lower[d])) mesh.fail("upper", "upper > lower in every direction");
  mesh.finish();

  // phases
  auto plist = f.list("phases");
  if (plist.empty() || plist.size() > 2) f.fail("phases", "one or two phases");
  for (auto& pn : plist) {
    s.phases.push_back(read_phase(pn));
    if (s.phases.size() == 2 && s.phases[0].name == s.phases[1].name)
      pn.fail("name", fmt::format("a name that differs from the first phase's, got '{}' twice", s.phases[1].name));
  }

  // numerics
  if (auto num = f.optional_child("numerics")) {
    std::string flux = num->get<std::string>("flux", "aufs", config::one_of({"aufs", "hllc", "rusanov"}));
    s.flux = flux == "aufs" ? FluxKind::AUFS : flux == "hllc" ? FluxKind::HLLC : FluxKind::Rusanov;
    std::string rec = num->get<std::string>("reconstruction", "muscl", config::one_of({"first_order", "muscl"}));
    s.reconstruction = rec == "muscl" ? Reconstruction::MUSCL : Reconstruction::FirstOrder;
    std::string lim = num->get<std::string>("limiter", "van_leer", config::one_of({"minmod", "van_leer", "mc"}));
    s.limiter = lim == "minmod" ? Limiter::Minmod : lim == "mc" ? Limiter::MC : Limiter::VanLeer;
    s.low_mach = num->get<bool>("low_mach", false);
    s.low_mach_cutoff = num->get<double>("low_mach_cutoff", 0.0, config::in_range(0.0, 1.0));
    if (s.low_mach && s.reconstruction != Reconstruction::MUSCL)
      num->fail("low_mach", "reconstruction: muscl (the correction modifies reconstructed face states)");
    num->finish();
  }

  s.coupled = coupled_end > 0;
  // time
  // In a coupled scene the coupler owns time (coupling.time); the fluid's time: then only sets cfl etc.
  Node time = coupled_end > 0 ? f.child_or_empty("time") : f.child("time");
  s.t_end = coupled_end > 0 ? time.get<double>("end", coupled_end, config::positive())
                            : time.require<double>("end", config::positive());
  s.cfl = time.get<double>("cfl", 0.4, config::in_open_closed(0.0, 1.0));
  std::string integ = time.get<std::string>("integrator", "rk2", config::one_of({"rk2", "rk3"}));
  s.integrator = integ == "rk3" ? TimeIntegrator::RK3 : TimeIntegrator::RK2;
  s.max_steps = time.get<long>("max_steps", 100000000L,
                               [](const long& v) { return v >= 1 ? std::string() : std::string("an integer >= 1"); });
  time.finish();

  // boundaries
  if (auto bn = f.optional_child("boundaries")) {
    for (int d = 0; d < s.dim; ++d)
      for (int side = 0; side < 2; ++side)
        s.boundaries[d][side] = read_boundary(*bn, kAxes[d] + (side == 0 ? "_lower" : "_upper"), s.phases, s.dim);
    bn->finish();
    for (int d = 0; d < s.dim; ++d) {
      bool p0 = s.boundaries[d][0].kind == BoundaryKind::Periodic;
      bool p1 = s.boundaries[d][1].kind == BoundaryKind::Periodic;
      if (p0 != p1) bn->fail(kAxes[d] + "_upper", "periodic on both sides of an axis or on neither");
    }
  }

  // embedded bodies
  if (auto em = f.optional_child("embedded")) {
    const int order = em->get<int>("order", 2, [](const int& v) {
      return v == 1 || v == 2 ? std::string() : std::string("1 (ghost cells only) or 2 (plus face states)");
    });
    s.embedded.second_order = order == 2;
    s.embedded.band = em->get<double>("band", 3.0, config::in_range(2.0, 50.0));
    s.embedded.ghost_pressure_from_interface =
        em->get<std::string>("ghost_pressure", "interface", config::one_of({"interface", "image"})) == "interface";
    s.embedded.conservative = em->get<bool>("conservative", false);
    // Optional: in a coupled scene the solid's faces are the embedded boundary.
    if (em->has("bodies") || coupled_end <= 0)
      for (auto& bn : em->list("bodies")) s.embedded.bodies.push_back(read_body(bn, s.dim));
    em->finish();
  }

  // exchange
  if (auto ex = f.optional_child("exchange")) {
    s.exchange.pressure_relaxation = ex->get<bool>("pressure_relaxation", true);
    std::string vr =
        ex->get<std::string>("velocity_relaxation", "instant", config::one_of({"none", "instant", "drag"}));
    s.exchange.velocity = vr == "none"   ? VelocityRelaxation::None
                          : vr == "drag" ? VelocityRelaxation::Drag
                                         : VelocityRelaxation::Instant;
    std::string dl = ex->get<std::string>("drag_law", "schiller_naumann",
                                          config::one_of({"schiller_naumann", "clift_gauvin", "akhatov_vainshtein"}));
    s.exchange.drag_law = dl == "clift_gauvin"         ? DragLaw::CliftGauvin
                          : dl == "akhatov_vainshtein" ? DragLaw::AkhatovVainshtein
                                                       : DragLaw::SchillerNaumann;
    std::string ht = ex->get<std::string>("heat_transfer", "none", config::one_of({"none", "ranz_marshall"}));
    s.exchange.heat_transfer = ht == "ranz_marshall";
    s.exchange.particle_diameter = ex->get<double>("particle_diameter", 1e-4, config::positive());
    s.exchange.gas_viscosity = ex->get<double>("gas_viscosity", 1.8e-5, config::positive());
    s.exchange.gas_conductivity = ex->get<double>("gas_conductivity", 0.026, config::positive());
    s.exchange.alpha_min = ex->get<double>("alpha_min", 1e-8, config::in_range(0.0, 0.01));
    // A trace phase keeps the carrier's pressure only with instantaneous pressure relaxation (docs/methods.md §2.7).
    s.exchange.trace_alpha =
        ex->get<double>("trace_alpha", s.exchange.pressure_relaxation ? 1e-3 : 0.0, config::in_range(0.0, 0.05));
    if (s.exchange.trace_alpha > 0 && !s.exchange.pressure_relaxation)
      ex->fail("trace_alpha",
               "a trace phase follows the carrier's pressure: it needs pressure_relaxation: true (or "
               "trace_alpha: 0)");
    s.exchange.dispersed = ex->get<bool>("dispersed", false);
    if (s.exchange.dispersed && !s.exchange.pressure_relaxation)
      ex->fail("dispersed", "a dispersed phase takes the carrier's pressure: it needs pressure_relaxation: true");
    if (auto ps = ex->optional_child("particle_stress")) {
      if (!s.exchange.dispersed)
        ex->fail("particle_stress", "a particle stress for a dispersed phase (dispersed: true)");
      ParticleStress& st = s.exchange.particle_stress;
      st.p_s = ps->get<double>("p_s", st.p_s, config::positive());
      st.beta = ps->get<double>("beta", st.beta, config::in_range(1.0, 10.0));
      st.packing = ps->get<double>("packing", st.packing, config::in_range(0.3, 0.74));
      st.delta = ps->get<double>("delta", st.delta, config::in_range(1e-4, 0.1));
      st.skip_below = ps->get<double>("skip_below", st.skip_below, config::in_range(0.0, 1e-3));
      ps->finish();
    }
    GranularGas& gr = s.exchange.granular;
    gr.enabled = ex->get<bool>("granular_temperature", s.exchange.dispersed);
    if (gr.enabled && !s.exchange.dispersed)
      ex->fail("granular_temperature", "a granular temperature for a dispersed phase (dispersed: true)");
    if (gr.enabled && s.flux != FluxKind::AUFS)
      ex->fail("granular_temperature",
               "a granular temperature with numerics.flux: aufs (or granular_temperature: false with this flux)");
    if (!gr.enabled && ex->has("restitution"))
      ex->fail("restitution",
               "the restitution of particle collisions for a granular temperature "
               "(granular_temperature: true)");
    gr.restitution = ex->get<double>("restitution", gr.restitution, config::in_range(0.0, 1.0));
    gr.packing = s.exchange.particle_stress.packing;
    gr.delta = s.exchange.particle_stress.delta;
    gr.diameter = s.exchange.particle_diameter;
    if (s.num_phases() == 1) ex->fail("velocity_relaxation", "no exchange section for a single-phase scene");
    ex->finish();
  }

  // initial conditions
  Node init = f.child("initial");
  if (auto prof = init.optional_child("profile")) {
    s.profile = read_profile(*prof, s.dim);
    if (s.num_phases() != 1) init.fail("profile", "analytic profiles for single-phase scenes only");
  }
  if (auto st = init.optional_child("state")) {
    s.background = read_state(*st, s.phases, s.dim);
  } else if (s.profile.kind == Profile::Kind::None) {
    init.fail("state", "a background state (or a profile)");
  }
  init.skip("regions");
  if (init.has("regions"))
    for (auto& rn : init.list("regions")) {
      s.regions.push_back(read_region(rn, s.phases, s.dim));
      // A region that selects no cell centre would leave the run uniform without a word.
      if (!covers_a_cell(s.regions.back(), s)) {
        std::vector<double> dx(static_cast<std::size_t>(s.dim));
        for (int d = 0; d < s.dim; ++d) dx[d] = (s.upper[d] - s.lower[d]) / s.cells[d];
        const Region& r = s.regions.back();
        rn.fail(r.shape == Region::Shape::Box      ? "box"
                : r.shape == Region::Shape::Sphere ? "sphere"
                                                   : "half_space",
                fmt::format("a region that contains the centre of at least one cell, but the {} covers no cell "
                            "(domain from [{:g}] to [{:g}], cells of [{:g}] m): enlarge it, move it into the "
                            "domain or refine the mesh",
                            region_box(r, s.dim), fmt::join(s.lower.begin(), s.lower.begin() + s.dim, ", "),
                            fmt::join(s.upper.begin(), s.upper.begin() + s.dim, ", "), fmt::join(dx, ", ")));
      }
    }
  init.finish();

  // output
  {
    auto out = f.optional_child("output");
    s.output_times = config::read_output_times(out ? &*out : nullptr, s.t_end);
    if (out) out->finish();
  }

  // checkpoint sets of a fluid-only run (the coupler writes them in a coupled one: coupling.checkpoint)
  if (auto ck = f.optional_child("checkpoint")) {
    if (coupled_end > 0)
      f.fail("checkpoint",
             "no fluid.checkpoint in a coupled scene (the coupler checkpoints the whole run: put it "
             "under coupling.checkpoint)");
    s.checkpoint = checkpoint::read_checkpoint_policy(&*ck);
  }

  s.threads = f.get<int>("threads", 0, config::int_at_least(0));
  if (auto par = f.optional_child("parallel")) {  // the layout of the blocks under MPI (checked against the ranks)
    const auto r = par->get_vector("ranks", static_cast<std::size_t>(s.dim), static_cast<std::size_t>(s.dim));
    for (int d = 0; d < s.dim; ++d) {
      if (r[d] < 1 || r[d] != std::floor(r[d]) || r[d] > s.cells[d])
        par->fail("ranks", fmt::format("a whole number of blocks per axis, from 1 to the cells along it ({}), got {:g}",
                                       s.cells[d], r[d]));
      s.parallel_ranks[d] = static_cast<int>(r[d]);
    }
    for (int d = s.dim; d < 3; ++d) s.parallel_ranks[d] = 1;
    if (s.coupled && s.parallel_ranks[0] * s.parallel_ranks[1] * s.parallel_ranks[2] > 1)
      par->fail("ranks", "one block in a coupled scene (the coupler serves one fluid process for now)");
    par->finish();
  }
  f.finish();

  // Refused before anything is allocated: a state that cannot fit in the memory the machine has (under a parallel
  // launcher, the blocks of the ranks on this node: their share of the mesh).
  const parallel::LaunchShape launch = parallel::launch_shape();
  const double need = static_cast<double>(estimated_state_bytes(s)) * launch.ranks_on_node / launch.ranks;
  const std::size_t have = util::available_memory_bytes();
  if (have > 0 && need > 0.9 * static_cast<double>(have)) {
    double n = 1;
    for (int d = 0; d < s.dim; ++d) n *= s.cells[d];
    mesh.fail("cells",
              fmt::format("a mesh whose state fits in memory: {:.4g} cells need about {} ({:.0f} bytes per "
                          "cell){}, this machine has {} available",
                          n, util::format_bytes(need), need / n * launch.ranks / launch.ranks_on_node,
                          launch.ranks > 1 ? fmt::format(" for the blocks of this node's {} of {} ranks",
                                                         launch.ranks_on_node, launch.ranks)
                                           : std::string(),
                          util::format_bytes(static_cast<double>(have))));
  }
  return s;
}

namespace {
FluidScene read_document(Node root) {
  // Top-level keys first, so that a typo in a section name gets a suggestion. Sections that
  // belong to the other processes of a coupled scene are read by them.
  for (const char* key : {"fluid", "solid", "coupling", "launcher"}) root.skip(key);
  const std::string name = root.get<std::string>("name", "scene");
  root.get<std::string>("description", "");
  root.finish();
  FluidScene s = read_fluid_scene(root, config::coupled_end_time(root));
  s.name = name;
  return s;
}
}  // namespace

FluidScene load_fluid_scene(const std::string& file, const std::vector<std::string>& overrides) {
  return read_document(config::load_file(file, overrides));
}

FluidScene parse_fluid_scene(const std::string& yaml_text, const std::vector<std::string>& overrides) {
  return read_document(config::load_string(yaml_text, "<scene>", overrides));
}

const char* to_string(FluxKind f) {
  switch (f) {
    case FluxKind::AUFS: return "aufs";
    case FluxKind::HLLC: return "hllc";
    case FluxKind::Rusanov: return "rusanov";
  }
  return "?";
}
const char* to_string(Limiter l) {
  switch (l) {
    case Limiter::Minmod: return "minmod";
    case Limiter::VanLeer: return "van_leer";
    case Limiter::MC: return "mc";
  }
  return "?";
}

}  // namespace cosim::fluid
