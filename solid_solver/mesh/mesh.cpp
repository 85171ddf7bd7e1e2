#include "solid_solver/mesh/mesh.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace cosim::solid {

namespace {
const char* kSide[3][2] = {{"x_lower", "x_upper"}, {"y_lower", "y_upper"}, {"z_lower", "z_upper"}};
}

Mesh make_box_mesh(int dim, const std::array<int, 3>& cells, const std::array<double, 3>& lower,
                   const std::array<double, 3>& upper) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("box mesh: dimension must be 2 or 3");
  Mesh m;
  m.dim = dim;
  m.npe = dim == 2 ? 4 : 8;
  const int nx = cells[0], ny = cells[1], nz = dim == 3 ? cells[2] : 1;
  const int nnx = nx + 1, nny = ny + 1, nnz = dim == 3 ? nz + 1 : 1;
  m.num_nodes = nnx * nny * nnz;
  m.num_elements = nx * ny * nz;
  m.x0.resize(static_cast<std::size_t>(m.num_nodes) * dim);
  auto nid = [&](int i, int j, int k) { return i + nnx * (j + nny * k); };
  for (int k = 0; k < nnz; ++k)
    for (int j = 0; j < nny; ++j)
      for (int i = 0; i < nnx; ++i) {
        const int n = nid(i, j, k);
        const int ijk[3] = {i, j, k};
        for (int d = 0; d < dim; ++d)
          m.x0[n * dim + d] = lower[d] + (upper[d] - lower[d]) * ijk[d] / static_cast<double>(cells[d]);
      }
  m.conn.resize(static_cast<std::size_t>(m.num_elements) * m.npe);
  auto eid = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int* c = &m.conn[static_cast<std::size_t>(eid(i, j, k)) * m.npe];
        c[0] = nid(i, j, k);
        c[1] = nid(i + 1, j, k);
        c[2] = nid(i + 1, j + 1, k);
        c[3] = nid(i, j + 1, k);
        if (dim == 3) {
          c[4] = nid(i, j, k + 1);
          c[5] = nid(i + 1, j, k + 1);
          c[6] = nid(i + 1, j + 1, k + 1);
          c[7] = nid(i, j + 1, k + 1);
        }
      }
  m.element_block.assign(m.num_elements, 0);
  m.block_names = {"default"};

  // Node sets by side.
  const int nn[3] = {nnx, nny, nnz};
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side) {
      auto& set = m.node_sets[kSide[d][side]];
      const int target = side == 0 ? 0 : nn[d] - 1;
      for (int k = 0; k < nnz; ++k)
        for (int j = 0; j < nny; ++j)
          for (int i = 0; i < nnx; ++i) {
            const int ijk[3] = {i, j, k};
            if (ijk[d] == target) set.push_back(nid(i, j, k));
          }
    }
  // Face sets by side, outward orientation (local faces of the VTK quad / hex).
  // 2D edges: y- (0,1), x+ (1,2), y+ (2,3), x- (3,0).
  // 3D faces: x- (0,4,7,3), x+ (1,2,6,5), y- (0,1,5,4), y+ (3,7,6,2), z- (0,3,2,1), z+ (4,5,6,7).
  static const int edge2[3][2][2] = {{{3, 0}, {1, 2}}, {{0, 1}, {2, 3}}, {{0, 0}, {0, 0}}};
  static const int face3[3][2][4] = {
      {{0, 4, 7, 3}, {1, 2, 6, 5}}, {{0, 1, 5, 4}, {3, 7, 6, 2}}, {{0, 3, 2, 1}, {4, 5, 6, 7}}};
  for (int d = 0; d < dim; ++d)
    for (int side = 0; side < 2; ++side) {
      auto& set = m.face_sets[kSide[d][side]];
      const int target = side == 0 ? 0 : cells[d] - 1;
      for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) {
            const int ijk[3] = {i, j, k};
            if (ijk[d] != target) continue;
            const int e = eid(i, j, k);
            const int* c = &m.conn[static_cast<std::size_t>(e) * m.npe];
            BoundaryFace f{{-1, -1, -1, -1}, e};
            if (dim == 2) {
              f.nodes[0] = c[edge2[d][side][0]];
              f.nodes[1] = c[edge2[d][side][1]];
            } else {
              for (int q = 0; q < 4; ++q) f.nodes[q] = c[face3[d][side][q]];
            }
            set.push_back(f);
          }
    }
  return m;
}

void finalize_mesh(Mesh& m) {
  const int ne = m.num_elements, npe = m.npe;
  const int nb = static_cast<int>(m.block_names.size());
  std::vector<int> order(ne);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return m.element_block[a] < m.element_block[b]; });
  std::vector<int> new_of_old(ne);
  std::vector<int> conn(m.conn.size()), blk(ne);
  for (int i = 0; i < ne; ++i) {
    new_of_old[order[i]] = i;
    blk[i] = m.element_block[order[i]];
    std::copy_n(&m.conn[static_cast<std::size_t>(order[i]) * npe], npe, &conn[static_cast<std::size_t>(i) * npe]);
  }
  m.conn.swap(conn);
  m.element_block.swap(blk);
  for (auto& [name, faces] : m.face_sets)
    for (auto& f : faces) f.element = new_of_old[f.element];
  m.block_range.assign(nb, {0, 0});
  for (int b = 0; b < nb; ++b) {
    auto lo = std::lower_bound(m.element_block.begin(), m.element_block.end(), b);
    auto hi = std::upper_bound(m.element_block.begin(), m.element_block.end(), b);
    m.block_range[b] = {static_cast<int>(lo - m.element_block.begin()), static_cast<int>(hi - m.element_block.begin())};
  }
  // Node -> corner lists.
  m.node_corner_offset.assign(m.num_nodes + 1, 0);
  for (int c = 0; c < ne * npe; ++c) ++m.node_corner_offset[m.conn[c] + 1];
  for (int n = 0; n < m.num_nodes; ++n) m.node_corner_offset[n + 1] += m.node_corner_offset[n];
  m.node_corners.resize(static_cast<std::size_t>(ne) * npe);
  std::vector<int> fill(m.node_corner_offset.begin(), m.node_corner_offset.end() - 1);
  for (int c = 0; c < ne * npe; ++c) m.node_corners[fill[m.conn[c]]++] = c;
}

std::array<double, 3> element_centroid(const Mesh& m, const std::vector<double>& x, int e) {
  std::array<double, 3> c{0, 0, 0};
  for (int a = 0; a < m.npe; ++a) {
    const int n = m.conn[static_cast<std::size_t>(e) * m.npe + a];
    for (int d = 0; d < m.dim; ++d) c[d] += x[static_cast<std::size_t>(n) * m.dim + d];
  }
  for (int d = 0; d < m.dim; ++d) c[d] /= m.npe;
  return c;
}

}  // namespace cosim::solid
