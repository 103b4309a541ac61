//! PLY, ASCII and binary (little- or big-endian). Reads the `vertex` element's x, y, z (any
//! numeric type) and the `face` element's `vertex_indices` (or `vertex_index`) list (any
//! integer types); the other scalar properties of these two elements become point and cell
//! data, list properties and other elements are skipped. Triangles and quads are kept, larger
//! polygons fan-triangulated. Written as ASCII with double coordinates and fields, or binary
//! little-endian (WriteOptions::binary) with float ones (double with
//! WriteOptions::double_precision); a uchar/int face list; the colour channels red, green,
//! blue, alpha as uchar (0..255) so that MeshLab and ParaView show them as vertex or face colours.
#include "core/log.h"
#include "io/formats.h"
#include "io/parse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string_view>

namespace polycube::io::detail {

namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_type(std::string_view s, Type& t) {
  if (s == "char" || s == "int8") t = Type::Int8;
  else if (s == "uchar" || s == "uint8") t = Type::UInt8;
  else if (s == "short" || s == "int16") t = Type::Int16;
  else if (s == "ushort" || s == "uint16") t = Type::UInt16;
  else if (s == "int" || s == "int32") t = Type::Int32;
  else if (s == "uint" || s == "uint32") t = Type::UInt32;
  else if (s == "float" || s == "float32") t = Type::Float32;
  else if (s == "double" || s == "float64") t = Type::Float64;
  else return false;
  return true;
}

std::size_t size_of(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 1;
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool is_list = false;
  Type count_type = Type::UInt8;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> props;
  long line = 0;
};

enum class Encoding { Ascii, BinaryLE, BinaryBE };

//! Reads one value of any PLY type from ASCII tokens or binary bytes, as a double.
class ValueReader {
 public:
  ValueReader(std::string_view data, const std::string& name, std::size_t start, long start_line, Encoding enc)
      : enc_(enc), scan_(data, name), bytes_(data, name, start) {
    scan_.seek(start, start_line);
  }
  double real(Type t, const char* what) {
    if (enc_ == Encoding::Ascii) return scan_.real(what);
    const bool swap = enc_ == Encoding::BinaryBE;
    double v = 0.0;
    switch (t) {
      case Type::Int8: v = bytes_.get<std::int8_t>(what, swap); break;
      case Type::UInt8: v = bytes_.get<std::uint8_t>(what, swap); break;
      case Type::Int16: v = bytes_.get<std::int16_t>(what, swap); break;
      case Type::UInt16: v = bytes_.get<std::uint16_t>(what, swap); break;
      case Type::Int32: v = bytes_.get<std::int32_t>(what, swap); break;
      case Type::UInt32: v = bytes_.get<std::uint32_t>(what, swap); break;
      case Type::Float32: v = bytes_.get<float>(what, swap); break;
      case Type::Float64: v = bytes_.get<double>(what, swap); break;
    }
    if (!std::isfinite(v)) bytes_.fail(std::string(what) + " is not finite (NaN or Inf)");
    return v;
  }
  long long integer(Type t, const char* what) {
    if (enc_ == Encoding::Ascii) return scan_.integer(what);
    return static_cast<long long>(real(t, what));  // every integer type fits a double exactly
  }
  void skip(Type t) {
    if (enc_ == Encoding::Ascii)
      scan_.token("property value");
    else
      bytes_.skip(size_of(t), "property value");
  }
  //! A list length, checked against what is left of the file.
  int list_count(Type t) {
    const long long n = integer(t, "list length");
    const std::size_t item = enc_ == Encoding::Ascii ? 2 : 1;
    if (n < 0) fail("negative list length " + std::to_string(n));
    if (static_cast<unsigned long long>(n) > remaining() / item + 1)
      fail("list length " + std::to_string(n) + " is more than the rest of the file can hold");
    return static_cast<int>(n);
  }
  [[nodiscard]] std::size_t remaining() const {
    return enc_ == Encoding::Ascii ? scan_.remaining() : bytes_.remaining();
  }
  [[noreturn]] void fail(const std::string& what) const {
    if (enc_ == Encoding::Ascii) scan_.fail(what);
    bytes_.fail(what);
  }
  Scanner& scanner() { return scan_; }

