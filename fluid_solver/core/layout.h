// Structure-of-arrays layout of the conservative and primitive variables, fixed at compile
// time by the dimension DIM and the phase count NP.
//   conservative, per phase k: m = alpha rho, momentum alpha rho u (DIM), energy alpha rho E;
//                 plus alpha of phase 0 when NP = 2 (alpha of phase 1 = 1 - alpha_0), and, for a dispersed
//                 phase 1 only, its material internal energy alpha rho e (docs/methods.md §2.9).
//   primitive,    per phase k: rho, u (DIM), p, c; plus alpha of phase 0 when NP = 2, and the dispersed
//                 phase's granular energy k per unit mass.
// The last slot of each is allocated and computed only in a scene with a dispersed phase (kCons - 1 and
// kPrim - 1 variables otherwise).
#pragma once

#include <cstddef>
#include <vector>

namespace cosim::fluid {

template <int DIM, int NP>
struct Layout {
  static_assert(DIM >= 1 && DIM <= 3 && NP >= 1 && NP <= 2);
  static constexpr int kConsPerPhase = 2 + DIM;
  static constexpr int kCons = NP * kConsPerPhase + (NP > 1 ? 2 : 0);
  static constexpr int mass(int k) { return k * kConsPerPhase; }
  static constexpr int mom(int k, int d) { return k * kConsPerPhase + 1 + d; }
  static constexpr int energy(int k) { return k * kConsPerPhase + 1 + DIM; }
  static constexpr int alpha = NP * kConsPerPhase;  // valid only when NP > 1
  static constexpr int heat = alpha + 1;            // dispersed phase only

  static constexpr int kPrimPerPhase = 3 + DIM;
  static constexpr int kPrim = NP * kPrimPerPhase + (NP > 1 ? 2 : 0);
  static constexpr int rho(int k) { return k * kPrimPerPhase; }
  static constexpr int vel(int k, int d) { return k * kPrimPerPhase + 1 + d; }
  static constexpr int pres(int k) { return k * kPrimPerPhase + 1 + DIM; }
  static constexpr int sound(int k) { return k * kPrimPerPhase + 2 + DIM; }
  static constexpr int palpha = NP * kPrimPerPhase;  // valid only when NP > 1
  static constexpr int pgran = palpha + 1;           // dispersed phase only
  // Variables in use: without a dispersed phase the last slot of each is not there.
  static constexpr int cons_vars(bool dispersed) { return NP > 1 && !dispersed ? kCons - 1 : kCons; }
  static constexpr int prim_vars(bool dispersed) { return NP > 1 && !dispersed ? kPrim - 1 : kPrim; }
};

// NV arrays of `cells` doubles each, stored one after the other.
struct FieldArray {
  std::vector<double> data;
  std::size_t cells = 0;
  int vars = 0;
  void resize(int nvars, std::size_t ncells) {
    vars = nvars;
    cells = ncells;
    data.assign(static_cast<std::size_t>(nvars) * ncells, 0.0);
  }
  double* var(int v) { return data.data() + static_cast<std::size_t>(v) * cells; }
  const double* var(int v) const { return data.data() + static_cast<std::size_t>(v) * cells; }
};

// Point state of one phase (primitive), used by flux functions.
template <int DIM>
struct PhaseState {
  double rho;
  double u[DIM];
  double p;
  double c;
};

// Normal flux of one phase through a unit face area: mass, momentum (DIM), energy.
template <int DIM>
struct PhaseFlux {
  double mass = 0;
  double mom[DIM] = {};
  double energy = 0;
};

}  // namespace cosim::fluid
