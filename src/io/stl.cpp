//! STL, ASCII and binary. A file is binary exactly when its size is 84 + 50 n, n being the
//! count at byte 80 (the "solid" keyword is no evidence: many binary files start with it),
//! unless it is also plain text that starts with "solid". Identical vertices are merged
//! exactly (same coordinates bit for bit, -0 = +0) so the surface comes out indexed, vertices
//! numbered in order of first appearance. Written in single precision, as the format is.
#include "io/formats.h"
#include "io/parse.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace polycube::io::detail {

namespace {

struct KeyHash {
  std::size_t operator()(const std::array<double, 3>& k) const {
    std::size_t h = 0;
    for (const double v : k) {
      std::uint64_t b;
      std::memcpy(&b, &v, sizeof(b));
      h ^= std::hash<std::uint64_t>{}(b) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return h;
  }
};

//! Collects triangle corners and merges identical positions.
class Welder {
 public:
  explicit Welder(core::MeshData& d, std::size_t expected_triangles) : d_(d) {
    index_.reserve(expected_triangles);
    d_.triangles.reserve(expected_triangles);
  }
  int vertex(const core::Vec3& p) {
    const std::array<double, 3> key{p.x() + 0.0, p.y() + 0.0, p.z() + 0.0};  // -0 -> +0
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(d_.points.size()));
    if (inserted) d_.points.push_back(p);
    return it->second;
  }

 private:
  core::MeshData& d_;
  std::unordered_map<std::array<double, 3>, int, KeyHash> index_;
};

bool starts_with_solid(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n')) ++i;
  return data.substr(i, 5) == "solid";
}

bool is_text(std::string_view data) {
  for (const char ch : data) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t') return false;
    if (c >= 0x7f) return false;
  }
  return true;
}

core::MeshData read_binary(std::string_view data, const std::string& name, std::uint32_t n) {
  core::MeshData d;
  ByteReader r(data, name, 84);
  Welder weld(d, n);
  for (std::uint32_t t = 0; t < n; ++t) {
    r.skip(12, "facet normal");
    core::Tri tri;
    for (int c = 0; c < 3; ++c) {
      core::Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = r.get<float>("vertex coordinate");
      if (!p.allFinite())
        r.fail("triangle " + std::to_string(t) + " has a non-finite (NaN or Inf) vertex coordinate");
      tri[c] = weld.vertex(p);
    }
    r.skip(2, "attribute count");
    d.triangles.push_back(tri);
  }
  return d;
}

core::MeshData read_ascii(std::string_view data, const std::string& name) {
  Scanner s(data, name);
  core::MeshData d;
  Welder weld(d, data.size() / 250);
  auto expect = [&](std::string_view word) {
    const std::string_view t = s.token(std::string(word).c_str());
    if (t != word) s.fail("expected '" + std::string(word) + "', found " + quote(t));
  };
  expect("solid");
  s.rest_of_line();  // solid name
  for (;;) {
    const std::string_view t = s.next();
    if (t.empty()) s.fail("unexpected end of file (expected 'endsolid')");
    if (t == "endsolid") {
      s.rest_of_line();
      if (s.at_end()) break;
      expect("solid");  // several solids in one file
      s.rest_of_line();
      continue;
    }
    if (t != "facet") s.fail("expected 'facet' or 'endsolid', found " + quote(t));
    expect("normal");
    for (int k = 0; k < 3; ++k) s.token("normal component");  // ignored (may be NaN in the wild)
    expect("outer");
    expect("loop");
    core::Tri tri;
    for (int c = 0; c < 3; ++c) {
      expect("vertex");
      core::Vec3 p;
      for (int k = 0; k < 3; ++k) {
        p[k] = s.real("vertex coordinate");
        // STL stores single precision: a value that rounds to an infinite float cannot be a
        // real STL coordinate (0x1.ffffffp127 = FLT_MAX + half an ulp: the rounding limit).
        if (std::abs(p[k]) >= 0x1.ffffffp127)
          s.fail("vertex coordinate " + fmt::format("{:g}", p[k]) + " exceeds the single-precision range of STL");
      }
      tri[c] = weld.vertex(p);
    }
    expect("endloop");
    expect("endfacet");
    d.triangles.push_back(tri);
  }
  return d;
}

core::Vec3 unit_normal(const core::MeshData& d, const core::Tri& t) {
  const core::Vec3 n = (d.points[t[1]] - d.points[t[0]]).cross(d.points[t[2]] - d.points[t[0]]);
  const double len = n.norm();
  return len > 0.0 && std::isfinite(len) ? core::Vec3(n / len) : core::Vec3::Zero();
}

}  // namespace

core::MeshData read_stl(std::string_view data, const std::string& name) {
  if (data.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    const bool size_fits = 84 + 50 * static_cast<std::uint64_t>(n) == data.size();
    if (size_fits && !(starts_with_solid(data) && is_text(data))) return read_binary(data, name, n);
    if (!starts_with_solid(data))
      throw core::InputError(name, 0,
                             "not an STL file: not ASCII (no 'solid'), and as binary STL its header declares " +
                                 std::to_string(n) + " triangles = " + std::to_string(84 + 50 * static_cast<std::uint64_t>(n)) +
                                 " bytes, but the file has " + std::to_string(data.size()) +
                                 " bytes (truncated or not STL)");
  } else if (!starts_with_solid(data)) {
    throw core::InputError(name, 0,
                           "not an STL file: " + std::to_string(data.size()) +
                               " bytes, too short for binary STL, and no ASCII 'solid' header");
  }
  return read_ascii(data, name);
}

// The caller (fit_to_format) has checked the float range and the triangle count.
std::string write_stl(const core::MeshData& d, const WriteOptions& options) {
  std::string out;
  if (options.binary) {
    out.reserve(84 + 50 * d.triangles.size());
    std::string header = "binary STL written by polycube";
    header.resize(80, ' ');
    out += header;
    put_bytes(out, static_cast<std::uint32_t>(d.triangles.size()));
    for (const core::Tri& t : d.triangles) {
      const core::Vec3 n = unit_normal(d, t);
      for (int k = 0; k < 3; ++k) put_bytes(out, static_cast<float>(n[k]));
      for (const int v : t)
        for (int k = 0; k < 3; ++k) put_bytes(out, static_cast<float>(d.points[v][k]));
      put_bytes(out, std::uint16_t{0});
    }
    return out;
  }
  out.reserve(d.triangles.size() * 220);
  TextWriter w(out);
  w << "solid polycube\n";
  for (const core::Tri& t : d.triangles) {
    const core::Vec3 n = unit_normal(d, t);
    w << "facet normal " << static_cast<float>(n.x()) << ' ' << static_cast<float>(n.y()) << ' '
      << static_cast<float>(n.z()) << "\n outer loop\n";
    for (const int v : t) {
      const core::Vec3& p = d.points[v];
      w << "  vertex " << static_cast<float>(p.x()) << ' ' << static_cast<float>(p.y()) << ' '
        << static_cast<float>(p.z()) << '\n';
    }
    w << " endloop\nendfacet\n";
  }
  w << "endsolid polycube\n";
  return out;
}

}  // namespace polycube::io::detail
