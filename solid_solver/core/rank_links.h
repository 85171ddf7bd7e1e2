// The seam between the solid's time step and the other ranks of a run (app/rank_links_mpi.h implements it over
// MPI): the step calls these at fixed points and stays decomposition-blind otherwise. See mesh/rank_part.h for what
// a rank computes.
#pragma once

#include <span>

#include "solid_solver/mesh/rank_part.h"

namespace cosim::solid {

class RankLinks {
 public:
  virtual ~RankLinks() = default;
  virtual const RankPart& part() const = 0;
  // The ghost nodes' values from their owners (ncomp values per node in each array).
  virtual void exchange_ghost_nodes(std::span<double* const> arrays, int ncomp) = 0;
  virtual double min_over_ranks(double local) = 0;
  virtual void sum_over_ranks(std::span<double> values) = 0;  // in place, every rank gets the sums
  // The entries owned elsewhere (owner per item, ncomp values per item) from their owners: on rank 0 or everywhere.
  virtual void gather_owned(std::span<double> values, int ncomp, std::span<const int> owner, bool to_all) = 0;
};

}  // namespace cosim::solid
