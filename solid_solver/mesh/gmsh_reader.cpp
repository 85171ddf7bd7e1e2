#include "solid_solver/mesh/gmsh_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "common/config/config.h"
#include "solid_solver/mesh/element_faces.h"

namespace cosim::solid {

namespace {

struct Lines {
  std::string path;
  std::vector<std::string> text;
  std::size_t next = 0;  // index of the next unread line

  [[noreturn]] void fail(std::size_t line, const std::string& msg) const {
    throw MeshError(fmt::format("{}:{}: {}", path, line + 1, msg));
  }
  // The next line as a stream; `at` gets its index.
  std::istringstream take(std::size_t& at, const char* what) {
    if (next >= text.size())
      fail(text.empty() ? 0 : text.size() - 1, fmt::format("unexpected end of file, expected {}", what));
    at = next;
    return std::istringstream(text[next++]);
  }
};

template <class T>
T field(std::istringstream& is, const Lines& L, std::size_t line, const char* what) {
  T v{};
  if (!(is >> v)) L.fail(line, fmt::format("expected {}", what));
  return v;
}

// A count of entries that follow, one or more lines each: a whole number (not "9e18", which reads as 9), never
// negative, never more than the lines left (a corrupt count must not become a huge allocation).
long count_field(std::istringstream& is, const Lines& L, std::size_t line, const char* what) {
  const std::string word = field<std::string>(is, L, line, what);
  long n = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), n);
  if (ec == std::errc::result_out_of_range)
    L.fail(line, fmt::format("{} is {}: far more than any mesh holds", what, word));
  if (ec != std::errc() || end != word.data() + word.size())
    L.fail(line, fmt::format("{} is '{}': expected a whole number", what, config::printable(word)));
  const long left = static_cast<long>(L.text.size() - L.next);
  if (n < 0) L.fail(line, fmt::format("{} is {}: expected a count >= 0", what, n));
  if (n > left) L.fail(line, fmt::format("{} is {}, but only {} lines follow in the file", what, n, left));
  return n;
}

// The header line of block b of a $Nodes or $Elements section that declares `blocks` of them: a "$End..." line
// there means the section holds fewer blocks than it says.
std::istringstream take_block(Lines& L, std::size_t& at, long b, long blocks, const char* section, const char* what) {
  auto is = L.take(at, what);
  if (L.text[at].rfind("$End", 0) == 0)
    L.fail(at,
           fmt::format("the {} section declares numEntityBlocks = {}, but ends after {} block(s)", section, blocks, b));
  return is;
}

// The section's $End line, after the entries its header declares; `count` says what a different line means.
void expect_end(Lines& L, const std::string& section, const std::string& count = "") {
  if (!count.empty() && L.next < L.text.size() && L.text[L.next].rfind("$End" + section, 0) != 0)
    L.fail(L.next, fmt::format("expected $End{} after {}: the section holds more than it declares", section, count));
  std::size_t at;
  auto is = L.take(at, ("$End" + section).c_str());
  std::string w;
  is >> w;
  if (w != "$End" + section) L.fail(at, fmt::format("expected $End{}, got '{}'", section, w));
}

struct ElementRecord {
  int type, entity_dim, entity_tag;
  long tag;
  std::size_t line;
  std::array<long, 8> nodes;
};

const char* type_name(int t) {
  switch (t) {
    case 1: return "2-node line";
    case 2: return "3-node triangle";
    case 3: return "4-node quadrangle";
    case 4: return "4-node tetrahedron";
    case 5: return "8-node hexahedron";
    case 6: return "6-node prism";
    case 7: return "5-node pyramid";
    case 8: return "3-node line";
    case 9: return "6-node triangle";
    case 10: return "9-node quadrangle";
    case 11: return "10-node tetrahedron";
    case 12: return "27-node hexahedron";
    case 15: return "point";
    case 16: return "8-node quadrangle";
    case 17: return "20-node hexahedron";
    default: return "higher-order or unknown element";
  }
}

int type_nodes(int t) { return t == 15 ? 1 : t == 1 ? 2 : t == 3 ? 4 : t == 5 ? 8 : -1; }

}  // namespace

