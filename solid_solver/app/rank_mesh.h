// The Gmsh mesh of a solid on several ranks, read once: rank 0 alone opens and parses the file, then broadcasts
// first its status (the mesh, or the error naming file and line) and then the parsed mesh, packed (mesh_pack.h), to
// every rank. A read error thus ends every rank alike, with rank 0's message; the other ranks never open the file.
// (docs/parallel.md, "The solid on many ranks").
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "common/parallel/mpi/graph_comm.h"
#include "solid_solver/core/scene.h"

namespace cosim::solid {

// What the loader did on this rank, for summary.json's "parallel" record.
struct MeshBroadcast {
  bool used = false;             // a Gmsh mesh was loaded through it
  bool opened_file = false;      // this rank opened and parsed the file (rank 0 only)
  std::string file;              // rank 0's path
  double bytes = 0;              // the packed mesh broadcast
  double read_seconds = 0;       // rank 0: opening and parsing the file
  double pack_seconds = 0;       // rank 0: packing the mesh
  double broadcast_seconds = 0;  // rank 0: its broadcast, until the last byte had left
  double unpack_seconds = 0;     // the other ranks: unpacking it
};

// The scene's mesh loader on every rank of `comm` (every rank calls it together, as every rank reads the same scene).
// Throws MeshError with rank 0's message on every rank when rank 0 could not read the file.
MeshLoader mesh_read_on_rank_zero(const parallel::GraphComm& comm, MeshBroadcast& record);

// {"read_by_ranks": the ranks that opened the file ([0]), "file", "bytes", "read_seconds", "pack_seconds",
// "broadcast_seconds" (rank 0's) and "unpack_seconds" (the slowest rank's)}; every rank calls it.
nlohmann::json mesh_broadcast_record(const parallel::GraphComm& comm, const MeshBroadcast& record);

}  // namespace cosim::solid
