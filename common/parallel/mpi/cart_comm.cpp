#include "common/parallel/mpi/cart_comm.h"

#include "common/parallel/mpi/passive_wait.h"

#include <hdf5.h>
#include <mpi.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <stdexcept>

namespace cosim::parallel {

namespace {

MPI_Comm& as_comm(void* p) { return *static_cast<MPI_Comm*>(p); }

}  // namespace

using detail::wait_passively;

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession(int* argc, char*** argv) {
  if (!launched_by_mpi()) return;
  // MPI-IO through ROMIO unless the user chose: OpenMPI 4.1's own component (OMPIO) wrote wrong values into the
  // collective snapshot files of blocks of unequal size (sod on 3 ranks: 12 runs of 12 wrong, ROMIO 12 of 12
  // right; docs/parallel.md). OpenMPI reads its MCA parameters from the environment when MPI starts.
  setenv("OMPI_MCA_io", "romio321", 0);
  int provided = 0;
  // The computation calls MPI from its master thread; the rank watchdog's thread (rank_watchdog.h) beside it.
  MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &local_size_);
  MPI_Comm_free(&node);
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}

void MpiSession::abort_all(int code) {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (initialised && !finalised) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

std::string MpiSession::describe() const {
  return active_ ? fmt::format("rank {} of {}", rank_, size_) : std::string();
}

CartComm::CartComm(const MpiSession& session, const Layout& layout, const std::array<bool, 3>& periodic,
                   const Index3& cells)
    : layout_(layout), cells_(cells), rank_(session.rank()) {
  if (layout.ranks() != session.size())
    throw std::invalid_argument(fmt::format("a layout of {} blocks for {} ranks", layout.ranks(), session.size()));
  block_ = block_of(layout, rank_, cells);
  if (!session.active()) return;
  comm_ = new MPI_Comm;
  int dims[3] = {layout.blocks[0], layout.blocks[1], layout.blocks[2]};
  int periods[3] = {periodic[0], periodic[1], periodic[2]};
  MPI_Cart_create(MPI_COMM_WORLD, 3, dims, periods, 0, &as_comm(comm_));  // rank order kept (block_of's)
  for (int d = 0; d < 3; ++d) {
    int lo = MPI_PROC_NULL, hi = MPI_PROC_NULL;
    if (layout.blocks[d] > 1) MPI_Cart_shift(as_comm(comm_), d, 1, &lo, &hi);
    neighbour_[d] = {lo == MPI_PROC_NULL ? -1 : lo, hi == MPI_PROC_NULL ? -1 : hi};
  }
}

CartComm::~CartComm() {
  if (!comm_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Comm_free(&as_comm(comm_));
  delete static_cast<MPI_Comm*>(comm_);
}

void CartComm::exchange_ghosts(double* const* vars, int nvars, const PaddedBox& box, int d) {
  if (neighbour_[d][0] < 0 && neighbour_[d][1] < 0) return;
  const auto t0 = std::chrono::steady_clock::now();
  const Index3 p = box.padded();
  const std::ptrdiff_t stride[3] = {1, p[0], static_cast<std::ptrdiff_t>(p[0]) * p[1]};
  // The range of the other axes: those before d over their ghost layers too, those after d their interior.
  int lo[3], hi[3];
  for (int e = 0; e < 3; ++e) {
    const int off = e < box.dim ? box.ng : 0;
    lo[e] = e < d && e < box.dim ? 0 : off;
    hi[e] = e < d && e < box.dim ? p[e] : off + box.n[e];
  }
  const std::size_t per_layer =
      static_cast<std::size_t>(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) / (hi[d] - lo[d]);
  const std::size_t count = per_layer * box.ng * nvars;
  // Visits the cells of layers [first, first + ng) along d (padded index), variable by variable, layer by layer.
  const auto visit = [&](int first, auto&& f) {
    std::size_t o = 0;
    for (int v = 0; v < nvars; ++v)
      for (int layer = first; layer < first + box.ng; ++layer) {
        int a[3] = {lo[0], lo[1], lo[2]}, b[3] = {hi[0], hi[1], hi[2]};
        a[d] = layer;
        b[d] = layer + 1;
        for (int k = a[2]; k < b[2]; ++k)
          for (int j = a[1]; j < b[1]; ++j) {
            double* row = vars[v] + k * stride[2] + j * stride[1];
            for (int i = a[0]; i < b[0]; ++i) f(row[i], o++);
          }
      }
  };
  const int ng = box.ng, n = box.n[d];
  MPI_Request req[4];
  int nreq = 0;
  // Tags: 2 d + side of the sender's face: what goes through a block's low face arrives at its neighbour's high side.
  for (int side = 0; side < 2; ++side) {
    if (neighbour_[d][side] < 0) continue;
    recv_[side].resize(count);
    MPI_Irecv(recv_[side].data(), static_cast<int>(count), MPI_DOUBLE, neighbour_[d][side], 2 * d + (1 - side),
              as_comm(comm_), &req[nreq++]);
  }
  for (int side = 0; side < 2; ++side) {
    if (neighbour_[d][side] < 0) continue;
    send_[side].resize(count);
    visit(side == 0 ? ng : n, [&](double& x, std::size_t o) { send_[side][o] = x; });  // the interior next to it
    MPI_Isend(send_[side].data(), static_cast<int>(count), MPI_DOUBLE, neighbour_[d][side], 2 * d + side,
              as_comm(comm_), &req[nreq++]);
    halo_bytes_ += 8.0 * static_cast<double>(count);
  }
  const auto w0 = std::chrono::steady_clock::now();
  wait_passively(nreq, req);
  halo_wait_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  for (int side = 0; side < 2; ++side) {
    if (neighbour_[d][side] < 0) continue;
    visit(side == 0 ? 0 : ng + n, [&](double& x, std::size_t o) { x = recv_[side][o]; });  // its ghost layers
  }
  halo_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double CartComm::max(double local) const { return comm_ ? detail::max_over(comm_, local) : local; }

double CartComm::min(double local) const { return -max(-local); }

void CartComm::sum(std::span<double> values) const {
  if (comm_) detail::sum_over(comm_, values);
}

bool CartComm::any(bool local) const { return max(local ? 1.0 : 0.0) > 0.0; }

SparsePlan CartComm::plan_sparse(std::span<const int> owner, std::span<const long> index) const {
  SparsePlan plan;
  plan.requests = owner.size();
  if (!comm_) {
    if (!owner.empty()) throw std::logic_error("a sparse exchange of cells on one block");
    return plan;
  }
  const int ranks = size();
  // The requests grouped by owner (stable: in request order within an owner).
  std::vector<std::size_t> order(owner.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return owner[a] < owner[b]; });
  std::vector<int> want(static_cast<std::size_t>(ranks), 0), give(static_cast<std::size_t>(ranks), 0);
  for (const int o : owner) {
    if (o < 0 || o >= ranks || o == rank_)
      throw std::logic_error(fmt::format("rank {}: a sparse request of a cell of rank {}", rank_, o));
    ++want[static_cast<std::size_t>(o)];
  }
  MPI_Request r;
  MPI_Ialltoall(want.data(), 1, MPI_INT, give.data(), 1, MPI_INT, as_comm(comm_), &r);
  wait_passively(1, &r);
  std::vector<int> sdispl(static_cast<std::size_t>(ranks), 0), rdispl(static_cast<std::size_t>(ranks), 0);
  for (int q = 1; q < ranks; ++q) {
    sdispl[q] = sdispl[q - 1] + want[q - 1];
    rdispl[q] = rdispl[q - 1] + give[q - 1];
  }
  std::vector<long> asked(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) asked[i] = index[order[i]];
  plan.send_index.resize(static_cast<std::size_t>(rdispl[ranks - 1] + give[ranks - 1]));
  MPI_Ialltoallv(asked.data(), want.data(), sdispl.data(), MPI_LONG, plan.send_index.data(), give.data(), rdispl.data(),
                 MPI_LONG, as_comm(comm_), &r);
  wait_passively(1, &r);
  for (int q = 0; q < ranks; ++q) {
    if (give[q] > 0) {
      plan.send_ranks.push_back(q);
      plan.send_counts.push_back(give[q]);
    }
    if (want[q] > 0) {
      plan.recv_ranks.push_back(q);
      plan.recv_counts.push_back(want[q]);
    }
  }
  plan.recv_slot = std::move(order);
  return plan;
}

void CartComm::exchange_sparse(const SparsePlan& plan, const double* send, double* recv, int width) {
  if (!comm_ || (plan.send_ranks.empty() && plan.recv_ranks.empty())) return;
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t w = static_cast<std::size_t>(width);
  sparse_recv_.resize(plan.requests * w);
  std::vector<MPI_Request> req(plan.send_ranks.size() + plan.recv_ranks.size());
  std::size_t n = 0, at = 0;
  for (std::size_t q = 0; q < plan.recv_ranks.size(); ++q) {
    const std::size_t c = static_cast<std::size_t>(plan.recv_counts[q]) * w;
    MPI_Irecv(sparse_recv_.data() + at, static_cast<int>(c), MPI_DOUBLE, plan.recv_ranks[q], 16, as_comm(comm_),
              &req[n++]);
    at += c;
  }
  at = 0;
  for (std::size_t q = 0; q < plan.send_ranks.size(); ++q) {
    const std::size_t c = static_cast<std::size_t>(plan.send_counts[q]) * w;
    MPI_Isend(send + at, static_cast<int>(c), MPI_DOUBLE, plan.send_ranks[q], 16, as_comm(comm_), &req[n++]);
    at += c;
    sparse_bytes_ += 8.0 * static_cast<double>(c);
  }
  wait_passively(static_cast<int>(n), req.data());
  for (std::size_t i = 0; i < plan.recv_slot.size(); ++i)
    std::copy(sparse_recv_.begin() + static_cast<std::ptrdiff_t>(i * w),
              sparse_recv_.begin() + static_cast<std::ptrdiff_t>((i + 1) * w), recv + plan.recv_slot[i] * w);
  halo_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::string> CartComm::gather_text(const std::string& local, bool to_all, TextTiming* timing) const {
  if (!comm_) return {local};
  const auto t0 = std::chrono::steady_clock::now();
  const int ranks = size();
  int n = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), displs(static_cast<std::size_t>(ranks), 0);
  MPI_Request r;
  if (to_all) MPI_Iallgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, as_comm(comm_), &r);
  else MPI_Igather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, as_comm(comm_), &r);
  wait_passively(1, &r);
  const auto t1 = std::chrono::steady_clock::now();
  const bool receives = to_all || rank_ == 0;
  for (int q = 1; q < ranks; ++q) displs[q] = displs[q - 1] + counts[q - 1];
  std::string all(receives ? static_cast<std::size_t>(displs[ranks - 1] + counts[ranks - 1]) : 0, '\0');
  if (to_all)
    MPI_Iallgatherv(local.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR, as_comm(comm_), &r);
  else
    MPI_Igatherv(local.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR, 0, as_comm(comm_), &r);
  wait_passively(1, &r);
  if (timing) {
    timing->wait_s += std::chrono::duration<double>(t1 - t0).count();
    timing->transfer_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    timing->bytes += static_cast<double>(all.size());
    ++timing->calls;
  }
  if (!receives) return {};
  std::vector<std::string> out;
  for (int q = 0; q < ranks; ++q) out.push_back(all.substr(static_cast<std::size_t>(displs[q]), counts[q]));
  return out;
}

std::string CartComm::broadcast(const std::string& from_root, TextTiming* timing) const {
  return comm_ ? detail::broadcast_over(comm_, from_root, timing) : from_root;
}

void CartComm::barrier() const {
  if (comm_) detail::barrier_over(comm_);
}

namespace {
class RankWrite final : public io::CollectiveWrite {
 public:
  RankWrite(const CartComm& comm, void* mpi_comm) : comm_(comm) {
    if (!mpi_comm) return;
    access_ = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_mpio(access_, as_comm(mpi_comm), MPI_INFO_NULL);
  }
  ~RankWrite() override {
    if (access_ > 0) H5Pclose(access_);
  }
  bool leader() const override { return comm_.rank() == 0; }
  std::int64_t file_access() override { return access_ > 0 ? access_ : 0; }
  void barrier() override { comm_.barrier(); }
  std::string from_leader(const std::string& bytes) override { return comm_.broadcast(bytes); }

 private:
  const CartComm& comm_;
  hid_t access_ = 0;
};
}  // namespace

std::unique_ptr<io::CollectiveWrite> CartComm::collective_write() const {
  return std::make_unique<RankWrite>(*this, comm_);
}

}  // namespace cosim::parallel