int find_bad_element(const Mesh& m, std::string& what) {
  // Corner a and its three edge neighbours, ordered so that the triple product is > 0 for a right-handed hex.
  static constexpr int hexc[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                     {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
  const int D = m.dim, N = m.npe;
  for (int e = 0; e < m.num_elements; ++e) {
    const int* c = &m.conn[static_cast<std::size_t>(e) * N];
    auto X = [&](int a, int d) { return m.x0[static_cast<std::size_t>(c[a]) * D + d]; };
    double lmax = 0.0;
    for (int a = 0; a < N; ++a)
      for (int b = a + 1; b < N; ++b) {
        double l2 = 0;
        for (int d = 0; d < D; ++d) l2 += (X(a, d) - X(b, d)) * (X(a, d) - X(b, d));
        lmax = std::max(lmax, std::sqrt(l2));
      }
    const double tol = 1e-10 * std::pow(lmax, D);
    int neg = 0, bad_corner = -1;
    bool degenerate = false;
    for (int a = 0; a < N; ++a) {
      double J;
      if (D == 2) {
        const int an = (a + 1) & 3, ap = (a + 3) & 3;
        J = (X(an, 0) - X(a, 0)) * (X(ap, 1) - X(a, 1)) - (X(an, 1) - X(a, 1)) * (X(ap, 0) - X(a, 0));
      } else {
        double u[3][3];
        for (int k = 0; k < 3; ++k)
          for (int d = 0; d < 3; ++d) u[k][d] = X(hexc[a][k], d) - X(a, d);
        J = u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) - u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
            u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0]);
      }
      if (J < -tol) {
        ++neg;
        if (bad_corner < 0) bad_corner = a;
      } else if (J <= tol && !degenerate) {
        degenerate = true;
        if (bad_corner < 0) bad_corner = a;
      }
    }
    if (neg == N) {
      what = D == 2 ? "inverted (negative area at every corner: clockwise node order)"
                    : "inverted (negative volume at every corner: left-handed node order)";
      return e;
    }
    if (neg > 0) {
      what = fmt::format("inverted or self-intersecting (negative Jacobian at local corner {})", bad_corner);
      return e;
    }
    if (degenerate) {
      what = fmt::format("degenerate (zero Jacobian at local corner {}: collapsed edge or face)", bad_corner);
      return e;
    }
  }
  return -1;
}

