// A row of cells of a two-phase conservative state, as views into the solver's arrays: what the row kernels of
// the relaxations and exchanges (relax_row.h, exchange_row.h) work on. The kernels take it by value: a local copy,
// whose pointers the compiler sees loop-invariant, so that their loops vectorise.
#pragma once

namespace cosim::fluid {

// alpha0, per phase mass, momentum and total energy, and (a dispersed phase with a granular temperature) the
// particles' material energy.
template <int DIM>
struct TwoPhaseRow {
  double* alpha = nullptr;
  double* m[2] = {nullptr, nullptr};
  double* mom[2][DIM] = {};
  double* E[2] = {nullptr, nullptr};
  double* heat = nullptr;
};

}  // namespace cosim::fluid
