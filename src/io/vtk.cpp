//! Legacy VTK, ASCII, DATASET UNSTRUCTURED_GRID, file versions 2.0 to 5.1 (read; 5.x with its
//! OFFSETS/CONNECTIVITY cell layout, which VTK 9 and ParaView write) and 3.0 (written: 5.1
//! cannot be read by Gmsh 4.8 or HexaLab). Cell types 5
//! (triangle), 9 (quad), 10 (tet), 12 (hex); the vertex orders are those of core/elements.h.
//! POINT_DATA / CELL_DATA: one-component SCALARS (with or without LOOKUP_TABLE) and
//! one-component FIELD arrays become fields; other attributes are skipped. An integer field
//! named "label" carries the element (cell data) or vertex (point data) labels.
//! Binary legacy files are refused.
#include "io/formats.h"
#include "io/parse.h"

#include <algorithm>
#include <cmath>

namespace polycube::io::detail {

namespace {

const char* vtk_cell_name(long long t) {
  switch (t) {
    case 1: return "vertex";
    case 2: return "poly-vertex";
    case 3: return "line";
    case 4: return "poly-line";
    case 6: return "triangle strip";
    case 7: return "polygon";
    case 8: return "pixel";
    case 11: return "voxel";
    case 13: return "wedge";
    case 14: return "pyramid";
    case 21: return "quadratic edge";
    case 22: return "quadratic triangle";
    case 23: return "quadratic quad";
    case 24: return "quadratic tetra";
    case 25: return "quadratic hexahedron";
    default: return "unknown";
  }
}

bool is_int_type(std::string_view t) {
  constexpr std::string_view kInt[] = {"bit",           "unsigned_char", "char",      "unsigned_short", "short",
                                       "unsigned_int",  "int",           "unsigned_long", "long",       "vtkIdType",
                                       "vtktypeint8",   "vtktypeuint8",  "vtktypeint16",  "vtktypeuint16",
                                       "vtktypeint32",  "vtktypeuint32", "vtktypeint64",  "vtktypeuint64",
                                       "signed_char",   "unsigned_long_long", "long_long"};
  for (const std::string_view k : kInt)
    if (iequals(k, t)) return true;
  return false;
}

bool is_data_type(std::string_view t) {
  return is_int_type(t) || iequals(t, "float") || iequals(t, "double") || iequals(t, "vtktypefloat32") ||
         iequals(t, "vtktypefloat64");
}

struct RawField {
  std::string name;
  std::vector<double> values;
  bool integer = false;
};

class VtkReader {
 public:
  VtkReader(std::string_view data, const std::string& name) : s_(data, name) {}

  core::MeshData read() {
    header();
    for (;;) {
      const std::string_view kw = s_.next();
      if (kw.empty()) break;
      if (iequals(kw, "POINTS")) points();
      else if (iequals(kw, "CELLS")) cells();
      else if (iequals(kw, "CELL_TYPES")) cell_types();
      else if (iequals(kw, "POINT_DATA")) attribute_section(false);
      else if (iequals(kw, "CELL_DATA")) attribute_section(true);
      else if (iequals(kw, "FIELD")) field(nullptr, 0);  // dataset field data: skipped
      else if (iequals(kw, "METADATA")) metadata();
      else if (iequals(kw, "OFFSETS") || iequals(kw, "CONNECTIVITY"))
        s_.fail(std::string(kw) + " outside a CELLS section of a version 5 file");
      else s_.fail("unknown VTK keyword " + quote(kw));
    }
    if (!have_points_) s_.fail("no POINTS section");
    if (!have_types_) s_.fail(have_cells_ ? "CELLS without CELL_TYPES" : "no CELLS section");
    finish_fields();
    return std::move(d_);
  }

 private:
  void header() {
    const std::string_view l1 = s_.rest_of_line();
    constexpr std::string_view kMagic = "# vtk DataFile Version";
    if (l1.size() < kMagic.size() || !iequals(l1.substr(0, kMagic.size()), kMagic))
      s_.fail("not a legacy VTK file (first line " + quote(l1, 40) + ")");
    Scanner v(l1.substr(kMagic.size()), s_.name());
    const std::string_view vt = v.next();
    double version = 0.0;
    if (!parse_double(vt, version)) s_.fail("bad VTK version " + quote(vt));
    if (version >= 6.0 || version < 2.0)
      s_.fail("VTK file version " + std::string(vt) + " is not supported (legacy 2.0 to 5.1 only)");
    offsets_layout_ = version >= 5.0;
    s_.rest_of_line();  // title
    const std::string_view enc = s_.rest_of_line();
    if (iequals(enc, "BINARY")) s_.fail("binary VTK files are not supported (only ASCII)");
    if (!iequals(enc, "ASCII")) s_.fail("expected 'ASCII', found " + quote(enc));
    const std::string_view ds = s_.token("DATASET");
    if (!iequals(ds, "DATASET")) s_.fail("expected 'DATASET', found " + quote(ds));
    const std::string_view type = s_.token("dataset type");
    if (!iequals(type, "UNSTRUCTURED_GRID"))
      s_.fail("unsupported VTK dataset " + quote(type) + " (only UNSTRUCTURED_GRID)");
  }

