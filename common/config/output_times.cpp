#include "common/config/output_times.h"

#include <algorithm>

namespace cosim::config {

std::vector<double> read_output_times(Node* out, double t_end) {
  std::vector<double> times;
  if (out) {
    const double interval = out->get<double>("interval", 0.0, non_negative());
    out->skip("times");
    if (out->has("times")) times = out->get_vector("times", 1, 100000, std::nullopt, positive());
    if (interval > 0)
      for (int i = 1; i * interval < t_end * (1 - 1e-12); ++i) times.push_back(i * interval);
  }
  times.push_back(t_end);
  std::sort(times.begin(), times.end());
  times.erase(std::remove_if(times.begin(), times.end(), [&](double t) { return t > t_end; }), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace cosim::config
