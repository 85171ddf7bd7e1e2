#include "solid_solver/core/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <set>

#include "common/config/output_times.h"
#include "common/eos/materials.h"
#include "solid_solver/mesh/gmsh_reader.h"

namespace cosim::solid {

using config::Node;

namespace {

// Rejects unknown keys (with a did-you-mean suggestion) before any required key is read, so that a typo in a
// required key is reported as the typo rather than as a missing key.
void known_keys(Node& n, std::initializer_list<const char*> keys) {
  for (const char* k : keys) n.skip(k);
  n.finish();
}

using config::read_point;

MaterialModel read_material(Node& b, bool rigid, bool& has_eos) {
  MaterialModel m;
  m.library_name = b.get<std::string>("material", "custom");
  const eos::MieGruneisenParams* lib = nullptr;
  if (m.library_name != "custom") {
    const auto* mat = eos::find_material(m.library_name);
    if (!mat || !mat->mg) {
      std::vector<std::string> names = {"custom"};
      for (const auto& x : eos::material_library())
        if (x.mg) names.push_back(x.name);
      b.fail("material", config::one_of(names)(m.library_name) + ", got '" + m.library_name + "'");
    }
    lib = &*mat->mg;
    m.eos = EosKind::MieGruneisen;
    m.mg = {lib->rho0, lib->c0, lib->s, lib->gamma0};
    m.density = lib->rho0;
  }
  auto e = b.optional_child("eos");
  if (e) {
    known_keys(*e, {"type", "gamma", "bulk_modulus", "rho0", "c0", "s", "gamma0", "p_min"});
    const std::string type = e->get<std::string>("type", lib ? "mie_gruneisen" : "",
                                                 config::one_of({"ideal_gas", "linear_elastic", "mie_gruneisen"}));
    if (type.empty()) e->fail("type", "one of ideal_gas, linear_elastic, mie_gruneisen");
    if (type == "ideal_gas") {
      m.eos = EosKind::IdealGas;
      m.ideal.gamma = e->require<double>("gamma", config::in_open_closed(1.0, 100.0));
    } else if (type == "linear_elastic") {
      m.eos = EosKind::LinearElastic;
      m.linear.bulk_modulus = e->require<double>("bulk_modulus", config::positive());
    } else {
      m.eos = EosKind::MieGruneisen;
      m.mg.rho0 = e->get<double>("rho0", lib ? lib->rho0 : 0.0, config::positive());
      m.mg.c0 = e->get<double>("c0", lib ? lib->c0 : 0.0, config::positive());
      m.mg.s = e->get<double>("s", lib ? lib->s : 0.0, config::non_negative());
      m.mg.gamma0 = e->get<double>("gamma0", lib ? lib->gamma0 : 0.0, config::positive());
      if (!lib && !(m.mg.rho0 > 0 && m.mg.c0 > 0 && m.mg.gamma0 > 0))
        e->fail("rho0", "rho0, c0, s and gamma0 for a custom mie_gruneisen eos (or a library material)");
      m.density = m.mg.rho0;
    }
    m.p_min = e->get<double>("p_min", m.p_min);
    e->finish();
  } else if (!lib && rigid) {
    has_eos = false;  // a rigid block needs only its density
  } else if (!lib) {
    b.fail("eos", "an eos section {type: ideal_gas | linear_elastic | mie_gruneisen, ...} or a library material");
  }
  // Density: required for ideal gas and linear elastic, defaults to rho0 for Mie-Grueneisen.
  if (m.eos == EosKind::MieGruneisen) m.density = b.get<double>("density", m.mg.rho0, config::positive());
  else m.density = b.require<double>("density", config::positive());
  m.linear.rho_ref = m.density;
  if (auto s = b.optional_child("strength")) {
    known_keys(*s, {"enabled", "shear_modulus", "yield_stress", "hardening"});
    m.strength.enabled = s->get<bool>("enabled", true);
    m.strength.shear_modulus = s->require<double>("shear_modulus", config::positive());
    m.strength.yield_stress = s->get<double>("yield_stress", 1e300, config::positive());
    m.strength.hardening = s->get<double>("hardening", 0.0, config::non_negative());
    s->finish();
  }
  return m;
}

BlockSpec read_block(Node& b, int dim) {
  BlockSpec s;
  known_keys(b, {"name", "material", "eos", "density", "strength", "initial", "rigid"});
  s.name = b.require<std::string>("name");
  s.rigid = b.get<bool>("rigid", false);
  s.material = read_material(b, s.rigid, s.has_eos);
  if (s.rigid && b.has("strength")) b.fail("strength", "no strength section for a rigid block (it has no stress)");
  if (auto in = b.optional_child("initial")) {
    s.energy = in->get<double>("energy", 0.0);
    if (in->has("pressure")) {
      s.has_pressure = true;
      s.pressure = in->get<double>("pressure", 0.0);
      if (in->has("energy")) in->fail("pressure", "either energy or pressure, not both");
      if (!s.has_eos) in->fail("pressure", "no initial pressure for a rigid block without an eos");
      if (s.material.eos == EosKind::LinearElastic)
        in->fail("pressure", "no initial pressure for linear_elastic (its pressure follows the density)");
      if (s.material.eos == EosKind::IdealGas && s.pressure < 0)
        in->fail("pressure", "a pressure >= 0 for an ideal gas");
    }
    s.velocity = read_point(*in, "velocity", dim, std::vector<double>(dim, 0.0), config::speed());
    // Spin about the block's centre of mass: a scalar (about z) in 2D, [wx, wy, wz] in 3D.
    in->skip("angular_velocity");
    if (in->has("angular_velocity")) {
      if (dim == 2) s.angular_velocity[2] = in->get<double>("angular_velocity", 0.0);
      else s.angular_velocity = read_point(*in, "angular_velocity", 3);
    }
    if (in->has("deviator")) {
      auto v = in->get_vector("deviator", 6, 6);
      std::copy(v.begin(), v.end(), s.deviator.begin());
      if (std::abs(v[0] + v[1] + v[2]) > 1e-12 * (std::abs(v[0]) + std::abs(v[1]) + std::abs(v[2])))
        in->fail("deviator", "a traceless stress deviator [xx, yy, zz, xy, yz, zx] (xx + yy + zz = 0)");
      if (dim == 2 && (v[4] != 0 || v[5] != 0)) in->fail("deviator", "yz = zx = 0 in 2D (plane strain)");
    }
    in->skip("deviator");
    in->finish();
  }
  if (s.material.eos == EosKind::IdealGas && !s.has_pressure && s.energy < 0)
    b.fail("initial", "a specific internal energy >= 0 for an ideal gas");
  b.finish();
  return s;
}

BoundarySpec read_boundary(Node& n, int dim, const std::set<std::string>& sets) {
  BoundarySpec b;
  known_keys(n, {"set", "box", "type", "vx", "vy", "vz", "value", "ramp"});
  if (n.has("box") == n.has("set")) n.fail("set", "either set: NAME (a boundary set) or box: {lower, upper} (nodes)");
  if (auto box = n.optional_child("box")) {
    known_keys(*box, {"lower", "upper"});
    b.node_box = true;
    b.lower = read_point(*box, "lower", dim);
    b.upper = read_point(*box, "upper", dim);
    for (int d = 0; d < dim; ++d)
      if (!(b.upper[d] >= b.lower[d])) box->fail("upper", "upper >= lower in every direction");
    box->finish();
  } else {
    b.set = n.require<std::string>("set");
  }
  if (!b.node_box && !sets.count(b.set)) {
    std::string list;
    for (auto& s : sets) list += (list.empty() ? "" : ", ") + s;
    std::string hint = config::closest(b.set, sets);
    n.fail("set", "a boundary set of the mesh (" + list + ")" + (hint.empty() ? "" : "; did you mean '" + hint + "'?") +
                      ", got '" + b.set + "'");
  }
  const std::string type =
      n.require<std::string>("type", config::one_of({"fixed", "symmetry", "velocity", "pressure", "non_reflecting"}));
  if (b.node_box && type != "fixed" && type != "velocity")
    n.fail("type", "fixed or velocity with a node box (pressure, non_reflecting and symmetry need a face set)");
  if (type == "fixed") b.kind = BcKind::Fixed;
  else if (type == "symmetry") b.kind = BcKind::Symmetry;
  else if (type == "velocity") {
    b.kind = BcKind::Velocity;
    const char* keys[3] = {"vx", "vy", "vz"};
    for (int d = 0; d < 3; ++d) {
      n.skip(keys[d]);
      if (!n.has(keys[d])) continue;
      if (d >= dim) n.fail(keys[d], fmt::format("a velocity component of a {}D mesh", dim));
      b.component[d] = true;
      b.velocity[d] = n.get<double>(keys[d], 0.0, config::speed());
    }
    if (!b.component[0] && !b.component[1] && !b.component[2])
      n.fail("vx", "at least one prescribed velocity component vx, vy or vz [m/s]");
  } else if (type == "pressure") {
    b.kind = BcKind::Pressure;
    b.pressure = n.require<double>("value");
  } else {
    b.kind = BcKind::NonReflecting;
    b.pressure = n.get<double>("value", 0.0);  // the ambient pressure [Pa]
  }
  b.ramp = n.get<double>("ramp", 0.0, config::non_negative());
  n.finish();
  return b;
}

}  // namespace

SolidScene read_solid_scene(Node& root, const std::string& base_dir, const MeshLoader& load_mesh) {
  SolidScene s;
  Node sn = root.child("solid");
  known_keys(sn,
             {"mesh", "blocks", "boundaries", "initial", "numerics", "ale", "time", "output", "checkpoint", "threads"});

  Node mesh = sn.child("mesh");
  known_keys(mesh, {"type", "cells", "lower", "upper", "regions", "file"});
  const std::string mesh_type = mesh.get<std::string>("type", "box", config::one_of({"box", "gmsh"}));
  std::vector<Node> region_nodes;
  std::shared_ptr<Mesh> file_mesh;
  if (mesh_type == "gmsh") {
    for (const char* k : {"cells", "lower", "upper", "regions"})
      if (mesh.has(k)) mesh.fail(k, "no cells, lower, upper or regions with type: gmsh (the mesh file defines them)");
    s.mesh_file = mesh.require<std::string>("file");
    std::filesystem::path f(s.mesh_file);
    if (f.is_relative() && !base_dir.empty()) f = std::filesystem::path(base_dir) / f;
    try {
      file_mesh = std::make_shared<Mesh>(load_mesh ? load_mesh(f.string()) : read_gmsh(f.string()));
    } catch (const MeshError& e) { throw config::ConfigError(fmt::format("{}: {}", mesh.where("file"), e.what())); }
    s.mesh_file = f.string();
    s.dim = file_mesh->dim;
  } else {
    if (mesh.has("file")) mesh.fail("file", "no file with type: box (or type: gmsh)");
    auto cells = mesh.get_vector("cells", 2, 3);
    s.dim = static_cast<int>(cells.size());
    for (int d = 0; d < s.dim; ++d) {
      if (cells[d] < 1 || cells[d] != std::floor(cells[d]) || cells[d] > 1e7)
        mesh.fail("cells", "positive whole numbers of cells per direction");
      s.cells[d] = static_cast<int>(cells[d]);
    }
    double total = 1;
    for (int d = 0; d < s.dim; ++d) total *= s.cells[d];
    if (total > 2e9 / 8) mesh.fail("cells", "fewer than 2.5e8 elements");
    s.lower = read_point(mesh, "lower", s.dim, std::vector<double>(s.dim, 0.0));
    s.upper = read_point(mesh, "upper", s.dim);
    for (int d = 0; d < s.dim; ++d)
      if (!(s.upper[d] > s.lower[d])) mesh.fail("upper", "upper > lower in every direction");
    mesh.skip("regions");
    if (mesh.has("regions")) region_nodes = mesh.list("regions");
  }
  mesh.finish();

  auto blist = sn.list("blocks");
  if (blist.empty()) sn.fail("blocks", "at least one block");
  std::set<std::string> names;
  for (auto& bn : blist) {
    s.blocks.push_back(read_block(bn, s.dim));
    if (!names.insert(s.blocks.back().name).second)
      bn.fail("name", "a block name used only once, got '" + s.blocks.back().name + "' again");
  }
  for (auto& rn : region_nodes) {
    RegionSpec r;
    known_keys(rn, {"block", "lower", "upper", "center", "radius"});
    r.block = rn.require<std::string>("block");
    if (!names.count(r.block)) {
      std::string hint = config::closest(r.block, names);
      rn.fail("block", "the name of a block in solid.blocks" + (hint.empty() ? "" : "; did you mean '" + hint + "'?") +
                           ", got '" + r.block + "'");
    }
    r.sphere = rn.has("center") || rn.has("radius");
    if (r.sphere) {
      if (rn.has("lower") || rn.has("upper"))
        rn.fail("center", "either lower/upper (a box) or center/radius (a sphere)");
      r.center = read_point(rn, "center", s.dim);
      r.radius = rn.require<double>("radius", config::positive());
    } else {
      r.lower = read_point(rn, "lower", s.dim);
      r.upper = read_point(rn, "upper", s.dim);
    }
    rn.finish();
    s.regions.push_back(r);
  }

  // Gmsh: every scene block names an element group of the file and every group has a block; the mesh is
  // renumbered to the order of solid.blocks.
  if (file_mesh) {
    std::vector<int> block_of_group(file_mesh->block_names.size(), -1);
    for (std::size_t b = 0; b < s.blocks.size(); ++b) {
      const auto& names_in_file = file_mesh->block_names;
      auto it = std::find(names_in_file.begin(), names_in_file.end(), s.blocks[b].name);
      if (it == names_in_file.end()) {
        std::string list;
        for (const auto& g : names_in_file) list += (list.empty() ? "" : ", ") + g;
        blist[b].fail("name", fmt::format("the name of a {} physical group in {} ({}), got '{}'",
                                          s.dim == 2 ? "surface" : "volume", s.mesh_file, list, s.blocks[b].name));
      }
      block_of_group[it - names_in_file.begin()] = static_cast<int>(b);
    }
    for (std::size_t g = 0; g < block_of_group.size(); ++g)
      if (block_of_group[g] < 0 &&
          std::count(file_mesh->element_block.begin(), file_mesh->element_block.end(), static_cast<int>(g)) > 0)
        sn.fail("blocks", fmt::format("a block for every element group of {}: group '{}' has none", s.mesh_file,
                                      file_mesh->block_names[g]));
    for (int& b : file_mesh->element_block) b = block_of_group[b];
    file_mesh->block_names.clear();
    for (const auto& b : s.blocks) file_mesh->block_names.push_back(b.name);
    finalize_mesh(*file_mesh);
    s.file_mesh = file_mesh;
  }

  std::set<std::string> sets;
  if (file_mesh) {
    for (const auto& [name, faces] : file_mesh->face_sets) sets.insert(name);
  } else {
    const char* axes = "xyz";
    for (int d = 0; d < s.dim; ++d) {
      sets.insert(std::string(1, axes[d]) + "_lower");
      sets.insert(std::string(1, axes[d]) + "_upper");
    }
  }
  sn.skip("boundaries");
  if (sn.has("boundaries"))
    for (auto& bn : sn.list("boundaries")) s.boundaries.push_back(read_boundary(bn, s.dim, sets));

  if (auto init = sn.optional_child("initial")) {
    init->skip("energy_deposits");
    if (init->has("energy_deposits"))
      for (auto& dn : init->list("energy_deposits")) {
        DepositSpec dep;
        known_keys(dn, {"energy", "point", "lower", "upper"});
        dep.energy = dn.require<double>("energy", config::positive());
        const bool p = dn.has("point"), bx = dn.has("lower") || dn.has("upper");
        if (p == bx) dn.fail("point", "either point: [..] or lower: [..], upper: [..]");
        dep.is_point = p;
        if (p) dep.point = read_point(dn, "point", s.dim);
        else {
          dep.lower = read_point(dn, "lower", s.dim);
          dep.upper = read_point(dn, "upper", s.dim);
        }
        dn.finish();
        s.deposits.push_back(dep);
      }
    init->finish();
  }

  if (auto num = sn.optional_child("numerics")) {
    Numerics& nu = s.numerics;
    nu.cfl = num->get<double>("cfl", nu.cfl, config::in_open_closed(0.0, 1.0));
    nu.q_quadratic = num->get<double>("q_quadratic", nu.q_quadratic, config::non_negative());
    nu.q_linear = num->get<double>("q_linear", nu.q_linear, config::non_negative());
    nu.hourglass = num->get<double>("hourglass", nu.hourglass, config::in_range(0.0, 1.0));
    nu.dt_growth = num->get<double>("dt_growth", nu.dt_growth, config::in_range(1.0, 10.0));
    nu.dt_initial = num->get<double>("dt_initial", nu.dt_initial, config::non_negative());
    nu.dt_min = num->get<double>("dt_min", nu.dt_min, config::non_negative());
    nu.max_subcycles = num->get<int>("max_subcycles", nu.max_subcycles, config::int_at_least(1));
    num->finish();
  }

  if (auto ale = sn.optional_child("ale")) {
    known_keys(*ale, {"blocks", "every", "sweeps"});
    for (auto& bn : ale->list("blocks")) {
      const std::string name = bn.as<std::string>();
      auto it = std::find_if(s.blocks.begin(), s.blocks.end(), [&](const BlockSpec& b) { return b.name == name; });
      if (it == s.blocks.end()) {
        std::string hint = config::closest(name, names);
        ale->fail("blocks", "names of blocks in solid.blocks" + (hint.empty() ? "" : "; did you mean '" + hint + "'?") +
                                ", got '" + name + "'");
      }
      if (it->rigid || !it->has_eos || it->material.strength.enabled)
        ale->fail("blocks", "gas blocks (an eos, no strength, not rigid) for ALE relaxation, got '" + name + "'");
      s.ale.blocks.push_back(name);
    }
    if (s.ale.blocks.empty()) ale->fail("blocks", "at least one block name");
    s.ale.every = ale->get<int>("every", 1, config::int_at_least(1));
    s.ale.sweeps = ale->get<int>("sweeps", 4, config::int_at_least(0));
    ale->finish();
  }

  // In a coupled scene the coupler owns time (coupling.time); the solid's time: is then optional.
  const double coupled_end = config::coupled_end_time(root);
  Node time = coupled_end > 0 ? sn.child_or_empty("time") : sn.child("time");
  known_keys(time, {"end", "max_steps"});
  s.t_end = coupled_end > 0 ? time.get<double>("end", coupled_end, config::positive())
                            : time.require<double>("end", config::positive());
  s.max_steps = time.get<long>("max_steps", s.max_steps,
                               [](const long& v) { return v >= 1 ? std::string() : std::string("an integer >= 1"); });
  time.finish();

  {
    auto out = sn.optional_child("output");
    s.output_times = config::read_output_times(out ? &*out : nullptr, s.t_end);
    if (out) {
      s.write_snapshots = out->get<bool>("snapshots", true);
      s.history_every = out->get<int>("history_every", 0, config::int_at_least(0));
      out->finish();
    }
  }

  // checkpoint sets of a solid-only run (the coupler writes them in a coupled one: coupling.checkpoint)
  if (auto ck = sn.optional_child("checkpoint")) {
    if (coupled_end > 0)
      sn.fail("checkpoint",
              "no solid.checkpoint in a coupled scene (the coupler checkpoints the whole run: put it under "
              "coupling.checkpoint)");
    s.checkpoint = checkpoint::read_checkpoint_policy(&*ck);
  }

  s.threads = sn.get<int>("threads", 0, config::int_at_least(0));
  sn.finish();
  return s;
}

namespace {
SolidScene read_document(Node root, const std::string& base_dir, const MeshLoader& load_mesh = {}) {
  SolidScene s = read_solid_scene(root, base_dir, load_mesh);
  s.name = root.get<std::string>("name", "scene");
  root.get<std::string>("description", "");
  for (const char* other : {"fluid", "coupling", "launcher"}) root.skip(other);
  root.finish();
  return s;
}
}  // namespace

SolidScene load_solid_scene(const std::string& file, const std::vector<std::string>& overrides,
                            const MeshLoader& load_mesh) {
  return read_document(config::load_file(file, overrides), config::scene_base_dir(file), load_mesh);
}

SolidScene parse_solid_scene(const std::string& yaml_text, const std::vector<std::string>& overrides) {
  return read_document(config::load_string(yaml_text, "<scene>", overrides), "");
}

}  // namespace cosim::solid
