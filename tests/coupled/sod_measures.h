// Measures of the modified Sod problem (paper 9.4, configs/modified_sod_2d.yaml) read from a run directory:
// L1 errors against the exact 1D Riemann solution on the background's flow cells and on the foreground's
// element centres, the positions of the shock, the contact and the foreground's edges, shock widths, and the
// totals of both domains together.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/exact/exact_riemann.h"
#include "common/io/hdf5_file.h"

namespace cosim::test::sod {

namespace fs = std::filesystem;

constexpr double kGamma = 1.4, kX0 = 0.5;
inline exact::RiemannSolution solution() {
  return exact::RiemannSolution({1.0, -0.5, 1.0}, {kGamma, 0.0}, {0.125, 0.0, 0.1}, {kGamma, 0.0});
}

inline fs::path snapshot(const fs::path& dir, const std::string& solver, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%06d.h5", solver.c_str(), k);
  return fs::exists(dir / solver) ? dir / solver / name : dir / name;
}

// The background at one snapshot: cell-centred fields of a uniform 2D grid, row-major (x fastest).
struct Background {
  double t = 0, dx = 0, dy = 0;
  int nx = 0, ny = 0;
  std::vector<double> rho, u, v, p;
  std::vector<char> flow;  // categories fluid and fluid-cut (everything without a body)
  int at(int i, int j) const { return j * nx + i; }
  double xc(int i) const { return (i + 0.5) * dx; }
};

inline Background read_background(const fs::path& dir, int k) {
  io::Hdf5File h(snapshot(dir, "fluid", k), io::Hdf5File::Mode::ReadOnly);
  Background b;
  b.t = h.read_double_attribute("/", "time").at(0);
  const auto cells = h.read_int64_attribute("/grid", "cells");
  const auto spacing = h.read_double_attribute("/grid", "spacing");
  b.nx = static_cast<int>(cells.at(0));
  b.ny = static_cast<int>(cells.at(1));
  b.dx = spacing.at(0);
  b.dy = spacing.at(1);
  b.rho = h.read_doubles("/cell/gas_density");
  b.p = h.read_doubles("/cell/gas_pressure");
  const auto vel = h.read_doubles("/cell/gas_velocity");
  const std::size_t n = b.rho.size();
  b.u.resize(n);
  b.v.resize(n);
  for (std::size_t c = 0; c < n; ++c) b.u[c] = vel[3 * c], b.v[c] = vel[3 * c + 1];
  b.flow.assign(n, 1);
  if (h.exists("/cell/embedded_category")) {
    const auto cat = h.read_doubles("/cell/embedded_category");
    for (std::size_t c = 0; c < n; ++c) b.flow[c] = cat[c] <= 1.0;
  }
  return b;
}

// The foreground at one snapshot: element centres, areas and fields; node positions and velocities.
struct Foreground {
  double t = 0;
  std::vector<double> xn, yn, un, vn;              // nodes
  std::vector<double> xc, yc, area, rho, p, u, e;  // elements (u: mean of the corner velocities; e specific)
  std::vector<std::array<std::int64_t, 4>> conn;
};

inline Foreground read_foreground(const fs::path& dir, int k) {
  io::Hdf5File h(snapshot(dir, "solid", k), io::Hdf5File::Mode::ReadOnly);
  Foreground f;
  f.t = h.read_double_attribute("/", "time").at(0);
  const auto x = h.read_doubles("/grid/coordinates"), vel = h.read_doubles("/node/velocity");
  const auto con = h.read_int64s("/grid/connectivity");
  for (std::size_t n = 0; n < x.size() / 3; ++n) {
    f.xn.push_back(x[3 * n]), f.yn.push_back(x[3 * n + 1]);
    f.un.push_back(vel[3 * n]), f.vn.push_back(vel[3 * n + 1]);
  }
  f.rho = h.read_doubles("/cell/density");
  f.p = h.read_doubles("/cell/pressure");
  f.e = h.read_doubles("/cell/energy");
  for (std::size_t el = 0; el < con.size() / 4; ++el) {
    const std::array<std::int64_t, 4> q{con[4 * el], con[4 * el + 1], con[4 * el + 2], con[4 * el + 3]};
    f.conn.push_back(q);
    double cx = 0, cy = 0, cu = 0;
    for (auto n : q) cx += f.xn[n] / 4, cy += f.yn[n] / 4, cu += f.un[n] / 4;
    // Shoelace area of the quadrilateral (counter-clockwise nodes).
    const double a = 0.5 * ((f.xn[q[2]] - f.xn[q[0]]) * (f.yn[q[3]] - f.yn[q[1]]) -
                            (f.xn[q[3]] - f.xn[q[1]]) * (f.yn[q[2]] - f.yn[q[0]]));
    f.xc.push_back(cx), f.yc.push_back(cy), f.u.push_back(cu), f.area.push_back(std::abs(a));
  }
  return f;
}

struct Errors {
  double rho = 0, u = 0, p = 0;  // L1 (mean absolute error, area-weighted)
};

inline Errors background_errors(const Background& b) {
  const auto s = solution();
  Errors e;
  double w = 0;
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i) {
      const int c = b.at(i, j);
      if (!b.flow[c]) continue;
      const auto ex = s.sample((b.xc(i) - kX0) / b.t);
      e.rho += std::abs(b.rho[c] - ex.rho), e.u += std::abs(b.u[c] - ex.u), e.p += std::abs(b.p[c] - ex.p);
      w += 1;
    }
  return {e.rho / w, e.u / w, e.p / w};
}