 private:
  Encoding enc_;
  Scanner scan_;
  ByteReader bytes_;
};

//! Refuse an element count the rest of the file cannot hold, before anything is allocated.
void check_count(const Element& e, Encoding enc, const ValueReader& in, const std::string& name) {
  std::size_t min_bytes = 0;  // per element instance
  for (const Property& p : e.props)
    min_bytes += enc == Encoding::Ascii ? 2 : (p.is_list ? size_of(p.count_type) : size_of(p.type));
  if (min_bytes == 0 && e.count > 0)
    throw core::InputError(name, e.line, "element '" + e.name + "' has no properties");
  if (e.count > 0x7fffffff || static_cast<unsigned long long>(e.count) >
                                  in.remaining() / std::max<std::size_t>(min_bytes, 1) + 1)
    throw core::InputError(name, e.line,
                           "declared " + std::to_string(e.count) + " '" + e.name +
                               "' elements, more than the rest of the file (" +
                               std::to_string(in.remaining()) + " bytes) can hold");
}

//! Skip one value of any property, list or not.
void skip_property(ValueReader& in, const Property& p) {
  if (p.is_list)
    for (int j = in.list_count(p.count_type); j > 0; --j) in.skip(p.type);
  else
    in.skip(p.type);
}

//! The scalar properties of an element that are not \p reserved ones, read as fields, and for
//! each property its field (-1: a list or a reserved property).
struct FieldColumns {
  std::vector<int> field_of;
  std::vector<core::Field> fields;
};

FieldColumns field_columns(const Element& e, std::initializer_list<std::string_view> reserved) {
  FieldColumns c;
  for (const Property& p : e.props) {
    const bool is_reserved = std::find(reserved.begin(), reserved.end(), p.name) != reserved.end();
    if (p.is_list || is_reserved) {
      c.field_of.push_back(-1);
      continue;
    }
    c.field_of.push_back(static_cast<int>(c.fields.size()));
    c.fields.push_back({p.name, {}});
    c.fields.back().values.reserve(static_cast<std::size_t>(e.count));
  }
  return c;
}

//! The vertex element: x, y, z as points, every other scalar property as point data.
void read_vertices(const Element& e, ValueReader& in, const std::string& name, core::MeshData& d) {
  int ix = -1, iy = -1, iz = -1;
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    const Property& p = e.props[k];
    if (p.is_list) continue;
    if (p.name == "x") ix = static_cast<int>(k);
    if (p.name == "y") iy = static_cast<int>(k);
    if (p.name == "z") iz = static_cast<int>(k);
  }
  if (ix < 0 || iy < 0 || iz < 0)
    throw core::InputError(name, e.line, "vertex element lacks x, y or z");
  FieldColumns columns = field_columns(e, {"x", "y", "z"});
  d.points.resize(static_cast<std::size_t>(e.count));
  for (core::Vec3& pt : d.points)
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      const int ik = static_cast<int>(k);
      if (ik == ix || ik == iy || ik == iz)
        pt[ik == ix ? 0 : ik == iy ? 1 : 2] = in.real(p.type, "vertex coordinate");
      else if (const int f = columns.field_of[k]; f >= 0)
        columns.fields[static_cast<std::size_t>(f)].values.push_back(
            in.real(p.type, "vertex property"));
      else
        skip_property(in, p);
    }
  d.point_data = std::move(columns.fields);
}

//! The face element: the vertex_indices list as polygons (triangles and quads kept, larger
//! polygons fanned), every scalar property as cell data. A fanned polygon's value goes to each
//! of its triangles, and the values follow the MeshData cell order: triangles, then quads.
void read_faces(const Element& e, ValueReader& in, const std::string& name, long long n_vertices,
                core::MeshData& d) {
  int il = -1;
  for (std::size_t k = 0; k < e.props.size(); ++k)
    if (e.props[k].is_list &&
        (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
      il = static_cast<int>(k);
  if (il < 0) throw core::InputError(name, e.line, "face element has no vertex_indices list");
  if (!is_integer(e.props[static_cast<std::size_t>(il)].type))
    throw core::InputError(name, e.line, "face vertex_indices must be of an integer type");
  FieldColumns columns = field_columns(e, {});
  const std::size_t n_fields = columns.fields.size();
  std::vector<double> face_values(n_fields);
  std::vector<std::vector<double>> quad_values(n_fields);  // triangles' go to columns.fields
  std::vector<int> poly;
  for (long long f = 0; f < e.count; ++f) {
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (static_cast<int>(k) == il) {
        const int n = in.list_count(p.count_type);
        if (n < 3)
          in.fail("face " + std::to_string(f) + " has " + std::to_string(n) +
                  " vertices (at least 3 needed)");
        poly.resize(static_cast<std::size_t>(n));
        for (int& v : poly) {
          const long long idx = in.integer(p.type, "vertex index");
          if (idx < 0 || idx >= n_vertices)
            in.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(idx) +
                    " out of range (0.." + std::to_string(n_vertices - 1) + ")");
          v = static_cast<int>(idx);
        }
      } else if (const int fi = columns.field_of[k]; fi >= 0) {
        face_values[static_cast<std::size_t>(fi)] = in.real(p.type, "face property");
      } else {
        skip_property(in, p);
      }
    }
    const std::size_t triangles_before = d.triangles.size(), quads_before = d.quads.size();
    add_polygon(d, poly);
    for (std::size_t fi = 0; fi < n_fields; ++fi) {
      columns.fields[fi].values.insert(columns.fields[fi].values.end(),
                                       d.triangles.size() - triangles_before, face_values[fi]);
      quad_values[fi].insert(quad_values[fi].end(), d.quads.size() - quads_before, face_values[fi]);
    }
  }
  for (std::size_t fi = 0; fi < n_fields; ++fi)
    columns.fields[fi].values.insert(columns.fields[fi].values.end(), quad_values[fi].begin(),
                                     quad_values[fi].end());
  d.cell_data = std::move(columns.fields);
}

