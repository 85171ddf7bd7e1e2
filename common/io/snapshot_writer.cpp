#include "common/io/snapshot_writer.h"

#include <cmath>
#include <span>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/io/atomic_file.h"
#include "common/io/hdf5_file.h"

namespace cosim::io {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kFormat = "cosim-snapshot-1";

[[noreturn]] void reject(const std::string& message) { throw std::invalid_argument("snapshot: " + message); }

// ---------------------------------------------------------------- names and XML text

bool is_valid_name(std::string_view name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f || c == '/' || c == ':') return false;
  }
  return true;
}

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// <DataItem> pointing at `dataset` in `h5_name` (a file name relative to the .xmf).
std::string data_item(const Hdf5Shape& shape, std::string_view number_type, const std::string& h5_name,
                      const std::string& dataset) {
  return fmt::format("<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"8\" Format=\"HDF\">{}:{}</DataItem>",
                     fmt::join(shape, " "), number_type, xml_escape(h5_name), xml_escape(dataset));
}

// ---------------------------------------------------------------- fields

// Number of values per entity, cells then nodes, slowest dimension first; `xml_cells` as the XDMF index states
// them (with a leading 1 per thin dimension of a 1D or 2D uniform grid; empty: `cells`).
struct EntityShapes {
  Hdf5Shape cells;
  Hdf5Shape nodes;
  Hdf5Shape xml_cells;
};

std::uint64_t product(const Hdf5Shape& shape) {
  std::uint64_t n = 1;
  for (const std::uint64_t d : shape) n *= d;
  return n;
}

const char* attribute_type(int ncomp) {
  switch (ncomp) {
    case 1: return "Scalar";
    case 2:
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return nullptr;
  }
}

int stored_components(int ncomp) { return ncomp == 2 ? 3 : ncomp; }

void check_fields(const std::vector<FieldView>& fields) {
  std::vector<std::pair<Center, std::string>> seen;
  for (const FieldView& f : fields) {
    if (!is_valid_name(f.name)) reject(fmt::format("invalid field name '{}'", f.name));
    if (f.data == nullptr) reject(fmt::format("field '{}' has no data", f.name));
    if (attribute_type(f.ncomp) == nullptr) {
      reject(fmt::format("field '{}' has {} components (allowed: 1, 2, 3, 6, 9)", f.name, f.ncomp));
    }
    for (const auto& [center, name] : seen) {
      if (center == f.center && name == f.name) reject(fmt::format("field '{}' given twice", f.name));
    }
    seen.emplace_back(f.center, f.name);
  }
}

// Field values in storage layout: 2-component vectors padded to 3 with z = 0.
std::vector<double> stored_values(const FieldView& f, std::uint64_t entities) {
  const auto in_c = static_cast<std::size_t>(f.ncomp);
  const auto out_c = static_cast<std::size_t>(stored_components(f.ncomp));
  std::vector<double> out(entities * out_c, 0.0);
  for (std::size_t i = 0; i < entities; ++i) {
    for (std::size_t c = 0; c < in_c; ++c) out[i * out_c + c] = f.data[i * in_c + c];
  }
  return out;
}

// The XDMF <Attribute> of a field dataset.
std::string field_xml(const FieldView& f, Hdf5Shape xml_shape, const std::string& dataset, const std::string& h5_name) {
  const int comps = stored_components(f.ncomp);
  if (comps > 1) xml_shape.push_back(static_cast<std::uint64_t>(comps));
  return fmt::format(
      "        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n          {}\n        </Attribute>\n",
      xml_escape(f.name), attribute_type(f.ncomp), f.center == Center::Cell ? "Cell" : "Node",
      data_item(xml_shape, "Float", h5_name, dataset));
}

// Writes one field dataset and returns its XDMF <Attribute>.
std::string write_field(Hdf5File& h5, const FieldView& f, const EntityShapes& shapes, const std::string& h5_name) {
  const bool cell = f.center == Center::Cell;
  Hdf5Shape shape = cell ? shapes.cells : shapes.nodes;
  const std::uint64_t entities = product(shape);
  const int comps = stored_components(f.ncomp);
  const Hdf5Shape xml_shape = cell && !shapes.xml_cells.empty() ? shapes.xml_cells : shape;
  if (comps > 1) shape.push_back(static_cast<std::uint64_t>(comps));
  const std::string dataset = fmt::format("/{}/{}", cell ? "cell" : "node", f.name);
  h5.write_dataset(dataset, stored_values(f, entities), shape);
  return field_xml(f, xml_shape, dataset, h5_name);
}

