// The one place that talks MPI: the process's MPI environment, the Cartesian communicator of a block layout, the
// ghost-layer exchange of padded block arrays, the reductions and the gathers and scatters of block data. Everything
// else is decomposition-blind and sees this through plain functions.
//
// MPI is initialised only when a launcher started the process (mpirun, srun: launched_by_mpi()); a process started
// without one is a layout of one block, and every call here is then a local no-op or copy. The same code path runs
// in both cases.
//
// Waiting is passive: every wait (point-to-point, reductions, gathers) tests its non-blocking requests and sleeps
// between tests once it has waited a few microseconds, so ranks oversubscribed on a machine's cores do not take the
// cores from the ranks they wait for (docs/parallel.md, "Waiting").
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/io/snapshot_writer.h"
#include "common/parallel/decomposition.h"
#include "common/parallel/text_timing.h"

namespace cosim::parallel {

// Whether a parallel launcher started this process (its environment names a world size).
bool launched_by_mpi();

// MPI for this process's lifetime (initialised when launched_by_mpi(), finalised by the destructor).
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  int ranks_on_this_node() const { return local_size_; }
  // Ends every rank of the run with `code` (MPI_Abort; a plain exit without MPI). Never returns.
  [[noreturn]] static void abort_all(int code);
  // A rank's one-line name for messages: "rank 2 of 4" ("" for one rank without a launcher).
  std::string describe() const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1, local_size_ = 1;
};

// A padded block array: n cells along each axis (1 beyond dim), ng ghost layers on each side of the active axes;
// cells i fastest, as the fluid grid stores them.
struct PaddedBox {
  int dim = 1;
  Index3 n{1, 1, 1};
  int ng = 2;
  Index3 padded() const {
    Index3 p{};
    for (int d = 0; d < 3; ++d) p[d] = d < dim ? n[d] + 2 * ng : 1;
    return p;
  }
};

// A sparse exchange of single cells between any blocks (the cells the embedded bodies' records read beyond the ghost
// layers), set up once per set of cells by CartComm::plan_sparse and used many times by exchange_sparse.
struct SparsePlan {
  std::vector<int> send_ranks, send_counts;  // the ranks this one sends to, and how many cells each
  std::vector<int> recv_ranks, recv_counts;  // the ranks it receives from (the owners of its requests)
  std::vector<long> send_index;              // the cells to send (indices at this rank), grouped by send_ranks
  std::vector<std::size_t> recv_slot;        // where each received cell goes in the request list, in arrival order
  std::size_t requests = 0;
};

class CartComm {
 public:
  // The layout's blocks over the session's ranks (layout.ranks() must equal session.size()); periodic[d]: the blocks
  // at the two ends of axis d are neighbours.
  CartComm(const MpiSession& session, const Layout& layout, const std::array<bool, 3>& periodic, const Index3& cells);
  ~CartComm();
  CartComm(const CartComm&) = delete;
  CartComm& operator=(const CartComm&) = delete;

  int rank() const { return rank_; }
  int size() const { return layout_.ranks(); }
  const Layout& layout() const { return layout_; }
  const Block& block() const { return block_; }
  const Index3& cells() const { return cells_; }
  // The rank of the neighbouring block on `side` (0 low, 1 high) of axis d, or -1 where there is none.
  int neighbour(int d, int side) const { return neighbour_[d][side]; }

  // Fills the ghost layers along axis d of `nvars` arrays of `box` on the sides with a neighbour from its cells next
  // to the shared face; the axes before d are swept over their ghost layers, so edges and corners come along.
  // Non-blocking sends and receives, waited for passively. Bytes moved so far: halo_bytes().
  void exchange_ghosts(double* const* vars, int nvars, const PaddedBox& box, int d);
  double halo_bytes() const { return halo_bytes_; }
  double halo_seconds() const { return halo_seconds_; }  // spent in exchange_ghosts, packing and waiting included
  double halo_wait_seconds() const { return halo_wait_seconds_; }  // of which waiting for the messages

  double max(double local) const;
  double min(double local) const;
  void sum(std::span<double> values) const;  // in place, every rank gets the sums (rank order of the reduction)
  bool any(bool local) const;

  // Sets up a sparse exchange: this rank needs the cells index[i] of rank owner[i] (each another rank). Collective
  // (every rank calls it, with or without requests). The plan's send_index tells which of its cells this rank must
  // pack, in order, for exchange_sparse.
  SparsePlan plan_sparse(std::span<const int> owner, std::span<const long> index) const;
  // Sends `width` values per cell of plan.send_index (packed in that order in `send`) and receives `width` values per
  // requested cell into `recv`, in the order of the requests. Point to point with the plan's ranks only; the bytes
  // count into sparse_bytes().
  void exchange_sparse(const SparsePlan& plan, const double* send, double* recv, int width);
  double sparse_bytes() const { return sparse_bytes_; }
  // Every rank's text on rank 0 (to_all: on every rank), in rank order (empty elsewhere). `timing`, when given, gains
  // the wait in the lengths' stage and the transfer of the texts.
  std::vector<std::string> gather_text(const std::string& local, bool to_all = false,
                                       TextTiming* timing = nullptr) const;
  // Rank 0's bytes to every rank (`timing` as above).
  std::string broadcast(const std::string& from_root, TextTiming* timing = nullptr) const;
  void barrier() const;
  // The ranks writing one snapshot file together (MPI-IO through parallel HDF5), rank 0 leading; without MPI, this
  // process alone.
  std::unique_ptr<io::CollectiveWrite> collective_write() const;

 private:
  Layout layout_;
  Block block_;
  Index3 cells_;
  int rank_ = 0;
  std::array<std::array<int, 2>, 3> neighbour_{{{-1, -1}, {-1, -1}, {-1, -1}}};
  void* comm_ = nullptr;  // MPI_Comm of the Cartesian topology (MPI stays out of this header)
  std::vector<double> send_[2], recv_[2];
  double halo_bytes_ = 0, halo_seconds_ = 0, halo_wait_seconds_ = 0, sparse_bytes_ = 0;
  std::vector<double> sparse_recv_;
};

}  // namespace cosim::parallel
