// What a scene asks cosim to run, read and checked before anything starts: a coupled run (fluid: and solid:, the
// three processes), a fluid-only run (fluid: alone) or a solid-only run (solid: alone), its name, the programs
// (the scene's launcher: commands where the command line gives none), and what each checked program will do.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "launcher/launch.h"

namespace cosim::launcher {

enum class RunKind { Coupled, FluidOnly, SolidOnly };

struct ScenePlan {
  RunKind kind = RunKind::FluidOnly;
  std::string name;
  LaunchOptions eff;               // the options with the scene's launcher: commands filled in
  std::vector<std::string> lines;  // what each checked program will do
  nlohmann::json facts;            // the figures of their plans (scene_check.h)
  bool coupled() const { return kind == RunKind::Coupled; }
  bool has_fluid() const { return kind != RunKind::SolidOnly; }
  bool has_solid() const { return kind != RunKind::FluidOnly; }
};

// "coupled", "fluid-only", "solid-only".
const char* kind_name(RunKind k);

// Reads the scene as the run's programs will (each asked with --check); prints the error and gives nothing when
// it cannot be read or a program refuses it.
std::optional<ScenePlan> read_plan(const LaunchOptions& opt);

}  // namespace cosim::launcher
