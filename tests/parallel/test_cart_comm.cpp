// The MPI module on 1 to 4 ranks (tests/programs/cart_comm_check under mpirun): the ghost layers of every block equal
// the cells they stand for, on open and periodic axes, in 1D, 2D and 3D; the reductions and the broadcast.
#include <gtest/gtest.h>

#include "tests/parallel/rank_runs.h"

TEST(CartComm, GhostLayersAndReductionsOnOneToFourRanks) {
  const std::string program = std::string(COSIM_BINARY_DIR) + "/bin/cart_comm_check";
  const auto log = cosim::test::scratch_path("cart_comm_check.log");
  for (const char* mesh : {"1 30 1 1", "2 17 12 1", "3 9 8 7"})
    for (int periodic = 0; periodic < 2; ++periodic)
      for (int ranks = 1; ranks <= 4; ++ranks) {
        const std::string cmd = "timeout -s KILL 60 " + cosim::test::launcher(ranks) + program + " " + mesh + " " +
                                std::to_string(periodic) + " > " + log.string() + " 2>&1";
        const int status = std::system(cmd.c_str());
        const std::string out = cosim::test::read_text(log);
        EXPECT_EQ(WEXITSTATUS(status), 0) << mesh << ", " << ranks << " ranks, periodic " << periodic << ":\n" << out;
        std::printf("[ measured ] %s", out.c_str());
      }
}