// --- writing ------------------------------------------------------------------------------

//! PLY's colour channels: written as uchar 0..255, the convention MeshLab and ParaView read.
bool is_colour_channel(std::string_view name) {
  return name == "red" || name == "green" || name == "blue" || name == "alpha";
}

bool all_bytes(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(),
                     [](double v) { return v >= 0.0 && v <= 255.0 && v == std::floor(v); });
}

//! How one field is written: its property name, uchar (a colour channel) or double.
struct OutProperty {
  std::string name;
  bool uchar = false;
  const std::vector<double>* values = nullptr;
};

//! The properties for the fields of one element. Names become single tokens; a name that is
//! one of the element's own properties gets "_data" appended. A colour channel whose values
//! are not all integers in 0..255 is written as double, with a warning (viewers will not show it).
std::vector<OutProperty> out_properties(const std::vector<core::Field>& fields,
                                        std::initializer_list<std::string_view> reserved,
                                        const char* element) {
  std::vector<OutProperty> out;
  for (const core::Field& f : fields) {
    OutProperty p;
    p.name = f.name;
    for (char& c : p.name)
      if (static_cast<unsigned char>(c) <= 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '_';
    if (std::find(reserved.begin(), reserved.end(), p.name) != reserved.end()) p.name += "_data";
    p.values = &f.values;
    if (is_colour_channel(p.name)) {
      p.uchar = all_bytes(f.values);
      if (!p.uchar)
        core::logger().warn(
            "PLY {} colour '{}' has values that are not integers in 0..255; written as double",
            element, p.name);
    }
    out.push_back(std::move(p));
  }
  return out;
}

//! How the real numbers go out: ASCII text, or binary float or double.
enum class Reals { Text, Float, Double };

void put_real(std::string& out, Reals reals, double v) {
  if (reals == Reals::Float)
    put_bytes(out, static_cast<float>(v));
  else
    put_bytes(out, v);
}

void write_header(TextWriter& w, const core::MeshData& d, Reals reals,
                  const std::vector<OutProperty>& vertex, const std::vector<OutProperty>& face) {
  const char* real = reals == Reals::Float ? "float " : "double ";
  w << "ply\nformat " << (reals == Reals::Text ? "ascii" : "binary_little_endian") << " 1.0\n"
    << "comment written by polycube\n"
    << "element vertex " << d.points.size() << "\nproperty " << real << "x\nproperty " << real
    << "y\nproperty " << real << "z\n";
  for (const OutProperty& p : vertex)
    w << "property " << (p.uchar ? "uchar " : real) << p.name << '\n';
  w << "element face " << d.triangles.size() + d.quads.size()
    << "\nproperty list uchar int vertex_indices\n";
  for (const OutProperty& p : face)
    w << "property " << (p.uchar ? "uchar " : real) << p.name << '\n';
  w << "end_header\n";
}

//! The values of entity \p i (a vertex or a face), after what is already written of it.
void write_values(std::string& out, Reals reals, const std::vector<OutProperty>& props,
                  std::size_t i) {
  TextWriter w(out);
  const bool binary = reals != Reals::Text;
  for (const OutProperty& p : props) {
    const double v = (*p.values)[i];
    if (binary && p.uchar)
      put_bytes(out, static_cast<std::uint8_t>(v));
    else if (binary)
      put_real(out, reals, v);
    else if (p.uchar)
      w << ' ' << static_cast<int>(v);
    else
      w << ' ' << v;
  }
}

template <std::size_t N>
void write_face(std::string& out, bool binary, const std::array<int, N>& f) {
  if (binary) {
    put_bytes(out, static_cast<std::uint8_t>(N));
    for (const int v : f) put_bytes(out, static_cast<std::int32_t>(v));
    return;
  }
  TextWriter w(out);
  w << static_cast<int>(N);
  for (const int v : f) w << ' ' << v;
}

}  // namespace

