// The element pass works on batches of elements, one per vector lane. Each element must get the same bits
// whatever batch it falls in and whatever shares the batch: a pass over the whole range must equal passes
// over one element at a time (a batch with one live lane, the others padding), on a distorted 3D and 2D
// mesh with Mie-Grueneisen compression and tension, spin and plastic flow, and an inverted element.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "solid_solver/forces/element_kernel.h"
#include "solid_test_util.h"

using namespace cosim::solid;
using solid_test::hash_unit;

namespace {

struct Field {
  std::vector<int> conn;
  std::vector<double> x, v, vbar, emass, vol, ie, p, q, c, s, eps_p, w_p, fc;

  ElementPassArgs args(double dt, const Strength& str) {
    return {conn.data(), x.data(), v.data(), vbar.data(), emass.data(), vol.data(), ie.data(),
            p.data(),    q.data(), c.data(), s.data(),    eps_p.data(), w_p.data(), fc.data(),
            dt,          4.0,      0.15,     0.1,         -1e9,         str};
  }
  bool same_bits(const Field& o) const {
    auto eq = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    return eq(vol, o.vol) && eq(ie, o.ie) && eq(p, o.p) && eq(q, o.q) && eq(c, o.c) && eq(s, o.s) &&
           eq(eps_p, o.eps_p) && eq(w_p, o.w_p) && eq(fc, o.fc);
  }
};

// A structured grid of nx x ny (x nz) elements with perturbed nodes and random velocities about a
// compression along x (so some elements compress, some expand), random deviators near the yield surface.
template <int D>
Field distorted_grid(int nx, int ny, int nz) {
  constexpr int N = ElemTraits<D>::npe;
  const int kz = D == 3 ? nz : 1;
  const int px = nx + 1, py = ny + 1, pz = D == 3 ? nz + 1 : 1;
  const double h = 1e-3;
  Field f;
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) {
        const int n = (k * py + j) * px + i;
        const double X[3] = {i * h, j * h, k * h};
        for (int d = 0; d < D; ++d) {
          f.x.push_back(X[d] + 0.12 * h * hash_unit(n, d));
          const double vd = (d == 0 ? -300.0 * X[0] / (nx * h) : 0.0) + 40.0 * hash_unit(n, d + 3);
          f.v.push_back(vd);
          f.vbar.push_back(vd + 5.0 * hash_unit(n, d + 6));
        }
      }
  for (int k = 0; k < kz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        auto node = [&](int a, int b, int c) { return ((k + c) * py + j + b) * px + i + a; };
        if (D == 2) {
          for (int n : {node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(0, 1, 0)}) f.conn.push_back(n);
        } else {
          for (int n : {node(0, 0, 0), node(1, 0, 0), node(1, 1, 0), node(0, 1, 0), node(0, 0, 1), node(1, 0, 1),
                        node(1, 1, 1), node(0, 1, 1)})
            f.conn.push_back(n);
        }
      }
  const int ne = nx * ny * kz;
  const double vol0 = D == 3 ? h * h * h : h * h;
  for (int z = 0; z < ne; ++z) {
    f.emass.push_back(7850.0 * vol0 * (1.0 + 0.08 * hash_unit(z, 1)));  // compression and tension
    f.vol.push_back(vol0 * (1.0 + 0.01 * hash_unit(z, 2)));
    f.ie.push_back(1e3 * vol0 * (1.0 + hash_unit(z, 3)));
    f.p.push_back(1e9 * hash_unit(z, 4));
    f.q.push_back(z % 3 == 0 ? 0.0 : 1e8 * (1.0 + hash_unit(z, 5)));
    f.c.push_back(0.0);
    for (int k = 0; k < 6; ++k) f.s.push_back(z % 5 == 0 ? 0.0 : 4e8 * hash_unit(z, 10 + k));
    f.eps_p.push_back(z % 2 == 0 ? 0.0 : 0.01 * (1.0 + hash_unit(z, 6)));
    f.w_p.push_back(0.0);
    for (int a = 0; a < N * D; ++a) f.fc.push_back(1e3 * hash_unit(z, 20 + a));
  }
  // A zero-spin element: its nodes move by a uniform velocity.
  for (int a = 0; a < N; ++a)
    for (int d = 0; d < D; ++d) f.v[static_cast<std::size_t>(f.conn[N + a]) * D + d] = d == 0 ? -7.0 : 3.0;
  return f;
}

template <int D>
void expect_batches_equal_single_elements(int nx, int ny, int nz, bool invert_one) {
  const Field init = distorted_grid<D>(nx, ny, nz);
  Field whole = init;
  const int ne = static_cast<int>(whole.vol.size());
  if (invert_one) {  // fold one interior node of element ne/2 through the element
    const int z = ne / 2;
    const int n = whole.conn[static_cast<std::size_t>(z) * ElemTraits<D>::npe + 2];
    for (int d = 0; d < D; ++d) whole.x[static_cast<std::size_t>(n) * D + d] -= 2.5e-3;
  }
  Field single = whole;
  const MieGruneisenEos steel{7850.0, 4578.0, 1.33, 1.67};
  const Strength str{true, 7.77e10, 7.92e8, 5.0e8};
  const double dt = 2e-8;
  ElementPassResult rw, rs;
  element_pass<D, MieGruneisenEos, true>(whole.args(dt, str), steel, 0, ne, rw);
  for (int z = 0; z < ne; ++z) element_pass<D, MieGruneisenEos, true>(single.args(dt, str), steel, z, z + 1, rs);
  EXPECT_TRUE(whole.same_bits(single));
  EXPECT_EQ(rw.dt_min, rs.dt_min);
  EXPECT_EQ(rw.bad, rs.bad);
  EXPECT_EQ(rw.bad_kind, rs.bad_kind);
  if (invert_one) {
    // The inverted element is reported (it or one that shares the folded node) and is not written.
    ASSERT_GE(rw.bad, 0);
    EXPECT_EQ(rw.bad_kind, 1);
    EXPECT_EQ(whole.vol[rw.bad], init.vol[rw.bad]);
    EXPECT_EQ(whole.s[rw.bad * 6], init.s[rw.bad * 6]);
  } else {
    EXPECT_EQ(rw.bad, -1);
    EXPECT_EQ(rw.ie_sum, rs.ie_sum);  // summed in element order either way
  }
  // The test covers what it claims: plastic flow in some elements and not in others, both EOS branches.
  int plastic = 0, elastic = 0, compressed = 0, stretched = 0;
  for (int z = 0; z < ne; ++z) {
    (whole.eps_p[z] > init.eps_p[z] ? plastic : elastic)++;
    (whole.emass[z] / whole.vol[z] > 7850.0 ? compressed : stretched)++;
  }
  EXPECT_GT(plastic, 0);
  EXPECT_GT(elastic, 0);
  EXPECT_GT(compressed, 0);
  EXPECT_GT(stretched, 0);
}

}  // namespace

TEST(ElementBatches, Hexes3dEqualOneElementAtATime) { expect_batches_equal_single_elements<3>(5, 3, 3, false); }
TEST(ElementBatches, Quads2dEqualOneElementAtATime) { expect_batches_equal_single_elements<2>(7, 5, 1, false); }
TEST(ElementBatches, InvertedHexReportedAndNotWritten) { expect_batches_equal_single_elements<3>(5, 3, 3, true); }