Mesh read_gmsh(const std::string& path) {
  Lines L;
  L.path = path;
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw MeshError(fmt::format("{}: is a directory, not a Gmsh mesh file", path));
    std::ifstream in(path);
    if (!in) throw MeshError(fmt::format("{}: cannot open the Gmsh mesh file", path));
    std::string s;
    while (std::getline(in, s)) {
      if (!s.empty() && s.back() == '\r') s.pop_back();
      L.text.push_back(s);
    }
  }
  std::map<std::pair<int, int>, std::string> phys_names;        // (dim, tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entity_phys;  // (dim, entity) -> physical tags
  std::vector<double> coords;                                   // 3 per node
  std::vector<std::size_t> node_line;
  std::unordered_map<long, int> node_index;
  std::vector<ElementRecord> elems;
  bool have_format = false, have_nodes = false, have_elements = false;

  while (L.next < L.text.size()) {
    const std::size_t at = L.next++;
    std::istringstream hs(L.text[at]);
    std::string h;
    if (!(hs >> h)) continue;
    if (h == "$MeshFormat") {
      std::size_t ln;
      auto is = L.take(ln, "the format line 'version file-type data-size'");
      const std::string version = field<std::string>(is, L, ln, "a version number");
      const int file_type = field<int>(is, L, ln, "the file type (0 = ASCII)");
      if (version != "4.1")
        L.fail(ln, fmt::format("MSH format version {} is not supported: expected 4.1 (gmsh -format msh41, or "
                               "Mesh.MshFileVersion = 4.1)",
                               version));
      if (file_type != 0)
        L.fail(ln, "binary MSH files are not supported: expected ASCII (file type 0; Mesh.Binary = 0)");
      expect_end(L, "MeshFormat");
      have_format = true;
    } else if (h == "$PhysicalNames") {
      std::size_t ln;
      auto is = L.take(ln, "the number of physical names");
      const int n = field<int>(is, L, ln, "the number of physical names");
      for (int k = 0; k < n; ++k) {
        auto ps = L.take(ln, "a physical name 'dim tag \"name\"'");
        const int dim = field<int>(ps, L, ln, "the dimension of a physical group");
        const int tag = field<int>(ps, L, ln, "the tag of a physical group");
        std::string rest;
        std::getline(ps, rest);
        const auto q1 = rest.find('"'), q2 = rest.rfind('"');
        if (q1 == std::string::npos || q2 == q1) L.fail(ln, "expected a quoted physical group name");
        const std::string name = rest.substr(q1 + 1, q2 - q1 - 1);
        // A scene (UTF-8 YAML) could not name it, and messages would carry its raw bytes.
        if (!config::is_printable(name))
          L.fail(ln, fmt::format("physical group {} is named '{}', which is not printable UTF-8 text (the bytes "
                                 "shown as \\xNN are control characters or invalid UTF-8): rename the group",
                                 tag, config::printable(name)));
        phys_names[{dim, tag}] = name;
      }
      expect_end(L, "PhysicalNames");
    } else if (h == "$Entities") {
      std::size_t ln;
      auto is = L.take(ln, "the entity counts");
      int count[4];
      for (int d = 0; d < 4; ++d) count[d] = field<int>(is, L, ln, "numPoints numCurves numSurfaces numVolumes");
      for (int d = 0; d < 4; ++d)
        for (int k = 0; k < count[d]; ++k) {
          auto es = L.take(ln, "an entity");
          const int tag = field<int>(es, L, ln, "an entity tag");
          for (int c = 0; c < (d == 0 ? 3 : 6); ++c) field<double>(es, L, ln, "the entity's bounding box");
          const int np = field<int>(es, L, ln, "the number of physical tags");
          auto& v = entity_phys[{d, tag}];
          for (int p = 0; p < np; ++p) v.push_back(field<int>(es, L, ln, "a physical tag"));
        }
      expect_end(L, "Entities");
    } else if (h == "$Nodes") {
      std::size_t ln;
      auto is = L.take(ln, "numEntityBlocks numNodes minNodeTag maxNodeTag");
      const long nblocks = count_field(is, L, ln, "numEntityBlocks");
      const long nnodes = count_field(is, L, ln, "numNodes");
      const std::size_t header = ln;
      coords.reserve(static_cast<std::size_t>(nnodes) * 3);  // checked: at most the lines left
      long read = 0;
      for (long b = 0; b < nblocks; ++b) {
        auto bs = take_block(L, ln, b, nblocks, "$Nodes",
                             "a node block header 'entityDim entityTag parametric numNodesInBlock'");
        field<int>(bs, L, ln, "entityDim");
        field<int>(bs, L, ln, "entityTag");
        const int parametric = field<int>(bs, L, ln, "parametric (0 or 1)");
        const long n = count_field(bs, L, ln, "numNodesInBlock");
        read += n;
        if (read > nnodes)
          L.fail(ln, fmt::format("the node blocks hold more nodes than the {} the $Nodes header (line {}) declares",
                                 nnodes, header + 1));
        std::vector<long> tags(n);
        for (long k = 0; k < n; ++k) {
          auto ts = L.take(ln, "a node tag");
          tags[k] = field<long>(ts, L, ln, "a node tag");
          if (!node_index.emplace(tags[k], static_cast<int>(node_index.size())).second)
            L.fail(ln, fmt::format("node {} is defined twice", tags[k]));
          node_line.push_back(ln);
        }
        for (long k = 0; k < n; ++k) {
          auto cs = L.take(ln, "node coordinates 'x y z'");
          for (int d = 0; d < 3; ++d) {
            const double v = field<double>(cs, L, ln, "node coordinates 'x y z'");
            // Beyond 1e100 m a corner Jacobian (an edge length to the power 3) could overflow.
            if (!(std::abs(v) <= 1e100))
              L.fail(ln, fmt::format("node {}: coordinate {:g} is not a finite number of at most 1e100 m in "
                                     "magnitude",
                                     tags[k], v));
            coords.push_back(v);
          }
          (void)parametric;  // parametric coordinates follow on the same line; not needed
        }
      }
      expect_end(L, "Nodes", fmt::format("the {} node block(s) numEntityBlocks declares", nblocks));
      if (read != nnodes)
        L.fail(header, fmt::format("numNodes is {}, but the node blocks hold {} nodes", nnodes, read));
      have_nodes = true;
    } else if (h == "$Elements") {
      std::size_t ln;
      auto is = L.take(ln, "numEntityBlocks numElements minElementTag maxElementTag");
      const long nblocks = count_field(is, L, ln, "numEntityBlocks");
      const long nelems = count_field(is, L, ln, "numElements");
      const std::size_t header = ln;
      long read = 0;
      for (long b = 0; b < nblocks; ++b) {
        auto bs = take_block(L, ln, b, nblocks, "$Elements",
                             "an element block header 'entityDim entityTag elementType numElementsInBlock'");
        const int edim = field<int>(bs, L, ln, "entityDim");
        const int etag = field<int>(bs, L, ln, "entityTag");
        const int type = field<int>(bs, L, ln, "elementType");
        const long n = count_field(bs, L, ln, "numElementsInBlock");
        read += n;
        if (read > nelems)
          L.fail(ln, fmt::format("the element blocks hold more elements than the {} the $Elements header (line {}) "
                                 "declares",
                                 nelems, header + 1));
        const int nn = type_nodes(type);
        for (long k = 0; k < n; ++k) {
          auto es = L.take(ln, "an element 'tag node...'");
          ElementRecord r{type, edim, etag, field<long>(es, L, ln, "an element tag"), ln, {}};
          if (nn < 0)
            L.fail(ln, fmt::format("element {}: element type {} ({}) is not supported: expected 4-node "
                                   "quadrangles (type 3) or 8-node hexahedra (type 5), with 2-node lines (type 1) "
                                   "as 2D boundary elements",
                                   r.tag, type, type_name(type)));
          for (int a = 0; a < nn; ++a) r.nodes[a] = field<long>(es, L, ln, "the element's node tags");
          elems.push_back(r);
        }
      }
      expect_end(L, "Elements", fmt::format("the {} element block(s) numEntityBlocks declares", nblocks));
      if (read != nelems)
        L.fail(header, fmt::format("numElements is {}, but the element blocks hold {} elements", nelems, read));
      have_elements = true;
    } else if (h[0] == '$' && h.rfind("$End", 0) != 0) {
      const std::string end = "$End" + h.substr(1);  // skip sections we do not need
      while (L.next < L.text.size() && L.text[L.next].rfind(end, 0) != 0) ++L.next;
      if (L.next >= L.text.size()) L.fail(at, fmt::format("section {} has no {}", h, end));
      ++L.next;
    } else {
      L.fail(at, fmt::format("expected a section header ($MeshFormat, $Nodes, $Elements, ...), got '{}'", h));
    }
  }
  if (!have_format) L.fail(0, "not a Gmsh MSH file: no $MeshFormat section");
  if (!have_nodes || !have_elements) L.fail(L.text.size() - 1, "no $Nodes or $Elements section");

  // Dimension: 3 with hexahedra, 2 with quadrangles on surfaces.
  int dim = 0;
  for (const auto& r : elems) {
    if (r.type == 5) dim = 3;
    if (r.type == 3 && r.entity_dim == 2 && dim == 0) dim = 2;
  }
  if (dim == 0) throw MeshError(fmt::format("{}: no quadrangles on surfaces or hexahedra on volumes", path));

  Mesh m;
  m.dim = dim;
  m.npe = dim == 2 ? 4 : 8;
  m.num_nodes = static_cast<int>(node_index.size());
  m.x0.resize(static_cast<std::size_t>(m.num_nodes) * dim);
  for (int n = 0; n < m.num_nodes; ++n)
    for (int d = 0; d < dim; ++d)
      m.x0[static_cast<std::size_t>(n) * dim + d] = coords[3 * static_cast<std::size_t>(n) + d];
  if (dim == 2) {
    double zmin = 1e300, zmax = -1e300, ext = 0;
    for (int n = 0; n < m.num_nodes; ++n) {
      zmin = std::min(zmin, coords[3 * n + 2]);
      zmax = std::max(zmax, coords[3 * n + 2]);
      ext = std::max({ext, std::abs(coords[3 * n]), std::abs(coords[3 * n + 1])});
    }
    if (zmax - zmin > 1e-9 * std::max(ext, 1e-300))
      throw MeshError(
          fmt::format("{}: a 2D mesh (quadrangles) must lie in a plane z = const (z from {} to {})", path, zmin, zmax));
  }
  auto group_name = [&](int d, int tag) {
    auto it = phys_names.find({d, tag});
    return it != phys_names.end() ? it->second : std::to_string(tag);
  };
  auto node_of = [&](const ElementRecord& r, int a) {
    auto it = node_index.find(r.nodes[a]);
    if (it == node_index.end()) L.fail(r.line, fmt::format("element {}: node {} is not in $Nodes", r.tag, r.nodes[a]));
    return it->second;
  };

  // Element blocks: the physical groups of dimension dim, ordered by tag.
  std::map<int, int> block_of_tag;
  for (const auto& [key, name] : phys_names)
    if (key.first == dim) block_of_tag.emplace(key.second, 0);
  for (const auto& [key, tags] : entity_phys)
    if (key.first == dim)
      for (int t : tags) block_of_tag.emplace(t, 0);
  for (auto& [tag, idx] : block_of_tag) {
    idx = static_cast<int>(m.block_names.size());
    m.block_names.push_back(group_name(dim, tag));
  }
  const int elem_type = dim == 2 ? 3 : 5, face_type = dim == 2 ? 1 : 3;
  std::vector<std::size_t> elem_line;
  std::vector<long> elem_tag;
  std::vector<const ElementRecord*> faces;
  for (const auto& r : elems) {
    if (r.entity_dim == dim && r.type == elem_type) {
      const auto it = entity_phys.find({dim, r.entity_tag});
      const int ng = it == entity_phys.end() ? 0 : static_cast<int>(it->second.size());
      if (ng == 0)
        L.fail(r.line,
               fmt::format("element {} ({} {}) belongs to no physical group: name the element blocks "
                           "with physical groups (Physical {})",
                           r.tag, dim == 2 ? "surface" : "volume", r.entity_tag, dim == 2 ? "Surface" : "Volume"));
      if (ng > 1)
        L.fail(r.line, fmt::format("element {} belongs to the physical groups '{}' and '{}': an element belongs to "
                                   "exactly one block",
                                   r.tag, group_name(dim, it->second[0]), group_name(dim, it->second[1])));
      for (int a = 0; a < m.npe; ++a) m.conn.push_back(node_of(r, a));
      m.element_block.push_back(block_of_tag.at(it->second[0]));
      elem_line.push_back(r.line);
      elem_tag.push_back(r.tag);
    } else if (r.entity_dim == dim - 1 && r.type == face_type) {
      faces.push_back(&r);
    } else if (r.type == 15 || (dim == 3 && r.type == 1)) {
      continue;  // points, and curve segments of a 3D mesh
    } else {
      L.fail(r.line,
             fmt::format("element {}: a {} (type {}) on a {}-dimensional entity does not fit a {}D mesh of {}", r.tag,
                         type_name(r.type), r.type, r.entity_dim, dim, dim == 2 ? "quadrangles" : "hexahedra"));
    }
  }
  m.num_elements = static_cast<int>(m.element_block.size());

  std::string what;
  const int bad = find_bad_element(m, what);
  if (bad >= 0)
    L.fail(elem_line[bad],
           fmt::format("element {} of group '{}': {}", elem_tag[bad], m.block_names[m.element_block[bad]], what));

  // Boundary sets: each boundary element must be the face of exactly one element.
  const auto all = all_element_faces(m);
  for (const ElementRecord* r : faces) {
    const auto it = entity_phys.find({dim - 1, r->entity_tag});
    if (it == entity_phys.end() || it->second.empty()) continue;  // boundary elements without a group
    std::array<int, 4> nodes{-1, -1, -1, -1};
    for (int a = 0; a < m.face_nodes(); ++a) nodes[a] = node_of(*r, a);
    const auto key = face_key(dim, nodes);
    auto lo = std::lower_bound(all.begin(), all.end(), key,
                               [](const FaceRef& f, const std::array<int, 4>& k) { return f.key < k; });
    const std::string gname = group_name(dim - 1, it->second[0]);
    if (lo == all.end() || lo->key != key)
      L.fail(r->line, fmt::format("boundary element {} of group '{}' is not a face of any {}", r->tag, gname,
                                  dim == 2 ? "quadrangle" : "hexahedron"));
    if (lo + 1 != all.end() && (lo + 1)->key == key)
      L.fail(r->line, fmt::format("boundary element {} of group '{}' is an interior face (between two elements); "
                                  "boundary groups must lie on the exterior",
                                  r->tag, gname));
    const BoundaryFace bf{element_face_nodes(m, lo->element, lo->local), lo->element};
    for (int t : it->second) {
      const std::string name = group_name(dim - 1, t);
      m.face_sets[name].push_back(bf);
      for (int a = 0; a < m.face_nodes(); ++a) m.node_sets[name].push_back(bf.nodes[a]);
    }
  }
  for (auto& [name, set] : m.node_sets) {
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  // Groups of boundary dimension without elements still exist (empty sets), so the scene can name them.
  for (const auto& [key, name] : phys_names)
    if (key.first == dim - 1) {
      m.face_sets[name];
      m.node_sets[name];
    }
  return m;
}

}  // namespace cosim::solid
