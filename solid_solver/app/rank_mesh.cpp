#include "solid_solver/app/rank_mesh.h"

#include <fmt/format.h>

#include <chrono>

#include "solid_solver/mesh/gmsh_reader.h"
#include "solid_solver/mesh/mesh_pack.h"

namespace cosim::solid {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
// The status broadcast first: "ok", or the error after this mark.
constexpr char kFailed = 'E';
}  // namespace

MeshLoader mesh_read_on_rank_zero(const parallel::GraphComm& comm, MeshBroadcast& record) {
  return [&comm, &record](const std::string& path) {
    record.used = true;
    Mesh mesh;
    std::string status = "ok";
    if (comm.rank() == 0) {
      record.file = path;
      record.opened_file = true;
      const auto t0 = Clock::now();
      try {
        mesh = read_gmsh(path);
      } catch (const MeshError& e) {
        status = std::string(1, kFailed) + e.what();
      } catch (const std::exception& e) {  // out of memory: every rank stops alike
        status = std::string(1, kFailed) + fmt::format("{}: cannot read the Gmsh mesh file: {}", path, e.what());
      }
      record.read_seconds = since(t0);
    }
    // Every rank takes part in both broadcasts whatever happened on rank 0: no rank waits for one that stopped.
    status = comm.broadcast(status);
    if (!status.empty() && status[0] == kFailed) throw MeshError(status.substr(1));
    auto t0 = Clock::now();
    std::string packed;
    if (comm.rank() == 0) {
      packed = pack_mesh(mesh);
      record.pack_seconds = since(t0);
      t0 = Clock::now();
    }
    packed = comm.broadcast(packed);
    if (comm.rank() == 0) record.broadcast_seconds = since(t0);
    record.bytes = static_cast<double>(packed.size());
    if (comm.rank() != 0) {
      t0 = Clock::now();
      mesh = unpack_mesh(packed, "the mesh broadcast from rank 0");
      record.unpack_seconds = since(t0);
    }
    return mesh;
  };
}

nlohmann::json mesh_broadcast_record(const parallel::GraphComm& comm, const MeshBroadcast& record) {
  std::vector<double> opened(static_cast<std::size_t>(comm.size()), 0.0);
  opened[static_cast<std::size_t>(comm.rank())] = record.opened_file ? 1.0 : 0.0;
  comm.sum(opened);
  std::vector<int> readers;
  for (std::size_t r = 0; r < opened.size(); ++r)
    if (opened[r] > 0) readers.push_back(static_cast<int>(r));
  return {{"read_by_ranks", readers},
          {"file", comm.broadcast(record.file)},
          {"bytes", record.bytes},
          {"read_seconds", comm.max(record.read_seconds)},
          {"pack_seconds", comm.max(record.pack_seconds)},
          {"broadcast_seconds", comm.max(record.broadcast_seconds)},
          {"unpack_seconds", comm.max(record.unpack_seconds)}};
}

}  // namespace cosim::solid
