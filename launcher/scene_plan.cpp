#include "launcher/scene_plan.h"

#include <fmt/format.h>

#include <iostream>

#include "common/app/scene_kind.h"
#include "common/config/config.h"
#include "launcher/python_paths.h"
#include "launcher/scene_check.h"

namespace fs = std::filesystem;

namespace cosim::launcher {

const char* kind_name(RunKind k) {
  switch (k) {
    case RunKind::Coupled: return "coupled";
    case RunKind::FluidOnly: return "fluid-only";
    case RunKind::SolidOnly: return "solid-only";
  }
  return "?";
}

std::optional<ScenePlan> read_plan(const LaunchOptions& opt) {
  ScenePlan plan;
  std::string& name = plan.name;
  LaunchOptions& eff = plan.eff;
  eff = opt;
  try {
    config::Node root = config::load_file(opt.scene, opt.overrides);
    app::refuse_coupling_without_solid(root);
    if (!root.has("fluid") && !root.has("solid"))
      root.fail("fluid", "a fluid: or a solid: section (a fluid-only, solid-only or coupled run)");
    if (!root.has("fluid") && root.has("coupling"))
      root.fail("coupling",
                "no coupling: section in a scene without fluid: (a solid-only run); add a fluid: "
                "section for a coupled run");
    plan.kind = !root.has("fluid") ? RunKind::SolidOnly : root.has("solid") ? RunKind::Coupled : RunKind::FluidOnly;
    name = root.get<std::string>("name", fs::path(opt.scene).stem().string());
    // launcher: {fluid: CMD, solid: CMD, coupler: CMD}: the programs of this scene (e.g. a solid written in
    // Python); {bin} is the directory of cosim, {python} the build's python directory, {scene_dir} the directory
    // of the scene the user gave (a program kept next to the scene).
    if (auto l = root.optional_child("launcher")) {
      const auto expand = [&](std::string c) {
        for (const auto& [key, value] :
             {std::pair<std::string, std::string>{"{bin}", opt.bin_dir.string()},
              {"{python}", python_paths(opt.bin_dir).scripts.string()},
              {"{scene_dir}", fs::absolute(opt.scene).parent_path().lexically_normal().string()}})
          for (std::size_t at; (at = c.find(key)) != std::string::npos;) c.replace(at, key.size(), value);
        return c;
      };
      // Each key is read (and so known) even where the command line's --fluid-exe etc. override it.
      const std::string fluid = l->get<std::string>("fluid", ""), solid = l->get<std::string>("solid", ""),
                        coupler = l->get<std::string>("coupler", "");
      const int ranks = l->get<int>("fluid_ranks", 0, config::int_at_least(1));
      if (eff.fluid_ranks == 0) eff.fluid_ranks = ranks;
      const int solid_ranks = l->get<int>("solid_ranks", 0, config::int_at_least(1));
      if (eff.solid_ranks == 0) eff.solid_ranks = solid_ranks;
      if (eff.fluid_cmd.empty()) eff.fluid_cmd = expand(fluid);
      if (eff.solid_cmd.empty()) eff.solid_cmd = expand(solid);
      if (eff.coupler_cmd.empty()) eff.coupler_cmd = expand(coupler);
      l->finish();
    }
  } catch (const std::exception& e) {
    std::cerr << "cosim: " << e.what() << "\n";
    return std::nullopt;
  }
  if (eff.fluid_ranks == 0) eff.fluid_ranks = 1;
  if (eff.fluid_ranks > 1 && !plan.has_fluid()) {
    std::cerr << fmt::format("cosim: {} fluid ranks: a {} run has no fluid\n", eff.fluid_ranks, kind_name(plan.kind));
    return std::nullopt;
  }
  if (eff.solid_ranks == 0) eff.solid_ranks = 1;
  if (eff.solid_ranks > 1 && !plan.has_solid()) {
    std::cerr << fmt::format("cosim: {} solid ranks: a {} run has no solid\n", eff.solid_ranks, kind_name(plan.kind));
    return std::nullopt;
  }
  for (const auto& [what, cmd] : {std::pair<const char*, const std::string&>{"the fluid command", eff.fluid_cmd},
                                  {"the solid command", eff.solid_cmd},
                                  {"the coupler command", eff.coupler_cmd}}) {
    try {
      split_command(cmd);
    } catch (const std::exception& e) {
      std::cerr << "cosim: " << what << ": " << e.what() << "\n";
      return std::nullopt;
    }
  }
  // The whole scene as each of the run's programs reads it, before anything starts or is written.
  const SceneCheck sc{opt.scene,
                      opt.overrides,
                      plan.coupled(),
                      opt.bin_dir,
                      plan.has_fluid() && eff.fluid_cmd.empty(),
                      plan.has_solid() && eff.solid_cmd.empty(),
                      eff.coupler_cmd.empty(),
                      plan.kind == RunKind::SolidOnly,
                      eff.fluid_ranks,
                      eff.solid_ranks};
  if (const auto refusal = check_scene(sc, &plan.lines, &plan.facts)) {
    std::cerr << fmt::format("cosim: {} refuses the scene (nothing was started):\n{}\n", refusal->program,
                             refusal->message);
    return std::nullopt;
  }
  return plan;
}

int check(const LaunchOptions& opt) {
  const auto plan = read_plan(opt);
  if (!plan) return 2;
  std::cout << fmt::format("{}: valid; a {} run of {}\n", opt.scene, kind_name(plan->kind),
                           plan->coupled()                    ? "the fluid, the solid and the coupler"
                           : plan->kind == RunKind::SolidOnly ? "the solid"
                                                              : "the fluid");
  for (std::string l : plan->lines) {  // a program's plan may hold several lines: each indented
    for (std::size_t at = 0; (at = l.find('\n', at)) != std::string::npos; at += 3) l.replace(at, 1, "\n  ");
    std::cout << "  " << l << "\n";
  }
  if (plan->coupled())
    if (const std::string estimate = coupled_estimate(plan->facts); !estimate.empty())
      std::cout << "  " << estimate << "\n";
  for (const auto& [role, cmd] : {std::pair<const char*, const std::string&>{"fluid", plan->eff.fluid_cmd},
                                  {"solid", plan->eff.solid_cmd},
                                  {"coupler", plan->eff.coupler_cmd}})
    if (!cmd.empty() && (plan->coupled() || (std::string(role) == "fluid" && plan->has_fluid()) ||
                         (std::string(role) == "solid" && plan->has_solid())))
      std::cout << fmt::format("  {}: the scene's own program (not checked): {}\n", role, cmd);
  return 0;
}

}  // namespace cosim::launcher