// Writes this process's part of one cell field (a collective write in a shared file) and returns its XDMF.
std::string write_field_part(Hdf5File& h5, const FieldView& f, const EntityShapes& shapes, const GridPart& part,
                             int dim, const std::string& h5_name) {
  Hdf5Shape shape = shapes.cells, offset, count;
  for (int d = dim - 1; d >= 0; --d) {
    offset.push_back(static_cast<std::uint64_t>(part.lower[d]));
    count.push_back(static_cast<std::uint64_t>(part.upper[d] - part.lower[d]));
  }
  const int comps = stored_components(f.ncomp);
  if (comps > 1) {
    shape.push_back(static_cast<std::uint64_t>(comps));
    offset.push_back(0);
    count.push_back(static_cast<std::uint64_t>(comps));
  }
  const std::string dataset = "/cell/" + f.name;
  std::uint64_t cells = 1;
  for (int d = 0; d < dim; ++d) cells *= static_cast<std::uint64_t>(part.upper[d] - part.lower[d]);
  h5.write_dataset_part(dataset, stored_values(f, cells), shape, offset, count);
  return field_xml(f, shapes.xml_cells.empty() ? shapes.cells : shapes.xml_cells, dataset, h5_name);
}

std::string write_fields(Hdf5File& h5, const std::vector<FieldView>& fields, const EntityShapes& shapes,
                         const std::string& h5_name) {
  std::string xml;
  for (const FieldView& f : fields) xml += write_field(h5, f, shapes, h5_name);
  return xml;
}

void write_root(Hdf5File& h5, double time, std::int64_t step) {
  h5.write_attribute("/", "time", time);
  h5.write_attribute("/", "step", step);
  h5.write_attribute("/", "format", kFormat);
  h5.create_group("/grid");
  h5.create_group("/cell");
  h5.create_group("/node");
}

// ---------------------------------------------------------------- uniform grids

// Validates the used dimensions and resets the unused ones to cells 1, origin 0, spacing 1.
UniformGrid normalized(const UniformGrid& g) {
  if (g.dim < 1 || g.dim > 3) reject(fmt::format("uniform grid dim must be 1, 2 or 3, not {}", g.dim));
  UniformGrid out = g;
  for (int d = 0; d < 3; ++d) {
    const bool used = d < g.dim;
    if (used && (g.cells[d] < 1 || !(g.spacing[d] > 0.0) || !std::isfinite(g.spacing[d]))) {
      reject(fmt::format("uniform grid needs cells >= 1 and spacing > 0 in dimension {}", d));
    }
    if (used && !std::isfinite(g.origin[d])) reject(fmt::format("uniform grid origin {} is not finite", d));
    if (!used) {
      out.cells[d] = 1;
      out.origin[d] = 0.0;
      out.spacing[d] = 1.0;
    }
  }
  return out;
}

EntityShapes uniform_shapes(const UniformGrid& g, bool slab) {
  EntityShapes s;
  for (int d = g.dim - 1; d >= 0; --d) {
    s.cells.push_back(static_cast<std::uint64_t>(g.cells[d]));
    s.nodes.push_back(static_cast<std::uint64_t>(g.cells[d]) + 1);
  }
  if (slab) {
    s.xml_cells.assign(static_cast<std::size_t>(3 - g.dim), 1);
    s.xml_cells.insert(s.xml_cells.end(), s.cells.begin(), s.cells.end());
  }
  return s;
}

// A 1D or 2D grid with cell data only is indexed as a slab one cell thick in its unused dimensions, as thick as
// its smallest cell and centred on 0: ParaView's default 3D view and slices show it, and both of its XDMF readers
// load its arrays (with a single node layer, a zero-volume grid, the legacy reader loads none).
bool slab_layout(const UniformGrid& g, const std::vector<FieldView>& fields) {
  if (g.dim == 3) return false;
  for (const FieldView& f : fields)
    if (f.center != Center::Cell) return false;
  return true;
}