  void points() {
    if (have_points_) s_.fail("second POINTS section");
    have_points_ = true;
    const int n = s_.count("points", 5);
    const std::string_view type = s_.token("point data type");
    if (!is_data_type(type)) s_.fail("unknown VTK data type " + quote(type));
    d_.points.resize(static_cast<std::size_t>(n));
    for (core::Vec3& p : d_.points)
      for (int k = 0; k < 3; ++k) p[k] = s_.real("point coordinate");
  }

  void cells() {
    if (!have_points_) s_.fail("CELLS before POINTS");
    if (have_cells_) s_.fail("second CELLS section");
    have_cells_ = true;
    if (offsets_layout_) return offsets_and_connectivity();
    n_cells_ = s_.count("cells", 4);
    const int size = s_.count("cell list size", 2);
    conn_.reserve(static_cast<std::size_t>(size));
    starts_.reserve(static_cast<std::size_t>(n_cells_) + 1);
    const auto np = static_cast<long long>(d_.points.size());
    for (int c = 0; c < n_cells_; ++c) {
      starts_.push_back(conn_.size());
      const long long k = s_.integer("cell vertex count");
      if (k < 1 || k > 1000) s_.fail("cell " + std::to_string(c) + " has " + std::to_string(k) + " vertices");
      if (conn_.size() + static_cast<std::size_t>(k) + static_cast<std::size_t>(c) + 1 > static_cast<std::size_t>(size))
        s_.fail("cell list longer than its declared size " + std::to_string(size));
      for (long long i = 0; i < k; ++i) conn_.push_back(s_.index(np, 0));
    }
    starts_.push_back(conn_.size());
    if (conn_.size() + static_cast<std::size_t>(n_cells_) != static_cast<std::size_t>(size))
      s_.fail("CELLS declares size " + std::to_string(size) + " but the list has " +
              std::to_string(conn_.size() + static_cast<std::size_t>(n_cells_)) + " numbers");
  }

  //! Version 5's cells: "CELLS n_offsets n_connectivity", then OFFSETS (n_cells + 1 ascending
  //! positions, the first 0) and CONNECTIVITY (the vertex indices), each with its data type.
  void offsets_and_connectivity() {
    const int n_offsets = s_.count("offsets", 2);
    const int n_conn = s_.count("connectivity entries", 2);
    n_cells_ = std::max(n_offsets - 1, 0);
    array_header("OFFSETS");
    starts_.reserve(static_cast<std::size_t>(n_offsets));
    for (int i = 0; i < n_offsets; ++i) {
      const long long at = s_.integer("cell offset");
      if (at < (starts_.empty() ? 0 : static_cast<long long>(starts_.back())) || at > n_conn || (i == 0 && at != 0))
        s_.fail("OFFSETS are not ascending from 0 to " + std::to_string(n_conn) + " (offset " + std::to_string(i) + " is " +
                std::to_string(at) + ")");
      starts_.push_back(static_cast<std::size_t>(at));
    }
    if (n_offsets > 0 && starts_.back() != static_cast<std::size_t>(n_conn))
      s_.fail("the last offset is " + std::to_string(starts_.back()) + ", not the connectivity size " + std::to_string(n_conn));
    if (starts_.empty()) starts_.push_back(0);
    array_header("CONNECTIVITY");
    conn_.reserve(static_cast<std::size_t>(n_conn));
    const auto np = static_cast<long long>(d_.points.size());
    for (int i = 0; i < n_conn; ++i) conn_.push_back(s_.index(np, 0));
  }

  //! "OFFSETS vtktypeint64" and the like: the keyword, then an integer type.
  void array_header(const char* keyword) {
    const std::string_view kw = s_.token(keyword);
    if (!iequals(kw, keyword)) s_.fail(std::string("expected ") + keyword + ", found " + quote(kw));
    const std::string_view type = s_.token("array type");
    if (!is_int_type(type)) s_.fail(std::string(keyword) + " has type " + quote(type) + ", not an integer type");
  }

