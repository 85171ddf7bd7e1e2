// fluid_solver SCENE.yaml --out DIR [--set key.path=value ...] [--quiet] [--threads N]
#include "common/app/run_options.h"
#include "common/app/threads.h"
#include "fluid_solver/app/runner.h"

int main(int argc, char** argv) {
  cosim::app::prefer_passive_waiting(argv);
  cosim::parallel::MpiSession mpi(&argc, &argv);  // MPI when a launcher started this process
  cosim::app::RunOptions opt;
  if (auto rc = cosim::app::parse_command_line(
          argc, argv, "fluid_solver", "multiphase DEM Godunov solver on a Cartesian mesh (standalone run)",
          "  fluid_solver configs/sod.yaml --out runs/sod             snapshots and summary.json in runs/sod\n"
          "  fluid_solver configs/sod.yaml --out runs/sod_800 --set 'fluid.mesh.cells=[800]' --threads 1\n"
          "  cosim run configs/sod.yaml                               the same run through the launcher\n"
          "  mpirun -np 4 fluid_solver configs/particle_blast_2d.yaml --out runs/pb   the mesh split over 4 ranks",
          opt))
    return *rc;
  return cosim::fluid::run_fluid(opt, mpi);
}
