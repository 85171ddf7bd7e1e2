// The fluid state a scene will allocate, known from the scene alone: checked against the machine's available
// memory before anything is allocated (a 1e9-cell scene is refused with the keys to change, not killed later).
#pragma once

#include <cstddef>

#include "fluid_solver/core/scene.h"

namespace cosim::fluid {

// Bytes of the conservative (state, step start, residual) and primitive arrays over the cells with their ghost
// layers (the solver's Layout and Grid); the per-thread row buffers and the output are small beside them.
std::size_t estimated_state_bytes(const FluidScene& s);

}  // namespace cosim::fluid