inline Errors foreground_errors(const Foreground& f) {
  const auto s = solution();
  Errors e;
  double w = 0;
  for (std::size_t el = 0; el < f.rho.size(); ++el) {
    const auto ex = s.sample((f.xc[el] - kX0) / f.t);
    const double a = f.area[el];
    e.rho += a * std::abs(f.rho[el] - ex.rho), e.u += a * std::abs(f.u[el] - ex.u), e.p += a * std::abs(f.p[el] - ex.p);
    w += a;
  }
  return {e.rho / w, e.u / w, e.p / w};
}

// L1(rho) of the coupled solution over the domain: the foreground's elements where it lies, the background's flow
// cells elsewhere (a cell the interface cuts counted whole), each weighted by its area.
inline double domain_density_error(const Background& b, const Foreground& f) {
  const auto s = solution();
  double e = 0, w = 0;
  const double a = b.dx * b.dy;
  for (int j = 0; j < b.ny; ++j)
    for (int i = 0; i < b.nx; ++i)
      if (b.flow[b.at(i, j)]) {
        e += a * std::abs(b.rho[b.at(i, j)] - s.sample((b.xc(i) - kX0) / b.t).rho);
        w += a;
      }
  for (std::size_t el = 0; el < f.rho.size(); ++el) {
    e += f.area[el] * std::abs(f.rho[el] - s.sample((f.xc[el] - kX0) / f.t).rho);
    w += f.area[el];
  }
  return e / w;
}

// Where the density on the background's middle row crosses `level` going from `from` towards `to` (cell
// indices), linearly interpolated between flow cells; NaN if it does not.
inline double row_crossing(const Background& b, double level, int from, int to) {
  const int j = b.ny / 2, step = to > from ? 1 : -1;
  for (int i = from; i != to; i += step) {
    const int a = b.at(i, j), c = b.at(i + step, j);
    if (!b.flow[a] || !b.flow[c]) continue;
    if ((b.rho[a] - level) * (b.rho[c] - level) <= 0 && b.rho[a] != b.rho[c])
      return b.xc(i) + step * b.dx * (b.rho[a] - level) / (b.rho[a] - b.rho[c]);
  }
  return std::nan("");
}

inline double background_shock(const Background& b) {
  const auto st = solution().star();
  return row_crossing(b, 0.5 * (st.rho_right + 0.125), b.nx - 1, 0);
}
// The contact: searched from the left state's side up to `right_limit` (the foreground's left edge).
inline double background_contact(const Background& b, double right_limit) {
  const auto st = solution().star();
  const int stop = std::min(b.nx - 1, static_cast<int>(right_limit / b.dx));
  return row_crossing(b, 0.5 * (st.rho_left + st.rho_right), static_cast<int>(0.55 / b.dx), stop);
}

// Mean x of the nodes that started on x = x0 (the foreground's left or right edge).
inline double edge_position(const Foreground& start, const Foreground& now, double x0) {
  double s = 0;
  int n = 0;
  for (std::size_t i = 0; i < start.xn.size(); ++i)
    if (std::abs(start.xn[i] - x0) < 1e-9) s += now.xn[i], ++n;
  return n ? s / n : std::nan("");
}

// Shock width in cells: the density jump over the largest jump between neighbouring cells (elements) along
// the middle of the channel. A shock spread over k cells gives about k.
inline double width_in_cells(std::vector<std::pair<double, double>> x_rho) {
  std::sort(x_rho.begin(), x_rho.end());
  double steepest = 0;
  for (std::size_t i = 1; i < x_rho.size(); ++i)
    steepest = std::max(steepest, std::abs(x_rho[i].second - x_rho[i - 1].second));
  const auto st = solution().star();
  return steepest > 0 ? (st.rho_right - 0.125) / steepest : std::nan("");
}
inline double background_shock_width(const Background& b, double x_from) {
  std::vector<std::pair<double, double>> row;
  for (int i = 0; i < b.nx; ++i)
    if (b.xc(i) > x_from && b.flow[b.at(i, b.ny / 2)]) row.push_back({b.xc(i), b.rho[b.at(i, b.ny / 2)]});
  return width_in_cells(row);
}
inline double foreground_shock_width(const Foreground& f, double element_height) {
  std::vector<std::pair<double, double>> row;
  for (std::size_t el = 0; el < f.rho.size(); ++el)
    if (std::abs(f.yc[el] - 0.5) < 0.6 * element_height) row.push_back({f.xc[el], f.rho[el]});
  return width_in_cells(row);
}

// Totals of both domains together (per unit depth): mass, x momentum, total energy. Background: flow cells.
// Foreground: element masses, nodal momenta (element masses lumped a quarter to each corner) and internal plus
// kinetic energy.
inline std::array<double, 3> totals(const Background& b, const Foreground* f) {
  std::array<double, 3> s{0, 0, 0};
  const double a = b.dx * b.dy;
  for (std::size_t c = 0; c < b.rho.size(); ++c) {
    if (!b.flow[c]) continue;
    s[0] += a * b.rho[c];
    s[1] += a * b.rho[c] * b.u[c];
    s[2] += a * (b.p[c] / (kGamma - 1) + 0.5 * b.rho[c] * (b.u[c] * b.u[c] + b.v[c] * b.v[c]));
  }
  if (!f) return s;
  std::vector<double> mn(f->xn.size(), 0.0);
  for (std::size_t el = 0; el < f->rho.size(); ++el) {
    const double m = f->rho[el] * f->area[el];
    s[0] += m;
    s[2] += m * f->e[el];
    for (auto n : f->conn[el]) mn[n] += m / 4;
  }
  for (std::size_t n = 0; n < mn.size(); ++n) {
    s[1] += mn[n] * f->un[n];
    s[2] += 0.5 * mn[n] * (f->un[n] * f->un[n] + f->vn[n] * f->vn[n]);
  }
  return s;
}

}  // namespace cosim::test::sod
