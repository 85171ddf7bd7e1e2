#include "solid_solver/mesh/mesh_pack.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <type_traits>

#include "solid_solver/mesh/gmsh_reader.h"

namespace cosim::solid {

namespace {

constexpr char kMagic[4] = {'C', 'S', 'M', '1'};  // the layout below; another layout gets another tag

struct Writer {
  std::string out;
  void bytes(const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); }
  void count(std::size_t n) {
    const std::uint64_t v = n;
    bytes(&v, sizeof v);
  }
  void integer(int v) { bytes(&v, sizeof v); }
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    count(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    count(s.size());
    bytes(s.data(), s.size());
  }
};

struct Reader {
  const std::string& in;
  const std::string& what;
  std::size_t at = 0;

  [[noreturn]] void fail(const std::string& msg) const {
    throw MeshError(fmt::format("{}: not a packed mesh ({} at byte {} of {})", what, msg, at, in.size()));
  }
  void bytes(void* p, std::size_t n) {
    if (n > in.size() - at) fail("it ends early");
    std::memcpy(p, in.data() + at, n);
    at += n;
  }
  // A count of items of `item` bytes each that must fit in the bytes left.
  std::size_t count(std::size_t item) {
    std::uint64_t v = 0;
    bytes(&v, sizeof v);
    if (item > 0 && v > (in.size() - at) / item)
      fail(fmt::format("it ends early: a count of {} items runs past its end", v));
    return static_cast<std::size_t>(v);
  }
  int integer() {
    int v = 0;
    bytes(&v, sizeof v);
    return v;
  }
  template <class T>
  std::vector<T> array() {
    std::vector<T> v(count(sizeof(T)));
    bytes(v.data(), v.size() * sizeof(T));
    return v;
  }
  std::string text() {
    std::string s(count(1), '\0');
    bytes(s.data(), s.size());
    return s;
  }
};

}  // namespace

std::string pack_mesh(const Mesh& m) {
  Writer w;
  std::size_t size = sizeof kMagic + 4 * sizeof(int) + sizeof(double) * m.x0.size() +
                     sizeof(int) * (m.conn.size() + m.element_block.size() + 2 * m.block_range.size() +
                                    m.node_corner_offset.size() + m.node_corners.size());
  for (const auto& [name, set] : m.node_sets) size += name.size() + sizeof(int) * set.size();
  for (const auto& [name, set] : m.face_sets) size += name.size() + 5 * sizeof(int) * set.size();
  w.out.reserve(size + 1024);
  w.bytes(kMagic, sizeof kMagic);
  for (int v : {m.dim, m.npe, m.num_nodes, m.num_elements}) w.integer(v);
  w.array(m.x0);
  w.array(m.conn);
  w.array(m.element_block);
  w.count(m.block_names.size());
  for (const std::string& s : m.block_names) w.text(s);
  w.array(m.block_range);
  w.count(m.node_sets.size());
  for (const auto& [name, set] : m.node_sets) {
    w.text(name);
    w.array(set);
  }
  w.count(m.face_sets.size());
  for (const auto& [name, set] : m.face_sets) {
    w.text(name);
    w.array(set);  // BoundaryFace: 5 ints, no padding (checked in unpack_mesh's static_assert)
  }
  w.array(m.node_corner_offset);
  w.array(m.node_corners);
  return std::move(w.out);
}

Mesh unpack_mesh(const std::string& buffer, const std::string& what) {
  static_assert(sizeof(BoundaryFace) == 5 * sizeof(int) && std::is_trivially_copyable_v<BoundaryFace>);
  Reader r{buffer, what};
  char magic[sizeof kMagic];
  r.bytes(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("another layout tag");
  Mesh m;
  m.dim = r.integer();
  m.npe = r.integer();
  m.num_nodes = r.integer();
  m.num_elements = r.integer();
  if (!((m.dim == 2 && m.npe == 4) || (m.dim == 3 && m.npe == 8)) || m.num_nodes < 0 || m.num_elements < 0)
    r.fail(fmt::format("dimension {}, {} nodes per element, {} nodes, {} elements", m.dim, m.npe, m.num_nodes,
                       m.num_elements));
  m.x0 = r.array<double>();
  m.conn = r.array<int>();
  m.element_block = r.array<int>();
  if (m.x0.size() != static_cast<std::size_t>(m.num_nodes) * m.dim ||
      m.conn.size() != static_cast<std::size_t>(m.num_elements) * m.npe ||
      m.element_block.size() != static_cast<std::size_t>(m.num_elements))
    r.fail("arrays of other lengths than the counts");
  m.block_names.resize(r.count(sizeof(std::uint64_t)));
  for (std::string& s : m.block_names) s = r.text();
  m.block_range = r.array<std::array<int, 2>>();
  for (std::size_t k = r.count(2 * sizeof(std::uint64_t)); k > 0; --k) {
    std::string name = r.text();
    m.node_sets[name] = r.array<int>();
  }
  for (std::size_t k = r.count(2 * sizeof(std::uint64_t)); k > 0; --k) {
    std::string name = r.text();
    m.face_sets[name] = r.array<BoundaryFace>();
  }
  m.node_corner_offset = r.array<int>();
  m.node_corners = r.array<int>();
  if (r.at != buffer.size()) r.fail("bytes left over");
  return m;
}

}  // namespace cosim::solid
