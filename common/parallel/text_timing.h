// Where the time of a collective of texts went on one rank (a broadcast of rank 0's bytes, an all-gather of every
// rank's): the first stage (the lengths, which every rank must have joined before it ends anywhere) waits for the
// rank that arrives last, rank 0 with its text among them; the second moves the bytes. Accumulated over the calls
// given the same record.
#pragma once

namespace cosim::parallel {

struct TextTiming {
  double wait_s = 0;      // in the lengths' stage: waiting for the other ranks
  double transfer_s = 0;  // in the bytes' stage
  double bytes = 0;       // the bytes this rank received (a broadcast: the text; an all-gather: every rank's)
  long calls = 0;
};

}  // namespace cosim::parallel
