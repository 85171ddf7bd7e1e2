// Run under mpirun by tests/parallel: checks the MPI module on this rank count. Every rank fills its block of a mesh
// with the global index of each cell, exchanges the ghost layers axis by axis and checks each ghost cell against the
// cell it stands for (wrapped on a periodic axis split over several blocks, untouched beyond the domain); then the
// gather and scatter of blocks and the reductions. Usage: cart_comm_check DIM NX NY NZ PERIODIC(0/1). Exit code 0
// when everything holds; each failure is printed with its rank.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/parallel/mpi/cart_comm.h"

using namespace cosim::parallel;

int main(int argc, char** argv) {
  MpiSession mpi(&argc, &argv);
  if (argc != 6) {
    std::fprintf(stderr, "usage: cart_comm_check DIM NX NY NZ PERIODIC\n");
    return 2;
  }
  const int dim = std::atoi(argv[1]);
  const Index3 cells{std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4])};
  const bool periodic = std::atoi(argv[5]) != 0;
  const Layout layout = choose_layout(mpi.size(), dim, cells, 2);
  CartComm comm(mpi, layout, {periodic, periodic && dim > 1, periodic && dim > 2}, cells);
  const Block& b = comm.block();
  PaddedBox box;
  box.dim = dim;
  for (int d = 0; d < 3; ++d) box.n[d] = b.upper[d] - b.lower[d];
  const Index3 p = box.padded();
  const std::size_t total = static_cast<std::size_t>(p[0]) * p[1] * p[2];
  const auto value = [&](int var, int i, int j, int k) {
    return var * 1e9 + ((static_cast<double>(k) * cells[1] + j) * cells[0] + i);
  };
  const int nvars = 3;
  std::vector<std::vector<double>> field(nvars, std::vector<double>(total, -1.0));
  const auto at = [&](int i, int j, int k) {  // padded index of block-local cell (i, j, k)
    const int o = box.ng;
    return static_cast<std::size_t>((i + o) + p[0] * ((j + (dim > 1 ? o : 0)) + p[1] * (k + (dim > 2 ? o : 0))));
  };
  for (int v = 0; v < nvars; ++v)
    for (int k = 0; k < box.n[2]; ++k)
      for (int j = 0; j < box.n[1]; ++j)
        for (int i = 0; i < box.n[0]; ++i)
          field[v][at(i, j, k)] = value(v, b.lower[0] + i, b.lower[1] + j, b.lower[2] + k);
  std::vector<double*> vars{field[0].data(), field[1].data(), field[2].data()};
  for (int d = 0; d < dim; ++d) comm.exchange_ghosts(vars.data(), nvars, box, d);

  int failures = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 5) std::fprintf(stderr, "rank %d of %d: %s\n", comm.rank(), comm.size(), what.c_str());
  };
  const int g = box.ng;
  for (int k = dim > 2 ? -g : 0; k < box.n[2] + (dim > 2 ? g : 0); ++k)
    for (int j = dim > 1 ? -g : 0; j < box.n[1] + (dim > 1 ? g : 0); ++j)
      for (int i = -g; i < box.n[0] + g; ++i) {
        int glob[3] = {b.lower[0] + i, b.lower[1] + j, b.lower[2] + k};
        bool filled = true;
        for (int d = 0; d < dim; ++d) {
          if (glob[d] >= 0 && glob[d] < cells[d]) continue;
          if (periodic && layout.blocks[d] > 1) glob[d] = (glob[d] + cells[d]) % cells[d];
          else filled = false;
        }
        for (int v = 0; v < nvars; ++v) {
          const double got = field[v][at(i, j, k)];
          const double want = filled ? value(v, glob[0], glob[1], glob[2]) : -1.0;
          if (got != want)
            fail("cell (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) + ") var " +
                 std::to_string(v) + ": " + std::to_string(got) + ", expected " + std::to_string(want));
        }
      }
  std::vector<double> sums{1.0, static_cast<double>(comm.rank())};
  comm.sum(sums);
  if (sums[0] != comm.size() || sums[1] != comm.size() * (comm.size() - 1) / 2.0) fail("sum");
  if (comm.max(comm.rank()) != comm.size() - 1 || comm.min(comm.rank()) != 0) fail("max/min");
  if (comm.any(comm.rank() == comm.size() - 1) != true || comm.any(false)) fail("any");
  if (comm.broadcast(comm.rank() == 0 ? "from rank 0" : "") != "from rank 0") fail("broadcast");
  const double all = comm.max(failures);
  if (comm.rank() == 0)
    std::printf("%d rank(s), layout %d x %d x %d, periodic %d: %s\n", comm.size(), layout.blocks[0], layout.blocks[1],
                layout.blocks[2], periodic, all == 0 ? "ghosts and reductions right" : "FAILED");
  return all == 0 ? 0 : 1;
}
