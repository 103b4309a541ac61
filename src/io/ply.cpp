//! PLY, ASCII and binary (little- or big-endian). Reads the `vertex` element's x, y, z (any
//! numeric type) and the `face` element's `vertex_indices` (or `vertex_index`) list (any
//! integer types); every other property and element is skipped. Triangles and quads are kept,
//! larger polygons fan-triangulated. Written as ASCII (or binary little-endian with
//! WriteOptions::binary) with double coordinates and a uchar/int face list.
#include "io/formats.h"
#include "io/parse.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  std::vector<int> poly;
  long long n_vertices = -1;
  for (const Element& e : elements) {
    // Minimum bytes per element instance, to refuse absurd counts before allocating.
    std::size_t min_bytes = 0;
    for (const Property& p : e.props)
      min_bytes += enc == Encoding::Ascii ? 2 : (p.is_list ? size_of(p.count_type) : size_of(p.type));
    if (min_bytes == 0 && e.count > 0)
      throw core::InputError(name, e.line, "element '" + e.name + "' has no properties");
    if (e.count > 0x7fffffff ||
        static_cast<unsigned long long>(e.count) > in.remaining() / std::max<std::size_t>(min_bytes, 1) + 1)
      throw core::InputError(name, e.line,
                             "declared " + std::to_string(e.count) + " '" + e.name +
                                 "' elements, more than the rest of the file (" + std::to_string(in.remaining()) +
                                 " bytes) can hold");

    if (e.name == "vertex") {
      int ix = -1, iy = -1, iz = -1;
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.is_list) continue;
        if (p.name == "x") ix = static_cast<int>(k);
        if (p.name == "y") iy = static_cast<int>(k);
        if (p.name == "z") iz = static_cast<int>(k);
      }
      if (ix < 0 || iy < 0 || iz < 0) throw core::InputError(name, e.line, "vertex element lacks x, y or z");
      if (n_vertices >= 0) throw core::InputError(name, e.line, "second vertex element");
      n_vertices = e.count;
      d.points.resize(static_cast<std::size_t>(e.count));
      for (core::Vec3& pt : d.points)
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          if (p.is_list) {
            for (int j = in.list_count(p.count_type); j > 0; --j) in.skip(p.type);
          } else if (static_cast<int>(k) == ix || static_cast<int>(k) == iy || static_cast<int>(k) == iz) {
            pt[static_cast<int>(k) == ix ? 0 : static_cast<int>(k) == iy ? 1 : 2] =
                in.real(p.type, "vertex coordinate");
          } else {
            in.skip(p.type);
          }
        }
    } else if (e.name == "face") {
      int il = -1;
      for (std::size_t k = 0; k < e.props.size(); ++k)
        if (e.props[k].is_list && (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
          il = static_cast<int>(k);
      if (il < 0) throw core::InputError(name, e.line, "face element has no vertex_indices list");
      if (!is_integer(e.props[static_cast<std::size_t>(il)].type))
        throw core::InputError(name, e.line, "face vertex_indices must be of an integer type");
      if (n_vertices < 0) throw core::InputError(name, e.line, "face element before the vertex element");
      for (long long f = 0; f < e.count; ++f)
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          if (static_cast<int>(k) == il) {
            const int n = in.list_count(p.count_type);
            if (n < 3) in.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
            poly.resize(static_cast<std::size_t>(n));
            for (int& v : poly) {
              const long long idx = in.integer(p.type, "vertex index");
              if (idx < 0 || idx >= n_vertices)
                in.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(idx) + " out of range (0.." +
                        std::to_string(n_vertices - 1) + ")");
              v = static_cast<int>(idx);
            }
            add_polygon(d, poly);
          } else if (p.is_list) {
            for (int j = in.list_count(p.count_type); j > 0; --j) in.skip(p.type);
          } else {
            in.skip(p.type);
          }
        }
    } else {
      for (long long i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          if (p.is_list)
            for (int j = in.list_count(p.count_type); j > 0; --j) in.skip(p.type);
          else
            in.skip(p.type);
        }
    }
  }
  return d;
}

std::string write_ply(const core::MeshData& d, const WriteOptions& options) {
  std::string out;
  out.reserve(d.points.size() * (options.binary ? 24 : 64) + d.num_cells() * 32);
  TextWriter w(out);
  w << "ply\nformat " << (options.binary ? "binary_little_endian" : "ascii") << " 1.0\n"
    << "comment written by polycube\n"
    << "element vertex " << d.points.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
    << "element face " << d.triangles.size() + d.quads.size() << "\nproperty list uchar int vertex_indices\n"
    << "end_header\n";
  if (options.binary) {
    for (const core::Vec3& p : d.points)
      for (int k = 0; k < 3; ++k) put_bytes(out, p[k]);
    for (const core::Tri& t : d.triangles) {
      put_bytes(out, std::uint8_t{3});
      for (const int v : t) put_bytes(out, static_cast<std::int32_t>(v));
    }
    for (const core::Quad& q : d.quads) {
      put_bytes(out, std::uint8_t{4});
      for (const int v : q) put_bytes(out, static_cast<std::int32_t>(v));
    }
    return out;
  }
  for (const core::Vec3& p : d.points) w << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const core::Tri& t : d.triangles) w << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  for (const core::Quad& q : d.quads) w << "4 " << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << '\n';
  return out;
}

}  // namespace polycube::io::detail
