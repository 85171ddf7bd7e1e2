#include "coupler/coupler_config.h"

#include "common/config/config.h"
#include "common/config/output_times.h"

namespace cosim::coupler {

CouplerConfig read_coupler_config(const std::string& file, const std::vector<std::string>& overrides) {
  using namespace cosim::config;
  Node root = load_file(file, overrides);
  Node n = root.child("coupling");
  CouplerConfig c;
  const std::string mode =
      n.get<std::string>("mode", "robin", one_of({"robin", "impedance", "characteristic", "standard"}));
  c.mode = mode == "standard"         ? coupling::Mode::Standard
           : mode == "characteristic" ? coupling::Mode::Characteristic
           : mode == "robin"          ? coupling::Mode::Robin
                                      : coupling::Mode::Impedance;
  c.scheme = n.get<std::string>("scheme", "pipelined", one_of({"pipelined", "sequential"})) == "sequential"
                 ? coupling::Scheme::Sequential
                 : coupling::Scheme::Pipelined;
  Node t = n.child("time");
  c.t_end = t.require<double>("end", positive());
  c.max_cycles = t.get<int>("max_cycles", 1000000000, int_at_least(1));
  c.dt_max = t.get<double>("dt_max", 0.0, non_negative());
  t.finish();
  auto out = n.optional_child("output");
  c.output_times = read_output_times(out ? &*out : nullptr, c.t_end);
  if (out) out->finish();
  c.timeout = n.get<double>("timeout", 3.0, positive());
  c.heartbeat_interval = n.get<double>("heartbeat_interval", c.timeout / 10.0, in_open_closed(0.0, c.timeout / 2.0));
  c.connect_timeout = n.get<double>("connect_timeout", 30.0, positive());
  c.step_timeout = n.get<double>("step_timeout", 0.0, non_negative());
  c.max_message_mb = n.get<double>("max_message_mb", 256.0, in_range(0.01, 65536.0));
  c.pressure_predictor = n.get<std::string>("predictor", "linear", one_of({"linear", "none"})) == "linear";
  auto ck = n.optional_child("checkpoint");
  c.checkpoint = checkpoint::read_checkpoint_policy(ck ? &*ck : nullptr);
  n.finish();
  return c;
}

}  // namespace cosim::coupler
