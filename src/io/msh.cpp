//! Gmsh MSH 4.1, ASCII. Reads $MeshFormat, $Entities (physical tags), $Nodes (entity blocks,
//! parametric coordinates skipped, node tags in any order and not necessarily contiguous) and
//! $Elements with types 1 (line -> edges), 2 (triangle), 3 (quad), 4 (tet), 5 (hex) and 15
//! (point, ignored); other sections are skipped. When some entity of $Entities has a physical
//! tag, each element's label is the first physical tag of its entity (0 when it has none); elements of one type are
//! kept in the order of their tags. MSH 2.x, 4.0 and binary files are refused. Written as one
//! node block and one element block per element type and label (tags in the mesh's order);
//! $Entities always (Gmsh needs every element block's entity declared), each with its label as
//! physical tag (0 included) when the data has labels.
#include "io/formats.h"
#include "io/parse.h"

#include <algorithm>
#include <climits>
#include <map>
#include <unordered_map>

namespace polycube::io::detail {

namespace {

const char* gmsh_type_name(long long t) {
  switch (t) {
    case 6: return "6-node prism";
    case 7: return "5-node pyramid";
    case 8: return "3-node line";
    case 9: return "6-node triangle";
    case 10: return "9-node quad";
    case 11: return "10-node tet";
    case 12: return "27-node hex";
    case 13: return "18-node prism";
    case 14: return "14-node pyramid";
    case 16: return "8-node quad";
    case 17: return "20-node hex";
    default: return "unknown";
  }
}

class MshReader {
 public:
  MshReader(std::string_view data, const std::string& name) : s_(data, name) {}

  core::MeshData read() {
    bool have_format = false;
    for (;;) {
      const std::string_view sec = s_.next();
      if (sec.empty()) break;
      if (sec.front() != '$') s_.fail("expected a section ($Name), found " + quote(sec));
      if (!have_format && sec != "$MeshFormat") s_.fail("not a Gmsh file (no $MeshFormat first)");
      if (sec == "$MeshFormat") {
        mesh_format();
        have_format = true;
      } else if (sec == "$Entities") {
        entities();
      } else if (sec == "$Nodes") {
        nodes();
      } else if (sec == "$Elements") {
        elements();
      } else {
        skip_section(sec);
        continue;
      }
      end_of(sec);
    }
    if (!have_format) s_.fail("not a Gmsh file (no $MeshFormat)");
    if (!have_nodes_) s_.fail("no $Nodes section");
    if (!have_elements_) s_.fail("no $Elements section");
    return std::move(d_);
  }

 private:
  void end_of(std::string_view sec) {
    const std::string want = "$End" + std::string(sec.substr(1));
    const std::string_view t = s_.token(want.c_str());
    if (t != want) s_.fail("expected " + want + ", found " + quote(t));
  }

  void skip_section(std::string_view sec) {
    const std::string want = "$End" + std::string(sec.substr(1));
    const long start = s_.line();
    for (;;) {
      const std::string_view t = s_.next();
      if (t.empty()) throw core::InputError(s_.name(), start, "section " + quote(sec, 40) + " has no " + quote(want, 44));
      if (t == want) return;
    }
  }

  void mesh_format() {
    const std::string_view v = s_.token("MSH version");
    if (v != "4.1")
      s_.fail("unsupported MSH version " + quote(v) + " (only 4.1 is read; re-export with gmsh -format msh41)");
    const long long file_type = s_.integer("file type");
    if (file_type == 1) s_.fail("binary MSH files are not supported (only ASCII)");
    if (file_type != 0) s_.fail("bad MSH file type " + std::to_string(file_type));
    s_.integer("data size");
  }

