#pragma once
// Snapshot output: one HDF5 file per snapshot plus an XDMF 3 index that ParaView opens as a time series.
//
// Files (the directory must exist):
//   <dir>/<basename>_<NNNNNN>.h5   one snapshot; NNNNNN = 0-based index in the series (not the step)
//   <dir>/<basename>.xmf           XDMF 3 temporal collection of every complete snapshot
// Each .h5 is written as <name>.tmp, closed, fsynced and renamed; only then is the .xmf rewritten (again via a
// .tmp file and a rename). A reader therefore never sees a partial file, and the .xmf only references complete
// snapshots. A new SnapshotSeries starts at index 0 and overwrites an earlier series of the same name.
//
// HDF5 layout of one snapshot ("cosim-snapshot-1"):
//   /                   attributes: time (double), step (int64), format = "cosim-snapshot-1" (string)
//   /grid               attributes: type = "uniform" | "unstructured" (string), dim (int64)
//     uniform grid:     attributes cells (int64[3]), origin (double[3]), spacing (double[3]), all in x, y, z
//                       order; unused dimensions are stored as cells 1, origin 0, spacing 1
//     unstructured:     attribute cell_type = "quadrilateral" | "hexahedron" | "line" (string)
//                       dataset coordinates  double [num_nodes, 3]   (z = 0 in 2D)
//                       dataset connectivity int64  [num_cells, nodes_per_cell]   0-based node ids, VTK order
//   /cell/<name>        one dataset per cell field (group always present, may be empty)
//   /node/<name>        one dataset per node field (group always present, may be empty)
// Field datasets are double, row-major (slowest dimension first, x / i fastest):
//   uniform cell field: [nx] in 1D, [ny, nx] in 2D, [nz, ny, nx] in 3D
//   uniform node field: the same with nx+1, ny+1, nz+1
//   unstructured:       [num_cells] or [num_nodes]
//   ncomp > 1 adds a trailing component dimension. Vectors (ncomp 2 or 3) are always stored with 3 components
//   (a 2-component vector gets z = 0) so ParaView shows them as vectors; ncomp 6 is a symmetric tensor
//   (xx, xy, xz, yy, yz, zz), ncomp 9 a full tensor. Other component counts are rejected.
//
// XDMF: <Xdmf Version="3.0"><Domain><Grid GridType="Collection" CollectionType="Temporal">, one Uniform <Grid>
// per snapshot with <Time Value=.../>. Uniform grids are 3DCoRectMesh + ORIGIN_DXDYDZ (z y x order); 1D and
// 2D grids have node dimensions "1 1 nx+1" / "1 ny+1 nx+1" so that node fields match. Unstructured grids are
// Quadrilateral / Hexahedron topology with XYZ geometry. Data items point at "<basename>_NNNNNN.h5:/cell/..."
// (relative file names). Open the .xmf in ParaView with "Xdmf3 Reader S" (or T); the legacy "XDMF Reader"
// (Xdmf2) cannot read the fields of 1D/2D uniform grids. Checked with ParaView 5.11 (pvpython).

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cosim::io {

enum class Center { Cell, Node };

// A field to write. data: ncomp values per entity, interleaved (x,y,z,x,y,z,...) when ncomp > 1.
// ncomp must be 1, 2, 3, 6 or 9. Names must be unique per center and contain no '/', ':' or control characters.
struct FieldView {
  std::string name;
  const double* data;
  int ncomp;
  Center center;
};

// Uniform Cartesian grid of 1, 2 or 3 dimensions (x, y, z order); entries beyond `dim` are ignored.
// Cell data in row-major order with i fastest (x), then j, then k; node data likewise.
struct UniformGrid {
  int dim;
  std::array<int, 3> cells;
  std::array<double, 3> origin;
  std::array<double, 3> spacing;
};

// Unstructured grid of quads (dim 2, nodes_per_cell 4) or hexahedra (dim 3, nodes_per_cell 8), VTK node order;
// or a surface: segments (dim 2, nodes_per_cell 2; XDMF Polyline) or quads (dim 3, nodes_per_cell 4).
// coords: `dim` values per node, interleaved; they may change between snapshots (Lagrangian mesh).
// connectivity: nodes_per_cell 0-based node ids per cell.
struct UnstructuredGrid {
  int dim;
  const double* coords;
  std::int64_t num_nodes;
  const std::int64_t* connectivity;
  std::int64_t num_cells;
  int nodes_per_cell;
};

// The processes that write one snapshot file together (each its part of a uniform grid: MPI ranks, implemented in
// common/parallel/mpi). Every process keeps its SnapshotSeries; the leader prepares the directory and publishes the
// file and the index.
class CollectiveWrite {
 public:
  virtual ~CollectiveWrite() = default;
  virtual bool leader() const = 0;
  virtual std::int64_t file_access() = 0;  // the shared file's HDF5 access property list (kept by the implementation)
  virtual void barrier() = 0;
  // The leader's bytes on every process (what a collective file needs alike everywhere: names, shapes, values).
  virtual std::string from_leader(const std::string& bytes) = 0;
};

// A process's part of a uniform grid: cells [lower, upper) along x, y, z.
struct GridPart {
  std::array<int, 3> lower{0, 0, 0}, upper{1, 1, 1};
};

class SnapshotSeries {
 public:
  // dir must exist when write() is called (std::runtime_error naming the path otherwise). basename must be
  // non-empty without '/', ':' or control characters (std::invalid_argument otherwise).
  SnapshotSeries(std::filesystem::path dir, std::string basename);

  // Each call writes one new HDF5 snapshot and rewrites the .xmf; returns the path of the .h5. The first
  // call first removes the snapshots <basename>_NNNNNN.h5 an earlier run left in the directory, so that a
  // shorter run never leaves a longer one's files behind (the .xmf only ever lists this run's).
  // Throws std::invalid_argument for bad grids/fields and std::runtime_error (naming the file) for I/O errors;
  // a failed write leaves the series (files and count) as it was.
  std::filesystem::path write(double time, std::int64_t step, const UniformGrid& g,
                              const std::vector<FieldView>& fields);
  std::filesystem::path write(double time, std::int64_t step, const UnstructuredGrid& g,
                              const std::vector<FieldView>& fields);
  // The same snapshot as write(time, step, g, fields) of the whole grid, written by several processes together:
  // `fields` hold this process's `part` of the grid (i fastest), every process calls it with the same time, step,
  // grid and field names. The file is written under a temporary name and published by the leader, as write().
  std::filesystem::path write_part(double time, std::int64_t step, const UniformGrid& g, const GridPart& part,
                                   const std::vector<FieldView>& fields, CollectiveWrite& together);

  std::size_t count() const { return grids_.size(); }
  // The XDMF entries of the snapshots written so far, for a checkpoint; resume() takes them back: the series then
  // continues after them (the files of later snapshots, written by the run that stopped, are removed and the .xmf
  // lists the kept ones). resume() throws std::runtime_error naming a kept snapshot that is missing.
  const std::vector<std::string>& entries() const { return grids_; }
  void resume(std::vector<std::string> entries);
  // What resume() records, without touching a file: for the processes that write a series with its leader
  // (write_part), which resumes the files.
  void follow(std::vector<std::string> entries) {
    grids_ = std::move(entries);
    resumed_ = true;
  }
  std::filesystem::path xdmf_path() const;

 private:
  std::string file_name(std::size_t index) const;
  // Throws if the directory is missing; before the first snapshot, removes an earlier run's series there.
  void prepare_directory() const;
  std::filesystem::path publish(const std::string& file_name, std::string grid_xml);

  std::filesystem::path dir_;
  std::string basename_;
  std::vector<std::string> grids_;  // XDMF <Grid> element of each snapshot written so far
  bool resumed_ = false;            // continues a checkpointed series: nothing of it is removed
};

// Removes the regular files <prefix>NNNNNN<suffix> (exactly six digits) with NNNNNN >= `from` from dir: what an
// earlier run of the same output left there (or, from a checkpoint's count on, what a stopped run wrote after it).
// Returns how many were removed; errors are ignored (best effort).
std::size_t remove_numbered_files(const std::filesystem::path& dir, std::string_view prefix, std::string_view suffix,
                                  std::size_t from = 0);

}  // namespace cosim::io
