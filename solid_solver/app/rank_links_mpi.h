// RankLinks (core/rank_links.h) over MPI: the graph exchange of common/parallel/mpi/graph_comm.h.
#pragma once

#include "common/parallel/mpi/graph_comm.h"
#include "solid_solver/core/rank_links.h"

namespace cosim::solid {

class MpiRankLinks final : public RankLinks {
 public:
  MpiRankLinks(parallel::GraphComm& comm, RankPart part) : comm_(comm), part_(std::move(part)) {}
  const RankPart& part() const override { return part_; }
  void exchange_ghost_nodes(std::span<double* const> arrays, int ncomp) override {
    comm_.exchange(part_.ghosts, arrays, ncomp);
  }
  double min_over_ranks(double local) override { return comm_.min(local); }
  void sum_over_ranks(std::span<double> values) override { comm_.sum(values); }
  void gather_owned(std::span<double> values, int ncomp, std::span<const int> owner, bool to_all) override {
    comm_.gather_owned(values, ncomp, owner, to_all);
  }

 private:
  parallel::GraphComm& comm_;
  RankPart part_;
};

}  // namespace cosim::solid