void write_uniform_grid(Hdf5File& h5, const UniformGrid& g) {
  const std::array<std::int64_t, 3> cells{g.cells[0], g.cells[1], g.cells[2]};
  h5.write_attribute("/grid", "type", std::string_view("uniform"));
  h5.write_attribute("/grid", "dim", std::int64_t{g.dim});
  h5.write_attribute("/grid", "cells", std::span<const std::int64_t>(cells));
  h5.write_attribute("/grid", "origin", std::span<const double>(g.origin));
  h5.write_attribute("/grid", "spacing", std::span<const double>(g.spacing));
}

// Topology and geometry (z y x order); unused dimensions get one node layer, or with `slab` two, one smallest
// cell apart around 0.
std::string uniform_grid_xml(const UniformGrid& g, bool slab) {
  std::array<int, 3> nodes{};
  std::array<double, 3> origin = g.origin, spacing = g.spacing;
  double thin = spacing[0];
  for (int d = 1; d < g.dim; ++d) thin = std::min(thin, spacing[d]);
  for (int d = 0; d < 3; ++d) {
    nodes[d] = d < g.dim ? g.cells[d] + 1 : slab ? 2 : 1;
    if (d >= g.dim && slab) {
      spacing[d] = thin;
      origin[d] = -0.5 * thin;
    }
  }
  return fmt::format(
      "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{} {} {}\"/>\n"
      "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
      "          <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
      "Format=\"XML\">{} {} {}</DataItem>\n"
      "          <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
      "Format=\"XML\">{} {} {}</DataItem>\n"
      "        </Geometry>\n",
      nodes[2], nodes[1], nodes[0], origin[2], origin[1], origin[0], spacing[2], spacing[1], spacing[0]);
}

// ---------------------------------------------------------------- unstructured grids

const char* cell_type_name(const UnstructuredGrid& g) {
  return g.nodes_per_cell == 2 ? "line" : g.nodes_per_cell == 4 ? "quadrilateral" : "hexahedron";
}
// TopologyType (and NodesPerElement where XDMF needs it).
const char* xdmf_topology(const UnstructuredGrid& g) {
  return g.nodes_per_cell == 2   ? "Polyline\" NodesPerElement=\"2"
         : g.nodes_per_cell == 4 ? "Quadrilateral"
                                 : "Hexahedron";
}

void check_unstructured(const UnstructuredGrid& g) {
  const bool ok = (g.dim == 2 && (g.nodes_per_cell == 4 || g.nodes_per_cell == 2)) ||
                  (g.dim == 3 && (g.nodes_per_cell == 8 || g.nodes_per_cell == 4));
  if (!ok) {
    reject(
        fmt::format("unstructured grid must be dim 2 with 4 (quads) or 2 (segments) nodes per cell, or dim 3 "
                    "with 8 (hexahedra) or 4 (surface quads), not dim {} with {}",
                    g.dim, g.nodes_per_cell));
  }
  if (g.num_nodes < 1 || g.num_cells < 1) reject("unstructured grid needs at least one node and one cell");
  if (g.coords == nullptr || g.connectivity == nullptr) reject("unstructured grid has no coordinates or connectivity");
  const std::int64_t n = g.num_cells * g.nodes_per_cell;
  for (std::int64_t i = 0; i < n; ++i) {
    if (g.connectivity[i] < 0 || g.connectivity[i] >= g.num_nodes) {
      reject(
          fmt::format("connectivity entry {} = {} is not a node id (num_nodes {})", i, g.connectivity[i], g.num_nodes));
    }
  }
}

EntityShapes unstructured_shapes(const UnstructuredGrid& g) {
  return {{static_cast<std::uint64_t>(g.num_cells)}, {static_cast<std::uint64_t>(g.num_nodes)}, {}};
}

