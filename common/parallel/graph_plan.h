// What one rank exchanges with its neighbours over a graph of ranks that share one global numbering of items (the
// nodes of an unstructured mesh): per neighbour rank (ascending), the items it sends (owned here, read there) and the
// items it receives (owned there, read here), each list in ascending global order. The sender's list for rank r is
// r's list from it, item for item. Plain data, no MPI: every rank computes the plans alike from the partition, and
// common/parallel/mpi/graph_comm.h moves the values.
#pragma once

#include <vector>

namespace cosim::parallel {

struct GraphPlan {
  std::vector<int> neighbours;
  std::vector<std::vector<int>> send, recv;
  long sent_items() const {
    long n = 0;
    for (const auto& s : send) n += static_cast<long>(s.size());
    return n;
  }
  long received_items() const {
    long n = 0;
    for (const auto& r : recv) n += static_cast<long>(r.size());
    return n;
  }
};

}  // namespace cosim::parallel
