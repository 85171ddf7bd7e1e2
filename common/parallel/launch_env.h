// What the parallel launcher (mpirun, srun) tells a process through its environment before MPI starts: how many
// ranks the run has and how many share this node. For checks made while a scene is read (the memory a rank's block
// needs), without MPI.
#pragma once

namespace cosim::parallel {

struct LaunchShape {
  int ranks = 1;          // in the whole run
  int ranks_on_node = 1;  // on this node
};

// From OpenMPI's (OMPI_COMM_WORLD_SIZE, _LOCAL_SIZE) or SLURM's (SLURM_NTASKS, SLURM_NTASKS_PER_NODE) variables;
// one rank on its node when neither is set.
LaunchShape launch_shape();

}  // namespace cosim::parallel