  void entities() {
    std::array<long long, 4> n{};
    for (long long& x : n) {
      x = s_.integer("entity count");
      s_.check_count(x, "entities", 8);
    }
    for (int dim = 0; dim < 4; ++dim)
      for (long long i = 0; i < n[static_cast<std::size_t>(dim)]; ++i) {
        const long long tag = s_.integer("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) s_.real("entity bounding box");
        const long long nphys = s_.integer("number of physical tags");
        s_.check_count(nphys, "physical tags", 2);
        int physical = 0;
        for (long long p = 0; p < nphys; ++p) {
          const long long t = s_.integer("physical tag");
          if (p == 0) {
            if (t < INT_MIN || t > INT_MAX) s_.fail("physical tag out of range");
            physical = static_cast<int>(t);
          }
        }
        if (dim > 0) {
          const long long nb = s_.integer("number of bounding entities");
          s_.check_count(nb, "bounding entities", 2);
          for (long long b = 0; b < nb; ++b) s_.integer("bounding entity tag");
        }
        physical_[{dim, tag}] = physical;
        if (nphys > 0) have_physical_ = true;
      }
  }

  void nodes() {
    if (have_nodes_) s_.fail("second $Nodes section");
    have_nodes_ = true;
    const long long blocks = s_.integer("number of node blocks");
    s_.check_count(blocks, "node blocks", 8);
    const int n = s_.count("nodes", 8);
    s_.integer("min node tag");
    s_.integer("max node tag");
    d_.points.reserve(static_cast<std::size_t>(n));
    std::vector<long long> tags;
    tags.reserve(static_cast<std::size_t>(n));
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = s_.integer("entity dimension");
      if (dim < 0 || dim > 3) s_.fail("bad entity dimension " + std::to_string(dim));
      s_.integer("entity tag");
      const long long parametric = s_.integer("parametric flag");
      const long long m = s_.integer("nodes in block");
      if (m < 0 || m > n - static_cast<long long>(tags.size()))
        s_.fail("node blocks hold more than the " + std::to_string(n) + " nodes declared");
      for (long long i = 0; i < m; ++i) {
        const long long t = s_.integer("node tag");
        if (t < 1) s_.fail("node tag " + std::to_string(t) + " (tags start at 1)");
        tags.push_back(t);
      }
      const long long extra = parametric != 0 ? dim : 0;
      for (long long i = 0; i < m; ++i) {
        core::Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = s_.real("node coordinate");
        for (long long k = 0; k < extra; ++k) s_.real("parametric coordinate");
        d_.points.push_back(p);
      }
    }
    if (static_cast<long long>(tags.size()) != n)
      s_.fail("$Nodes declares " + std::to_string(n) + " nodes, the blocks hold " + std::to_string(tags.size()));
    // Tag -> index: a dense table when tags are compact, a hash map otherwise.
    const long long max_tag = tags.empty() ? 0 : *std::max_element(tags.begin(), tags.end());
    dense_ = max_tag <= 4LL * n + 1024;
    if (dense_) dense_index_.assign(static_cast<std::size_t>(max_tag) + 1, -1);
    for (std::size_t i = 0; i < tags.size(); ++i) {
      int& slot = dense_ ? dense_index_[static_cast<std::size_t>(tags[i])] : sparse_index_[tags[i]];
      if (dense_ ? slot >= 0 : slot != 0) s_.fail("node tag " + std::to_string(tags[i]) + " appears twice");
      slot = dense_ ? static_cast<int>(i) : static_cast<int>(i) + 1;  // sparse: 0 means absent
    }
  }

  int node(long long tag) {
    int i = -1;
    if (dense_) {
      if (tag >= 0 && tag < static_cast<long long>(dense_index_.size())) i = dense_index_[static_cast<std::size_t>(tag)];
    } else {
      const auto it = sparse_index_.find(tag);
      if (it != sparse_index_.end()) i = it->second - 1;
    }
    if (i < 0) s_.fail("element refers to node tag " + std::to_string(tag) + ", which is not in $Nodes");
    return i;
  }

  template <std::size_t N>
  void read_elements(long long m, std::vector<std::array<int, N>>& cells, std::vector<int>& labels, int label,
                     std::vector<long long>& tags) {
    for (long long i = 0; i < m; ++i) {
      tags.push_back(s_.integer("element tag"));
      std::array<int, N> c;
      for (std::size_t k = 0; k < N; ++k) c[k] = node(s_.integer("element node tag"));
      cells.push_back(c);
      if (have_physical_) labels.push_back(label);
    }
  }