std::vector<double> xyz_coordinates(const UnstructuredGrid& g) {
  const auto n = static_cast<std::size_t>(g.num_nodes);
  const auto dim = static_cast<std::size_t>(g.dim);
  std::vector<double> xyz(n * 3, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t d = 0; d < dim; ++d) xyz[i * 3 + d] = g.coords[i * dim + d];
  }
  return xyz;
}

Hdf5Shape coordinates_shape(const UnstructuredGrid& g) { return {static_cast<std::uint64_t>(g.num_nodes), 3}; }
Hdf5Shape connectivity_shape(const UnstructuredGrid& g) {
  return {static_cast<std::uint64_t>(g.num_cells), static_cast<std::uint64_t>(g.nodes_per_cell)};
}

void write_unstructured_grid(Hdf5File& h5, const UnstructuredGrid& g) {
  h5.write_attribute("/grid", "type", std::string_view("unstructured"));
  h5.write_attribute("/grid", "dim", std::int64_t{g.dim});
  h5.write_attribute("/grid", "cell_type", std::string_view(cell_type_name(g)));
  h5.write_dataset("/grid/coordinates", xyz_coordinates(g), coordinates_shape(g));
  const std::span<const std::int64_t> conn(g.connectivity, static_cast<std::size_t>(g.num_cells * g.nodes_per_cell));
  h5.write_dataset("/grid/connectivity", conn, connectivity_shape(g));
}

std::string unstructured_grid_xml(const UnstructuredGrid& g, const std::string& h5_name) {
  return fmt::format(
      "        <Topology TopologyType=\"{}\" NumberOfElements=\"{}\">\n          {}\n        </Topology>\n"
      "        <Geometry GeometryType=\"XYZ\">\n          {}\n        </Geometry>\n",
      xdmf_topology(g), g.num_cells, data_item(connectivity_shape(g), "Int", h5_name, "/grid/connectivity"),
      data_item(coordinates_shape(g), "Float", h5_name, "/grid/coordinates"));
}

// ---------------------------------------------------------------- files

void check_time(double time) {
  if (!std::isfinite(time)) reject(fmt::format("time {} is not finite", time));
}

// Writes an HDF5 file under a temporary name via `fill`, closes it and renames it to `target`.
template <class Fill>
void write_hdf5_atomically(const fs::path& target, Fill&& fill) {
  const fs::path tmp = temp_path_for(target);
  try {
    Hdf5File h5(tmp, Hdf5File::Mode::Create);
    fill(h5);
    h5.close();
    commit_file(tmp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

std::string grid_element(const std::string& name, double time, const std::string& body) {
  return fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n        <Time Value=\"{}\"/>\n{}      </Grid>\n",
                     xml_escape(name), time, body);
}

std::string xdmf_document(const std::string& basename, const std::vector<std::string>& grids) {
  std::string doc = fmt::format(
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n"
      "    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
      xml_escape(basename));
  for (const std::string& g : grids) doc += g;
  doc += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return doc;
}

}  // namespace

SnapshotSeries::SnapshotSeries(fs::path dir, std::string basename)
    : dir_(std::move(dir)), basename_(std::move(basename)) {
  if (!is_valid_name(basename_)) reject(fmt::format("invalid series basename '{}'", basename_));
}

fs::path SnapshotSeries::xdmf_path() const { return dir_ / (basename_ + ".xmf"); }

std::string SnapshotSeries::file_name(std::size_t index) const { return fmt::format("{}_{:06}.h5", basename_, index); }

void SnapshotSeries::prepare_directory() const {
  std::error_code ec;
  if (!fs::is_directory(dir_, ec)) {
    throw std::runtime_error(fmt::format("snapshot: output directory '{}' does not exist", dir_.string()));
  }
  if (count() == 0 && !resumed_) remove_numbered_files(dir_, basename_ + "_", ".h5");  // an earlier run's series
}

void SnapshotSeries::resume(std::vector<std::string> entries) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    std::error_code ec;
    if (!fs::is_regular_file(dir_ / file_name(i), ec))
      throw std::runtime_error(
          fmt::format("{}: snapshot {} of the checkpointed series is missing", (dir_ / file_name(i)).string(), i));
  }
  // Later snapshots of the run that stopped: written again (or, with an earlier end time, not at all).
  remove_numbered_files(dir_, basename_ + "_", ".h5", entries.size());
  grids_ = std::move(entries);
  resumed_ = true;
  write_file_atomically(xdmf_path(), xdmf_document(basename_, grids_));
}

