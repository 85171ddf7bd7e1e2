// OpenMP threads chosen by the work, and passive waiting (docs/design.md, "Threads"). Measured on 2 cores: a 1D Sod of
// 1000 cells took 0.1-0.2 s with one thread but 1.3-28 s with two spinning threads on a busy machine (1D has one
// row of cells: nothing to share); a 2D run of 32^2 cells already gains from two threads on an idle machine.
#pragma once

namespace cosim::app {

// Re-executes the program once with OMP_WAIT_POLICY=PASSIVE when the user set no policy (the OpenMP runtime reads
// it only when it starts): waiting threads sleep instead of spinning on cores other processes need. Returns only
// when no re-execution took place (a policy was set, or exec failed).
void prefer_passive_waiting(char** argv);

// The threads for `work` units that parallel loops share (rows of cells, elements) when the user chose none: one
// per `min_work_per_thread` units, at least 1, at most the threads the runtime offered at start-up.
int threads_for(long work, long min_work_per_thread);

}  // namespace cosim::app