  void elements() {
    if (!have_nodes_) s_.fail("$Elements before $Nodes");
    if (have_elements_) s_.fail("second $Elements section");
    have_elements_ = true;
    const long long blocks = s_.integer("number of element blocks");
    s_.check_count(blocks, "element blocks", 8);
    const int n = s_.count("elements", 4);
    s_.integer("min element tag");
    s_.integer("max element tag");
    long long total = 0;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = s_.integer("entity dimension");
      const long long tag = s_.integer("entity tag");
      const long long type = s_.integer("element type");
      const long long m = s_.integer("elements in block");
      if (m < 0 || m > n - total)
        s_.fail("element blocks hold more than the " + std::to_string(n) + " elements declared");
      total += m;
      int label = 0;
      if (have_physical_) {
        const auto it = physical_.find({static_cast<int>(std::clamp(dim, 0LL, 3LL)), tag});
        if (it != physical_.end()) label = it->second;
      }
      switch (type) {
        case 15:  // point elements: nothing to keep
          for (long long i = 0; i < 2 * m; ++i) s_.integer("element tag or node");
          break;
        case 1: read_elements(m, d_.edges, d_.edge_labels, label, tags_[0]); break;
        case 2: read_elements(m, d_.triangles, d_.triangle_labels, label, tags_[1]); break;
        case 3: read_elements(m, d_.quads, d_.quad_labels, label, tags_[2]); break;
        case 4: read_elements(m, d_.tets, d_.tet_labels, label, tags_[3]); break;
        case 5: read_elements(m, d_.hexes, d_.hex_labels, label, tags_[4]); break;
        default:
          s_.fail("unsupported Gmsh element type " + std::to_string(type) + " (" + gmsh_type_name(type) +
                  "); only linear triangles, quads, tets and hexes");
      }
    }
    if (total != n)
      s_.fail("$Elements declares " + std::to_string(n) + " elements, the blocks hold " + std::to_string(total));
    in_tag_order(d_.edges, d_.edge_labels, tags_[0]);
    in_tag_order(d_.triangles, d_.triangle_labels, tags_[1]);
    in_tag_order(d_.quads, d_.quad_labels, tags_[2]);
    in_tag_order(d_.tets, d_.tet_labels, tags_[3]);
    in_tag_order(d_.hexes, d_.hex_labels, tags_[4]);
  }