fs::path SnapshotSeries::write(double time, std::int64_t step, const UniformGrid& g,
                               const std::vector<FieldView>& fields) {
  check_time(time);
  check_fields(fields);
  const UniformGrid grid = normalized(g);
  prepare_directory();
  const std::string name = file_name(count());
  const bool slab = slab_layout(grid, fields);
  std::string body = uniform_grid_xml(grid, slab);
  write_hdf5_atomically(dir_ / name, [&](Hdf5File& h5) {
    write_root(h5, time, step);
    write_uniform_grid(h5, grid);
    body += write_fields(h5, fields, uniform_shapes(grid, slab), name);
  });
  return publish(name, grid_element(fs::path(name).stem().string(), time, body));
}

fs::path SnapshotSeries::write(double time, std::int64_t step, const UnstructuredGrid& g,
                               const std::vector<FieldView>& fields) {
  check_time(time);
  check_fields(fields);
  check_unstructured(g);
  prepare_directory();
  const std::string name = file_name(count());
  std::string body = unstructured_grid_xml(g, name);
  write_hdf5_atomically(dir_ / name, [&](Hdf5File& h5) {
    write_root(h5, time, step);
    write_unstructured_grid(h5, g);
    body += write_fields(h5, fields, unstructured_shapes(g), name);
  });
  return publish(name, grid_element(fs::path(name).stem().string(), time, body));
}

fs::path SnapshotSeries::write_part(double time, std::int64_t step, const UniformGrid& g, const GridPart& part,
                                    const std::vector<FieldView>& fields, CollectiveWrite& together) {
  check_time(time);
  check_fields(fields);
  for (const FieldView& f : fields)
    if (f.center != Center::Cell) reject(fmt::format("field '{}': a grid part holds cell fields only", f.name));
  const UniformGrid grid = normalized(g);
  if (together.leader()) prepare_directory();
  together.barrier();  // an earlier run's files are gone before the new one is created
  const std::string name = file_name(count());
  const bool slab = slab_layout(grid, fields);
  std::string body = uniform_grid_xml(grid, slab);
  const fs::path target = dir_ / name, tmp = temp_path_for(target);
  try {
    Hdf5File h5(tmp, Hdf5File::Mode::Create, together.file_access());
    write_root(h5, time, step);
    write_uniform_grid(h5, grid);
    const EntityShapes shapes = uniform_shapes(grid, slab);
    for (const FieldView& f : fields) body += write_field_part(h5, f, shapes, part, grid.dim, name);
    h5.close();
    if (together.leader()) commit_file(tmp, target);
  } catch (...) {
    std::error_code ignored;
    if (together.leader()) fs::remove(tmp, ignored);
    throw;
  }
  const std::string grid_xml = grid_element(fs::path(name).stem().string(), time, body);
  if (together.leader()) return publish(name, grid_xml);
  grids_.push_back(grid_xml);  // the others keep the count and the entries alike
  return target;
}

// Adds a complete snapshot to the .xmf; on failure the snapshot is dropped again.
fs::path SnapshotSeries::publish(const std::string& file_name, std::string grid_xml) {
  const fs::path h5_path = dir_ / file_name;
  grids_.push_back(std::move(grid_xml));
  try {
    write_file_atomically(xdmf_path(), xdmf_document(basename_, grids_));
  } catch (...) {
    grids_.pop_back();
    std::error_code ignored;
    fs::remove(h5_path, ignored);
    throw;
  }
  return h5_path;
}

std::size_t remove_numbered_files(const fs::path& dir, std::string_view prefix, std::string_view suffix,
                                  std::size_t from) {
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() != prefix.size() + 6 + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix))
      continue;
    const std::string_view digits = std::string_view(name).substr(prefix.size(), 6);
    if (digits.find_first_not_of("0123456789") != std::string_view::npos) continue;
    if (std::stoul(std::string(digits)) < from) continue;
    std::error_code rm;
    if (it->is_regular_file(rm) && fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace cosim::io
