// Readers shared by the parts of the fluid scene reader (scene.cpp): points, phases and their equations of
// state, and mixture states (scene_phases.cpp). Internal to the scene reader.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/config/config.h"
#include "fluid_solver/core/scene.h"

namespace cosim::fluid::scene_readers {

using config::read_point;

// One entry of fluid.phases: name, material (library or custom) and equation of state.
Phase read_phase(config::Node& n);

// A state: top-level defaults (rho | T, p, velocity, alpha list) with optional per-phase overrides. A condensed
// library material more than 10% from its reference density is refused unless its phase allows it. Every value in a
// physical range (|p| <= 1e13 Pa, rho in (0, 1e5] kg/m^3, T in (0, 1e9] K, speeds <= 1e5 m/s); a boundary's state
// (`boundary`) has p > 0.
MixtureValue read_state(config::Node& n, const std::vector<Phase>& phases, int dim, bool boundary = false);

}  // namespace cosim::fluid::scene_readers
