// The coupler's heartbeat endpoint, derived from its data endpoint, and the endpoint a solver connects to.
#include <gtest/gtest.h>

#include "common/coupling/endpoints.h"

using namespace cosim::coupling;

TEST(Endpoints, TheHeartbeatSocketSitsBesideTheDataSocket) {
  EXPECT_EQ(heartbeat_bind_endpoint("ipc:///run/dir/coupler.sock"), "ipc:///run/dir/coupler-hb.sock");
  EXPECT_EQ(heartbeat_bind_endpoint("ipc:///tmp/piston"), "ipc:///tmp/piston-hb");
  EXPECT_EQ(heartbeat_bind_endpoint("inproc://coupler"), "inproc://coupler-hb");
  EXPECT_EQ(heartbeat_bind_endpoint("tcp://127.0.0.1:5555"), "tcp://127.0.0.1:*");
  EXPECT_EQ(heartbeat_bind_endpoint("tcp://*:5555"), "tcp://*:*");
  EXPECT_THROW(heartbeat_bind_endpoint("tcp://127.0.0.1"), std::invalid_argument);
}

TEST(Endpoints, ASolverReachesTheHeartbeatSocketOnTheHostItReachedTheCouplerAt) {
  // A coupler in a container binds tcp://*:5555 and tells tcp://0.0.0.0:41234; its solvers reached it as
  // tcp://coupler:5555.
  EXPECT_EQ(heartbeat_connect_endpoint("tcp://0.0.0.0:41234", "tcp://coupler:5555"), "tcp://coupler:41234");
  EXPECT_EQ(heartbeat_connect_endpoint("tcp://[::]:41234", "tcp://10.0.0.7:5555"), "tcp://10.0.0.7:41234");
  EXPECT_EQ(heartbeat_connect_endpoint("tcp://127.0.0.1:41234", "tcp://localhost:5555"), "tcp://127.0.0.1:41234");
  EXPECT_EQ(heartbeat_connect_endpoint("ipc:///d/coupler-hb.sock", "ipc:///d/coupler.sock"),
            "ipc:///d/coupler-hb.sock");
  EXPECT_EQ(heartbeat_connect_endpoint("", "ipc:///d/coupler.sock"), "ipc:///d/coupler.sock");
}
