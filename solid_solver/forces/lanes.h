// A batch of element values processed together: one GCC/Clang vector of kLanes doubles, one element per
// lane. Arithmetic on a Lanes value is the scalar arithmetic done lane by lane (IEEE, no reassociation,
// no contraction under -ffp-contract=off), so a batched kernel gives the bits of the scalar one; the
// helpers below keep that true for the operations that have no vector operator (select, sqrt, cbrt).
// Generic code works on double and Lanes alike: comparisons give bool or a lane mask, and `m ? a : b`
// selects per lane for a mask.
#pragma once

#include <cmath>
#include <cstddef>

namespace cosim::solid::lanes {

constexpr int kLanes = 8;
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));

inline Lanes splat(double x) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = x;
  return r;
}

// The constant x as a value of the type of the first argument.
inline double like(double, double x) { return x; }
inline Lanes like(Lanes, double x) { return splat(x); }

// max(p, 0) with std::max's rule (p < 0 ? 0 : p), so a NaN stays a NaN as in the scalar code.
inline double max_zero(double p) { return p < 0.0 ? 0.0 : p; }
inline Lanes max_zero(Lanes p) { return p < 0.0 ? Lanes{} : p; }

inline double sqrt(double x) { return std::sqrt(x); }
inline Lanes sqrt(Lanes x) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(x[l]);
  return r;
}

inline Lanes cbrt(Lanes x) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::cbrt(x[l]);
  return r;
}

// Lane l takes p[idx[l]].
inline Lanes gather(const double* p, const std::ptrdiff_t (&idx)[kLanes]) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r[l] = p[idx[l]];
  return r;
}

// Any lane of a mask set.
template <class M>
inline bool any(M m) {
  for (int l = 0; l < kLanes; ++l)
    if (m[l]) return true;
  return false;
}

}  // namespace cosim::solid::lanes
