// Compile-time choice of the flux used for same-phase contacts (the scene's `numerics.flux`).
#pragma once

#include "fluid_solver/core/scene.h"
#include "fluid_solver/flux/aufs.h"
#include "fluid_solver/flux/hllc.h"
#include "fluid_solver/flux/rusanov.h"

namespace cosim::fluid {

template <FluxKind FK, int DIM, int D>
inline PhaseFlux<DIM> same_phase_flux(const PhaseState<DIM>& L, const PhaseState<DIM>& R, const eos::StiffenedGas& e) {
  if constexpr (FK == FluxKind::AUFS) return aufs_flux<DIM, D>(L, R, e);
  else if constexpr (FK == FluxKind::HLLC) return hllc_flux<DIM, D>(L, e, R, e).flux;
  else return rusanov_flux<DIM, D>(L, R, e);
}

}  // namespace cosim::fluid
