//! Wavefront OBJ: `v x y z [w | r g b]` and `f a b c ...` with `a`, `a/t`, `a//n`, `a/t/n`
//! references (1-based, negative = relative to the last vertex). Triangles and quads are kept,
//! larger polygons are fan-triangulated from their first vertex. Texture coordinates, normals,
//! groups, smoothing, materials, lines and points are ignored; statements OBJ does not define
//! (vendor extensions, `c ...`) are skipped with one warning per keyword and its count, as
//! other readers of the format do, so that a clean surface is never refused for them.
#include "io/formats.h"
#include "io/parse.h"

#include "core/log.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <string>

namespace polycube::io::detail {

namespace {

//! Statements that are valid OBJ but carry nothing a MeshData holds.
bool is_ignored_statement(std::string_view kw) {
  static constexpr std::string_view kIgnored[] = {
      "vt",        "vn",    "vp",       "g",        "o",    "s",      "usemtl", "mtllib",
      "l",         "p",     "cstype",   "deg",      "bmat", "step",   "curv",   "curv2",
      "surf",      "parm",  "trim",     "hole",     "scrv", "sp",     "end",    "con",
      "mg",        "bevel", "c_interp", "d_interp", "lod",  "maplib", "usemap", "shadow_obj",
      "trace_obj", "ctech", "stech",    "call"};
  return std::find(std::begin(kIgnored), std::end(kIgnored), kw) != std::end(kIgnored);
}

}  // namespace

core::MeshData read_obj(std::string_view data, const std::string& name) {
  // Text only: a NUL byte means a binary file under the wrong extension, not statements to skip.
  if (data.find('\0') != std::string_view::npos)
    throw core::InputError(name, 0, "binary data in a text OBJ file: not an OBJ file?");
  Scanner s(data, name, '#');
  core::MeshData d;
  // Reserve from a quick count of the lines starting with "v " and "f " (an exact upper bound
  // for vertices; faces of more than 3 vertices may add triangles).
  std::size_t nv = 0, nf = 0;
  for (std::size_t i = 0; i + 1 < data.size(); ++i)
    if ((i == 0 || data[i - 1] == '\n') && (data[i + 1] == ' ' || data[i + 1] == '\t')) {
      nv += data[i] == 'v';
      nf += data[i] == 'f';
    }
  d.points.reserve(nv);
  d.triangles.reserve(nf);
  std::vector<int> poly;
  std::map<std::string, int, std::less<>>
      unknown;  // keyword -> lines skipped (sorted: stable output)
  for (;;) {
    const std::string_view kw = s.next();
    if (kw.empty()) break;
    if (kw == "v") {
      core::Vec3 p;
      for (int k = 0; k < 3; ++k)
        p[k] = s.real(s.line_token("vertex coordinate"), "vertex coordinate");
      d.points.push_back(p);
      s.skip_line();  // optional w or vertex colour
    } else if (kw == "f") {
      poly.clear();
      for (std::string_view t = s.next_on_line(); !t.empty(); t = s.next_on_line()) {
        const std::string_view ref = t.substr(0, t.find('/'));
        long long v = s.integer(ref, "face vertex index");
        const auto n = static_cast<long long>(d.points.size());
        if (v == 0) s.fail("vertex index 0 (OBJ indices start at 1)");
        if (v < 0) v += n + 1;  // relative reference: -1 is the last vertex read
        poly.push_back(s.check_index(v, n, 1));
      }
      if (poly.size() < 3)
        s.fail("face with " + std::to_string(poly.size()) + " vertices (at least 3 needed)");
      add_polygon(d, poly);
    } else if (is_ignored_statement(kw)) {
      s.skip_line();
    } else {
      ++unknown[std::string(kw)];
      s.skip_line();
    }
  }
  if (!unknown.empty() && d.triangles.empty() && d.quads.empty())
    throw core::InputError(
        name, 0,
        fmt::format("no faces, and {} kind(s) of statement OBJ does not define (first {}): "
                    "not an OBJ file?",
                    unknown.size(), quote(unknown.begin()->first)));
  for (const auto& [kw, count] : unknown)
    core::logger().warn("{}: skipped {} line(s) with the statement {}, which OBJ does not define",
                        name, count, quote(kw));
  return d;
}

std::string write_obj(const core::MeshData& d, const WriteOptions& /*options*/) {
  std::string out;
  out.reserve(d.points.size() * 64 + d.num_cells() * 32);
  TextWriter w(out);
  w << "# written by polycube: " << d.points.size() << " vertices, " << d.triangles.size()
    << " triangles, " << d.quads.size() << " quads\n";
  for (const core::Vec3& p : d.points) w << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const core::Tri& t : d.triangles)
    w << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  for (const core::Quad& q : d.quads)
    w << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << '\n';
  return out;
}

}  // namespace polycube::io::detail