  //! Elements of one type in the order of their tags: blocks group them by entity (Gmsh's and
  //! our writer's), the tags keep the mesh's own order (which cell data and map files rely on).
  template <class Cell>
  static void in_tag_order(std::vector<Cell>& cells, std::vector<int>& labels, const std::vector<long long>& tags) {
    if (std::is_sorted(tags.begin(), tags.end())) return;
    std::vector<std::size_t> order(tags.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tags[a] < tags[b]; });
    std::vector<Cell> sorted_cells(cells.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted_cells[i] = cells[order[i]];
    cells = std::move(sorted_cells);
    if (labels.empty()) return;
    std::vector<int> sorted_labels(labels.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted_labels[i] = labels[order[i]];
    labels = std::move(sorted_labels);
  }

  Scanner s_;
  core::MeshData d_;
  bool have_nodes_ = false, have_elements_ = false;
  bool have_physical_ = false;  // some entity has a physical tag: elements get labels
  std::map<std::pair<int, long long>, int> physical_;  // (dim, entity tag) -> first physical tag
  std::array<std::vector<long long>, 5> tags_;          // element tags of edges, triangles, quads, tets, hexes
  bool dense_ = true;
  std::vector<int> dense_index_;
  std::unordered_map<long long, int> sparse_index_;
};

}  // namespace

core::MeshData read_msh(std::string_view data, const std::string& name) { return MshReader(data, name).read(); }

std::string write_msh(const core::MeshData& d, const WriteOptions& /*options*/) {
  // Element blocks: one per element type and label, in the order edges, triangles, quads, tets,
  // hexes; each element's tag is its place in that order, so that readers (ours) restore it.
  struct Block {
    int dim, type, label, entity;
    std::vector<std::size_t> cells;  // indices into its element vector, ascending
    std::size_t first_tag;           // tag of the type's first element
  };
  const bool labeled = !d.edge_labels.empty() || !d.triangle_labels.empty() || !d.quad_labels.empty() ||
                       !d.tet_labels.empty() || !d.hex_labels.empty();
  std::vector<Block> blocks;
  std::map<std::pair<int, int>, int> entity_of;  // (dim, label) -> entity tag (per dimension)
  std::array<int, 4> next_entity{1, 1, 1, 1};
  std::size_t first_tag = 1;
  auto group = [&](std::size_t count, const std::vector<int>& labels, int dim, int type) {
    std::map<int, std::vector<std::size_t>> by_label;
    for (std::size_t i = 0; i < count; ++i) by_label[labels.empty() ? 0 : labels[i]].push_back(i);
    for (auto& [label, cells] : by_label) {
      // Unlabeled data: one entity per dimension; labeled: one per (dimension, label).
      const std::pair<int, int> key{dim, labeled ? label : 0};
      auto it = entity_of.find(key);
      if (it == entity_of.end()) it = entity_of.emplace(key, next_entity[static_cast<std::size_t>(dim)]++).first;
      blocks.push_back({dim, type, label, it->second, std::move(cells), first_tag});
    }
    first_tag += count;
  };
  group(d.edges.size(), d.edge_labels, 1, 1);
  group(d.triangles.size(), d.triangle_labels, 2, 2);
  group(d.quads.size(), d.quad_labels, 2, 3);
  group(d.tets.size(), d.tet_labels, 3, 4);
  group(d.hexes.size(), d.hex_labels, 3, 5);
  const int top_dim = !d.tets.empty() || !d.hexes.empty() ? 3 : (!d.triangles.empty() || !d.quads.empty() ? 2 : 1);

  std::string out;
  const std::size_t n_elems = d.edges.size() + d.num_cells();
  out.reserve(d.points.size() * 70 + n_elems * 60);
  TextWriter w(out);
  w << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  {
    // $Entities always: Gmsh refuses element blocks on entities it was not told of. Bounding
    // box of each entity's nodes.
    std::map<std::pair<int, int>, core::BoundingBox> box;  // (dim, entity)
    std::map<std::pair<int, int>, int> label_of;
    auto grow = [&](const Block& b, const auto& cells) {
      auto [it, fresh] = box.try_emplace({b.dim, b.entity});
      for (const std::size_t c : b.cells)
        for (const int v : cells[c]) {
          if (fresh) {
            it->second.min = it->second.max = d.points[static_cast<std::size_t>(v)];
            fresh = false;
          }
          it->second.min = it->second.min.cwiseMin(d.points[static_cast<std::size_t>(v)]);
          it->second.max = it->second.max.cwiseMax(d.points[static_cast<std::size_t>(v)]);
        }
      label_of[{b.dim, b.entity}] = b.label;
    };
    for (const Block& b : blocks) {
      switch (b.type) {
        case 1: grow(b, d.edges); break;
        case 2: grow(b, d.triangles); break;
        case 3: grow(b, d.quads); break;
        case 4: grow(b, d.tets); break;
        default: grow(b, d.hexes); break;
      }
    }
    std::array<int, 4> count{};
    for (const auto& [key, bb] : box) ++count[static_cast<std::size_t>(key.first)];
    w << "$Entities\n0 " << count[1] << ' ' << count[2] << ' ' << count[3] << '\n';
    for (const auto& [key, bb] : box) {
      const int label = label_of[key];
      w << key.second << ' ' << bb.min.x() << ' ' << bb.min.y() << ' ' << bb.min.z() << ' ' << bb.max.x() << ' '
        << bb.max.y() << ' ' << bb.max.z() << ' ';
      // Labeled: every entity carries its label as physical tag, 0 included (meshio expects a
      // physical tag on every element block once one has it); unlabeled: none.
      if (labeled)
        w << "1 " << label << " 0\n";  // no bounding entities
      else
        w << "0 0\n";
    }
    w << "$EndEntities\n";
  }
  const std::size_t np = d.points.size();
  w << "$Nodes\n1 " << np << " 1 " << np << '\n' << top_dim << " 1 0 " << np << '\n';
  for (std::size_t i = 1; i <= np; ++i) w << i << '\n';
  for (const core::Vec3& p : d.points) w << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  w << "$EndNodes\n$Elements\n" << blocks.size() << ' ' << n_elems << " 1 " << n_elems << '\n';
  auto write_block = [&](const Block& b, const auto& cells) {
    w << b.dim << ' ' << b.entity << ' ' << b.type << ' ' << b.cells.size() << '\n';
    for (const std::size_t c : b.cells) {
      w << b.first_tag + c;
      for (const int v : cells[c]) w << ' ' << v + 1;
      w << '\n';
    }
  };
  for (const Block& b : blocks) {
    switch (b.type) {
      case 1: write_block(b, d.edges); break;
      case 2: write_block(b, d.triangles); break;
      case 3: write_block(b, d.quads); break;
      case 4: write_block(b, d.tets); break;
      default: write_block(b, d.hexes); break;
    }
  }
  w << "$EndElements\n";
  return out;
}

}  // namespace polycube::io::detail