core::MeshData read_ply(std::string_view data, const std::string& name) {
  Scanner s(data, name);
  // --- header, line by line
  if (s.rest_of_line() != "ply") s.fail("not a PLY file (first line is not 'ply')");
  Encoding enc = Encoding::Ascii;
  bool have_format = false;
  std::vector<Element> elements;
  for (;;) {
    if (s.remaining() == 0) s.fail("unexpected end of file in the PLY header (no 'end_header')");
    const std::string_view line = s.rest_of_line();
    Scanner words(line, name);
    const std::string_view kw = words.next();
    auto word = [&](const char* what) {
      const std::string_view w = words.next();
      if (w.empty()) s.fail(std::string("PLY header line ends early (expected ") + what + ")");
      return w;
    };
    if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
    if (kw == "end_header") break;
    if (kw == "format") {
      const std::string_view f = word("format");
      if (f == "ascii") enc = Encoding::Ascii;
      else if (f == "binary_little_endian") enc = Encoding::BinaryLE;
      else if (f == "binary_big_endian") enc = Encoding::BinaryBE;
      else s.fail("unknown PLY format " + quote(f));
      const std::string_view v = word("version");
      if (v != "1.0") s.fail("unsupported PLY version " + quote(v) + " (only 1.0)");
      have_format = true;
    } else if (kw == "element") {
      Element e;
      e.name = std::string(word("element name"));
      long long n = 0;
      const std::string_view c = word("element count");
      if (!parse_int64(c, n) || n < 0) s.fail("bad element count " + quote(c));
      e.count = n;
      e.line = s.line();
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) s.fail("'property' before any 'element'");
      Property p;
      std::string_view t = word("property type");
      if (t == "list") {
        p.is_list = true;
        const std::string_view ct = word("list count type");
        if (!parse_type(ct, p.count_type) || !is_integer(p.count_type))
          s.fail("bad PLY list count type " + quote(ct));
        t = word("list item type");
      }
      if (!parse_type(t, p.type)) s.fail("unknown PLY property type " + quote(t));
      p.name = std::string(word("property name"));
      elements.back().props.push_back(std::move(p));
    } else {
      s.fail("unknown PLY header line " + quote(line, 40));
    }
    if (const std::string_view extra = words.next(); !extra.empty())
      s.fail("unexpected " + quote(extra) + " at the end of a PLY header line");
  }
  if (!have_format) s.fail("PLY header has no 'format' line");

  // --- body
  ValueReader in(data, name, s.offset(), s.current_line(), enc);
  core::MeshData d;
  long long n_vertices = -1;
  bool have_faces = false;
  for (const Element& e : elements) {
    check_count(e, enc, in, name);
    if (e.name == "vertex") {
      if (n_vertices >= 0) throw core::InputError(name, e.line, "second vertex element");
      n_vertices = e.count;
      read_vertices(e, in, name, d);
    } else if (e.name == "face") {
      if (n_vertices < 0) throw core::InputError(name, e.line, "face element before the vertex element");
      if (have_faces) throw core::InputError(name, e.line, "second face element");
      have_faces = true;
      read_faces(e, in, name, n_vertices, d);
    } else {
      for (long long i = 0; i < e.count; ++i)
        for (const Property& p : e.props) skip_property(in, p);
    }
  }
  return d;
}

std::string write_ply(const core::MeshData& d, const WriteOptions& options) {
  const bool binary = options.binary;
  const Reals reals = !binary ? Reals::Text : options.double_precision ? Reals::Double : Reals::Float;
  const std::vector<OutProperty> vertex = out_properties(d.point_data, {"x", "y", "z"}, "vertex");
  const std::vector<OutProperty> face = out_properties(d.cell_data, {"vertex_indices"}, "face");
  std::string out;
  out.reserve(d.points.size() * (binary ? 24 : 64) * (1 + vertex.size() / 3) +
              d.num_cells() * (32 + 16 * face.size()));
  TextWriter w(out);
  write_header(w, d, reals, vertex, face);
  for (std::size_t v = 0; v < d.points.size(); ++v) {
    const core::Vec3& p = d.points[v];
    if (binary)
      for (int k = 0; k < 3; ++k) put_real(out, reals, p[k]);
    else
      w << p.x() << ' ' << p.y() << ' ' << p.z();
    write_values(out, reals, vertex, v);
    if (!binary) w << '\n';
  }
  // Faces in the MeshData cell order (triangles, then quads), which the cell data follow.
  std::size_t cell = 0;
  auto face_line = [&](const auto& f) {
    write_face(out, binary, f);
    write_values(out, reals, face, cell++);
    if (!binary) w << '\n';
  };
  for (const core::Tri& t : d.triangles) face_line(t);
  for (const core::Quad& q : d.quads) face_line(q);
  return out;
}

}  // namespace polycube::io::detail