  void cell_types() {
    if (!have_cells_) s_.fail("CELL_TYPES before CELLS");
    if (have_types_) s_.fail("second CELL_TYPES section");
    have_types_ = true;
    const long long n = s_.integer("cell count");
    if (n != n_cells_)
      s_.fail("CELL_TYPES has " + std::to_string(n) + " cells, CELLS has " + std::to_string(n_cells_));
    std::vector<int> type(static_cast<std::size_t>(n_cells_));
    std::array<int, 4> count{};  // triangles, quads, tets, hexes
    for (int c = 0; c < n_cells_; ++c) {
      const long long t = s_.integer("cell type");
      int block = -1, nv = 0;
      switch (t) {
        case 5: block = 0, nv = 3; break;
        case 9: block = 1, nv = 4; break;
        case 10: block = 2, nv = 4; break;
        case 12: block = 3, nv = 8; break;
        default:
          s_.fail("unsupported VTK cell type " + std::to_string(t) + " (" + vtk_cell_name(t) +
                  "); only triangles (5), quads (9), tets (10) and hexes (12)");
      }
      const std::size_t k = starts_[static_cast<std::size_t>(c) + 1] - starts_[static_cast<std::size_t>(c)];
      if (static_cast<int>(k) != nv)
        s_.fail("cell " + std::to_string(c) + " of type " + std::to_string(t) + " has " + std::to_string(k) +
                " vertices instead of " + std::to_string(nv));
      type[static_cast<std::size_t>(c)] = block;
      ++count[static_cast<std::size_t>(block)];
    }
    // Cells go to their blocks in file order; cell data are reordered to match (see types.h).
    std::array<int, 4> offset{0, count[0], count[0] + count[1], count[0] + count[1] + count[2]};
    std::array<int, 4> next = offset;
    cell_order_.resize(static_cast<std::size_t>(n_cells_));
    for (int c = 0; c < n_cells_; ++c) {
      const int* v = conn_.data() + starts_[static_cast<std::size_t>(c)];
      const auto b = static_cast<std::size_t>(type[static_cast<std::size_t>(c)]);
      cell_order_[static_cast<std::size_t>(c)] = next[b]++;
      switch (b) {
        case 0: d_.triangles.push_back({v[0], v[1], v[2]}); break;
        case 1: d_.quads.push_back({v[0], v[1], v[2], v[3]}); break;
        case 2: d_.tets.push_back({v[0], v[1], v[2], v[3]}); break;
        default: d_.hexes.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]}); break;
      }
    }
    conn_ = {};
    starts_ = {};
  }

  //! POINT_DATA n or CELL_DATA n, then its attributes until the next section.
  void attribute_section(bool cell) {
    const long long n = s_.integer("attribute count");
    const long long expected = cell ? (have_types_ ? n_cells_ : -1) : static_cast<long long>(d_.points.size());
    if (cell && !have_types_) s_.fail("CELL_DATA before CELLS and CELL_TYPES");
    if (!cell && !have_points_) s_.fail("POINT_DATA before POINTS");
    if (n != expected)
      s_.fail(std::string(cell ? "CELL_DATA" : "POINT_DATA") + " has " + std::to_string(n) + " values for " +
              std::to_string(expected) + (cell ? " cells" : " points"));
    std::vector<RawField>& out = cell ? cell_fields_ : point_fields_;
    for (;;) {
      // Peek: stop at anything that is not an attribute of this section.
      const std::size_t pos = s_.offset();
      const long line = s_.current_line();
      const std::string_view kw = s_.next();
      if (kw.empty()) return;
      if (iequals(kw, "SCALARS")) {
        scalars(out, n);
      } else if (iequals(kw, "FIELD")) {
        field(&out, n);
      } else if (iequals(kw, "LOOKUP_TABLE")) {
        s_.token("lookup table name");
        skip_values(s_.count("lookup table size", 8) * 4LL);
      } else if (iequals(kw, "COLOR_SCALARS")) {
        s_.token("attribute name");
        skip_values(n * small(s_.integer("number of colour components"), 1, 4, "colour components"));
      } else if (iequals(kw, "VECTORS") || iequals(kw, "NORMALS")) {
        s_.token("attribute name");
        data_type();
        skip_values(3 * n);
      } else if (iequals(kw, "TENSORS") || iequals(kw, "TENSORS6")) {
        s_.token("attribute name");
        data_type();
        skip_values((iequals(kw, "TENSORS") ? 9 : 6) * n);
      } else if (iequals(kw, "TEXTURE_COORDINATES")) {
        s_.token("attribute name");
        const long long dim = small(s_.integer("texture dimension"), 1, 3, "texture dimension");
        data_type();
        skip_values(dim * n);
      } else if (iequals(kw, "GLOBAL_IDS") || iequals(kw, "PEDIGREE_IDS")) {
        s_.token("attribute name");
        data_type();
        skip_values(n);
      } else if (iequals(kw, "METADATA")) {
        metadata();
      } else {
        s_.seek(pos, line);
        return;
      }
    }
  }

  //! A small header number checked against its allowed range.
  long long small(long long v, long long lo, long long hi, const char* what) const {
    if (v < lo || v > hi)
      s_.fail(std::string(what) + " " + std::to_string(v) + " out of range (" + std::to_string(lo) + ".." +
              std::to_string(hi) + ")");
    return v;
  }

  std::string_view data_type() {
    const std::string_view t = s_.token("data type");
    if (!is_data_type(t)) s_.fail("unknown VTK data type " + quote(t));
    return t;
  }

  void skip_values(long long n) {
    s_.check_count(n, "values", 2);
    for (long long i = 0; i < n; ++i) s_.real("attribute value");
  }

  std::vector<double> values(long long n) {
    s_.check_count(n, "values", 2);
    std::vector<double> v(static_cast<std::size_t>(n));
    for (double& x : v) x = s_.real("attribute value");
    return v;
  }

  void scalars(std::vector<RawField>& out, long long n) {
    RawField f;
    f.name = std::string(s_.token("scalar name"));
    f.integer = is_int_type(data_type());
    long long ncomp = 1;
    const std::string_view c = s_.next_on_line();
    if (!c.empty()) {
      ncomp = s_.integer(c, "number of components");
      if (ncomp < 1 || ncomp > 4) s_.fail("SCALARS with " + std::to_string(ncomp) + " components (1 to 4 allowed)");
    }
    // LOOKUP_TABLE is mandatory in the format but often missing: accept both.
    const std::size_t pos = s_.offset();
    const long line = s_.current_line();
    const std::string_view lt = s_.next();
    if (iequals(lt, "LOOKUP_TABLE"))
      s_.token("lookup table name");
    else
      s_.seek(pos, line);
    if (ncomp != 1) {
      skip_values(n * ncomp);
      return;
    }
    f.values = values(n);
    out.push_back(std::move(f));
  }

  //! FIELD name numArrays; each array: name numComponents numTuples type, values.
  //! One-component arrays with \p n tuples go to \p out (when given), the others are skipped.
  void field(std::vector<RawField>* out, long long n) {
    s_.token("field name");
    const long long arrays = s_.integer("number of arrays");
    s_.check_count(arrays, "arrays", 8);
    for (long long a = 0; a < arrays; ++a) {
      RawField f;
      f.name = std::string(s_.token("array name"));
      const long long ncomp = s_.integer("number of components");
      const long long tuples = s_.integer("number of tuples");
      if (ncomp < 0 || tuples < 0) s_.fail("negative array size");
      f.integer = is_int_type(data_type());
      if (ncomp > 0 && tuples > (1LL << 40) / ncomp) s_.fail("array too large");
      if (out != nullptr && ncomp == 1 && tuples == n) {
        f.values = values(n);
        out->push_back(std::move(f));
      } else {
        skip_values(ncomp * tuples);
      }
      // VTK >= 8 may follow an array with METADATA.
      const std::size_t pos = s_.offset();
      const long line = s_.current_line();
      if (iequals(s_.next(), "METADATA"))
        metadata();
      else
        s_.seek(pos, line);
    }
  }

  //! METADATA blocks end at the first empty line.
  void metadata() {
    s_.rest_of_line();
    while (s_.remaining() > 0 && !s_.rest_of_line().empty()) {
    }
  }

  void finish_fields() {
    auto is_label = [](const RawField& f) {
      if (f.name != kLabelField || !f.integer) return false;
      for (const double v : f.values)
        if (v != std::floor(v) || std::abs(v) > 2147483647.0) return false;
      return true;
    };
    for (RawField& f : point_fields_) {
      if (is_label(f) && d_.point_labels.empty())
        d_.point_labels.assign(f.values.begin(), f.values.end());
      else
        d_.point_data.push_back({std::move(f.name), std::move(f.values)});
    }
    for (RawField& f : cell_fields_) {
      std::vector<double> v(f.values.size());
      for (std::size_t c = 0; c < v.size(); ++c) v[static_cast<std::size_t>(cell_order_[c])] = f.values[c];
      if (is_label(f) && d_.triangle_labels.empty() && d_.quad_labels.empty() && d_.tet_labels.empty() &&
          d_.hex_labels.empty()) {
        std::size_t at = 0;
        auto take = [&](std::vector<int>& labels, std::size_t count) {
          labels.assign(v.begin() + static_cast<std::ptrdiff_t>(at), v.begin() + static_cast<std::ptrdiff_t>(at + count));
          at += count;
        };
        take(d_.triangle_labels, d_.triangles.size());
        take(d_.quad_labels, d_.quads.size());
        take(d_.tet_labels, d_.tets.size());
        take(d_.hex_labels, d_.hexes.size());
      } else {
        d_.cell_data.push_back({std::move(f.name), std::move(v)});
      }
    }
  }

  Scanner s_;
  core::MeshData d_;
  bool offsets_layout_ = false;  // version 5: OFFSETS/CONNECTIVITY after CELLS
  bool have_points_ = false, have_cells_ = false, have_types_ = false;
  int n_cells_ = 0;
  std::vector<int> conn_;
  std::vector<std::size_t> starts_;
  std::vector<int> cell_order_;  // file cell -> index in the MeshData cell order
  std::vector<RawField> point_fields_, cell_fields_;
};

