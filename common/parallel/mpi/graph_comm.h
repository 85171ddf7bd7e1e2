// Exchanges between ranks that share one global numbering of items (the nodes or the elements of an unstructured
// mesh), each item owned by one rank: the halo exchange over the graph of neighbouring ranks, the gather of every
// rank's owned items, and the reductions. The plans are plain data that every rank computes alike from the
// partition (no MPI there); this class only moves the values.
//
// Like CartComm (cart_comm.h): without a launcher every call is a local no-op, and every wait is passive.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "common/parallel/graph_plan.h"
#include "common/parallel/mpi/cart_comm.h"

namespace cosim::parallel {

class GraphComm {
 public:
  explicit GraphComm(const MpiSession& session);
  ~GraphComm();
  GraphComm(const GraphComm&) = delete;
  GraphComm& operator=(const GraphComm&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // For each array (ncomp doubles per item, item-major): the plan's received items get their owners' values.
  // Non-blocking sends and receives of one message per neighbour, waited for passively.
  void exchange(const GraphPlan& plan, std::span<double* const> arrays, int ncomp);
  // values holds ncomp doubles per item; owner[i] is the rank that owns item i. The entries owned by other ranks
  // get their owners' values: on rank 0 only (to_all false) or on every rank.
  void gather_owned(std::span<double> values, int ncomp, std::span<const int> owner, bool to_all);

  double max(double local) const;
  double min(double local) const;
  void sum(std::span<double> values) const;  // in place, every rank gets the sums (the order is MPI's)
  bool any(bool local) const;
  std::string broadcast(const std::string& from_root) const;  // rank 0's text on every rank (every rank calls it)
  void barrier() const;

  double halo_bytes() const { return halo_bytes_; }  // sent by exchange() so far
  double halo_seconds() const { return halo_seconds_; }
  double halo_wait_seconds() const { return halo_wait_seconds_; }

 private:
  int rank_ = 0, size_ = 1;
  void* comm_ = nullptr;  // MPI_Comm (a duplicate of the world's), null without MPI
  std::vector<std::vector<double>> send_, recv_;
  double halo_bytes_ = 0, halo_seconds_ = 0, halo_wait_seconds_ = 0;
};

}  // namespace cosim::parallel
