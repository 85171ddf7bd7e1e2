#include "common/parallel/mpi/graph_comm.h"

#include <mpi.h>

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

#include "common/parallel/mpi/passive_wait.h"

namespace cosim::parallel {

namespace {
MPI_Comm& as_comm(void* p) { return *static_cast<MPI_Comm*>(p); }
using detail::wait_passively;
using Clock = std::chrono::steady_clock;
}  // namespace

GraphComm::GraphComm(const MpiSession& session) : rank_(session.rank()), size_(session.size()) {
  if (!session.active()) return;
  comm_ = new MPI_Comm;
  MPI_Comm_dup(MPI_COMM_WORLD, &as_comm(comm_));
}

GraphComm::~GraphComm() {
  if (!comm_) return;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Comm_free(&as_comm(comm_));
  delete static_cast<MPI_Comm*>(comm_);
}

void GraphComm::exchange(const GraphPlan& plan, std::span<double* const> arrays, int ncomp) {
  if (!comm_ || plan.neighbours.empty()) return;
  const auto t0 = Clock::now();
  const std::size_t k = plan.neighbours.size(), per_item = arrays.size() * static_cast<std::size_t>(ncomp);
  send_.resize(k);
  recv_.resize(k);
  std::vector<MPI_Request> req(2 * k);
  for (std::size_t i = 0; i < k; ++i) {
    recv_[i].resize(plan.recv[i].size() * per_item);
    MPI_Irecv(recv_[i].data(), static_cast<int>(recv_[i].size()), MPI_DOUBLE, plan.neighbours[i], 0, as_comm(comm_),
              &req[i]);
  }
  for (std::size_t i = 0; i < k; ++i) {
    std::vector<double>& buf = send_[i];
    buf.resize(plan.send[i].size() * per_item);
    std::size_t o = 0;
    for (double* a : arrays)
      for (int item : plan.send[i])
        for (int c = 0; c < ncomp; ++c) buf[o++] = a[static_cast<std::size_t>(item) * ncomp + c];
    MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, plan.neighbours[i], 0, as_comm(comm_), &req[k + i]);
    halo_bytes_ += 8.0 * static_cast<double>(buf.size());
  }
  const auto w0 = Clock::now();
  wait_passively(static_cast<int>(req.size()), req.data());
  halo_wait_seconds_ += std::chrono::duration<double>(Clock::now() - w0).count();
  for (std::size_t i = 0; i < k; ++i) {
    std::size_t o = 0;
    for (double* a : arrays)
      for (int item : plan.recv[i])
        for (int c = 0; c < ncomp; ++c) a[static_cast<std::size_t>(item) * ncomp + c] = recv_[i][o++];
  }
  halo_seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
}

void GraphComm::gather_owned(std::span<double> values, int ncomp, std::span<const int> owner, bool to_all) {
  if (!comm_) return;
  if (values.size() != owner.size() * static_cast<std::size_t>(ncomp))
    throw std::invalid_argument(
        fmt::format("gather_owned: {} values for {} items of {} components", values.size(), owner.size(), ncomp));
  std::vector<int> counts(size_, 0), displs(size_, 0);
  for (int o : owner) counts[o] += ncomp;
  for (int r = 1; r < size_; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<double> mine(static_cast<std::size_t>(counts[rank_]));
  for (std::size_t i = 0, at = 0; i < owner.size(); ++i)
    if (owner[i] == rank_)
      for (int c = 0; c < ncomp; ++c) mine[at++] = values[i * ncomp + c];
  const bool receives = to_all || rank_ == 0;
  std::vector<double> all(receives ? values.size() : 0);
  MPI_Request r;
  if (to_all)
    MPI_Iallgatherv(mine.data(), counts[rank_], MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                    as_comm(comm_), &r);
  else
    MPI_Igatherv(mine.data(), counts[rank_], MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
                 as_comm(comm_), &r);
  wait_passively(1, &r);
  if (!receives) return;
  std::vector<int> at(displs);  // each rank's items in ascending order
  for (std::size_t i = 0; i < owner.size(); ++i) {
    const int o = owner[i];
    for (int c = 0; c < ncomp; ++c) {
      const double v = all[static_cast<std::size_t>(at[o]++)];
      if (o != rank_) values[i * ncomp + c] = v;
    }
  }
}

double GraphComm::max(double local) const { return comm_ ? detail::max_over(comm_, local) : local; }

double GraphComm::min(double local) const { return -max(-local); }

void GraphComm::sum(std::span<double> values) const {
  if (comm_) detail::sum_over(comm_, values);
}

bool GraphComm::any(bool local) const { return max(local ? 1.0 : 0.0) > 0.0; }

std::string GraphComm::broadcast(const std::string& from_root) const {
  return comm_ ? detail::broadcast_over(comm_, from_root) : from_root;
}

void GraphComm::barrier() const {
  if (comm_) detail::barrier_over(comm_);
}

}  // namespace cosim::parallel