//! A field name VTK can read back (no whitespace).
std::string vtk_name(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (static_cast<unsigned char>(c) <= 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '_';
  return s;
}

}  // namespace

core::MeshData read_vtk(std::string_view data, const std::string& name) { return VtkReader(data, name).read(); }

std::string write_vtk(const core::MeshData& d, const WriteOptions& /*options*/) {
  std::string out;
  const std::size_t nc = d.num_cells();
  out.reserve(d.points.size() * 64 + nc * 48 + (d.point_data.size() * d.points.size() + d.cell_data.size() * nc) * 20);
  TextWriter w(out);
  w << "# vtk DataFile Version 3.0\npolycube mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  w << "POINTS " << d.points.size() << " double\n";
  for (const core::Vec3& p : d.points) w << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  const std::size_t size = nc + 3 * d.triangles.size() + 4 * d.quads.size() + 4 * d.tets.size() + 8 * d.hexes.size();
  w << "CELLS " << nc << ' ' << size << '\n';
  auto cells = [&](const auto& block) {
    for (const auto& c : block) {
      w << c.size();
      for (const int v : c) w << ' ' << v;
      w << '\n';
    }
  };
  cells(d.triangles);
  cells(d.quads);
  cells(d.tets);
  cells(d.hexes);
  w << "CELL_TYPES " << nc << '\n';
  auto types = [&](std::size_t n, const char* t) {
    for (std::size_t i = 0; i < n; ++i) w << t;
  };
  types(d.triangles.size(), "5\n");
  types(d.quads.size(), "9\n");
  types(d.tets.size(), "10\n");
  types(d.hexes.size(), "12\n");

  auto scalars = [&](const std::string& fname, const char* type, auto&& value, std::size_t n) {
    w << "SCALARS " << vtk_name(fname) << ' ' << type << " 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) w << value(i) << '\n';
  };
  // A user field literally named "label" would clash with the labels on reading.
  auto field_name = [](const std::string& n, bool labels) { return labels && n == kLabelField ? n + "_data" : n; };

  const bool cell_labels = !d.triangle_labels.empty() || !d.quad_labels.empty() || !d.tet_labels.empty() ||
                           !d.hex_labels.empty();
  if (cell_labels || !d.cell_data.empty()) {
    w << "CELL_DATA " << nc << '\n';
    if (cell_labels) {
      std::vector<int> labels;
      labels.reserve(nc);
      auto add = [&](const std::vector<int>& l, std::size_t n) {
        if (l.empty())
          labels.insert(labels.end(), n, 0);
        else
          labels.insert(labels.end(), l.begin(), l.end());
      };
      add(d.triangle_labels, d.triangles.size());
      add(d.quad_labels, d.quads.size());
      add(d.tet_labels, d.tets.size());
      add(d.hex_labels, d.hexes.size());
      scalars(kLabelField, "int", [&](std::size_t i) { return labels[i]; }, nc);
    }
    for (const core::Field& f : d.cell_data)
      scalars(field_name(f.name, cell_labels), "double", [&](std::size_t i) { return f.values[i]; }, nc);
  }
  const bool point_labels = !d.point_labels.empty();
  if (point_labels || !d.point_data.empty()) {
    w << "POINT_DATA " << d.points.size() << '\n';
    if (point_labels)
      scalars(kLabelField, "int", [&](std::size_t i) { return d.point_labels[i]; }, d.points.size());
    for (const core::Field& f : d.point_data)
      scalars(field_name(f.name, point_labels), "double", [&](std::size_t i) { return f.values[i]; },
              d.points.size());
  }
  return out;
}

}  // namespace polycube::io::detail
