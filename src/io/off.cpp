//! Object File Format: `OFF`, then `#vertices #faces #edges`, one vertex per line, one face per
//! line (`n i0 .. in-1`, 0-based). Comments `#` anywhere. The variants COFF, NOFF, CNOFF, STOFF
//! (extra values after the coordinates) are accepted, and face colours are ignored; 4OFF, nOFF
//! with n != 3 and binary OFF are refused. Polygons of more than 4 vertices are fan-triangulated.
#include "io/formats.h"
#include "io/parse.h"

namespace polycube::io::detail {

core::MeshData read_off(std::string_view data, const std::string& name) {
  Scanner s(data, name, '#');
  std::string_view kw = s.token("OFF header");
  // Strip the optional prefixes of the variants: ST (texture), C (colour), N (normal), 4, n.
  std::string_view rest = kw;
  if (rest.size() < 3 || rest.substr(rest.size() - 3) != "OFF") s.fail("not an OFF file (first word " + quote(kw) + ")");
  rest.remove_suffix(3);
  if (rest.substr(0, 2) == "ST") rest.remove_prefix(2);
  if (!rest.empty() && rest.front() == 'C') rest.remove_prefix(1);
  if (!rest.empty() && rest.front() == 'N') rest.remove_prefix(1);
  if (!rest.empty() && rest.front() == '4') s.fail("4D OFF (" + quote(kw) + ") is not supported");
  if (rest == "n") {
    const long long dim = s.integer("OFF dimension");
    if (dim != 3) s.fail("OFF dimension " + std::to_string(dim) + " is not supported (only 3)");
  } else if (!rest.empty()) {
    s.fail("not an OFF file (first word " + quote(kw) + ")");
  }

  const int nv = s.count("vertices", 6);
  const int nf = s.count("faces", 8);
  s.integer("edge count");  // unused but required by the format
  s.skip_line();

  core::MeshData d;
  d.points.resize(static_cast<std::size_t>(nv));
  for (core::Vec3& p : d.points) {
    if (s.at_end()) s.fail("unexpected end of file: " + std::to_string(nv) + " vertices declared");
    p.x() = s.real("vertex coordinate");
    for (int k = 1; k < 3; ++k) p[k] = s.real(s.line_token("vertex coordinate"), "vertex coordinate");
    s.skip_line();  // normals, colours, texture coordinates of the variants
  }
  std::vector<int> poly;
  for (int f = 0; f < nf; ++f) {
    if (s.at_end()) s.fail("unexpected end of file: " + std::to_string(nf) + " faces declared, " + std::to_string(f) + " read");
    const long long n = s.integer("face vertex count");
    if (n < 3) s.fail("face with " + std::to_string(n) + " vertices (at least 3 needed)");
    s.check_count(n, "face vertices", 2);
    poly.resize(static_cast<std::size_t>(n));
    for (int& v : poly) v = s.check_index(s.integer(s.line_token("vertex index"), "vertex index"), nv, 0);
    add_polygon(d, poly);
    s.skip_line();  // optional face colour
  }
  return d;
}

std::string write_off(const core::MeshData& d, const WriteOptions& /*options*/) {
  std::string out;
  out.reserve(d.points.size() * 64 + d.num_cells() * 32);
  TextWriter w(out);
  w << "OFF\n# written by polycube\n"
    << d.points.size() << ' ' << d.triangles.size() + d.quads.size() << " 0\n";
  for (const core::Vec3& p : d.points) w << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const core::Tri& t : d.triangles) w << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  for (const core::Quad& q : d.quads) w << "4 " << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << '\n';
  return out;
}

}  // namespace polycube::io::detail
