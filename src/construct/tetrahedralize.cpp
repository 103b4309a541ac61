#include "construct/tetrahedralize.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"

#define TETLIBRARY
#include <tetgen.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace polycube::construct {

namespace {

using core::Tet;
using core::TetMesh;
using core::Vec3;
using Edge = std::array<int, 2>;

double signed_volume6(const TetMesh& m, const Tet& t) {
  const Vec3& p0 = m.points[t[0]];
  return (m.points[t[1]] - p0).dot((m.points[t[2]] - p0).cross(m.points[t[3]] - p0));
}

Edge sorted_edge(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

//! Boundary vertex flags and sorted boundary edges of a tet mesh.
struct BoundaryInfo {
  std::vector<char> is_boundary_vertex;
  std::vector<Edge> boundary_edges;  // sorted, unique
  std::vector<int> boundary_faces_of_cell;
  [[nodiscard]] bool is_boundary_edge(int a, int b) const {
    return std::binary_search(boundary_edges.begin(), boundary_edges.end(), sorted_edge(a, b));
  }
};

BoundaryInfo boundary_info(const TetMesh& m) {
  const auto ft = core::unique_faces(m);
  BoundaryInfo info;
  info.is_boundary_vertex.assign(m.points.size(), 0);
  info.boundary_faces_of_cell.assign(m.cells.size(), 0);
  for (int f = 0; f < ft.num_faces(); ++f) {
    if (!ft.is_boundary(f)) continue;
    const auto& face = ft.faces[f];
    ++info.boundary_faces_of_cell[ft.face_cells[f][0]];
    for (int k = 0; k < 3; ++k) {
      info.is_boundary_vertex[face[k]] = 1;
      info.boundary_edges.push_back(sorted_edge(face[k], face[(k + 1) % 3]));
    }
  }
  std::sort(info.boundary_edges.begin(), info.boundary_edges.end());
  info.boundary_edges.erase(std::unique(info.boundary_edges.begin(), info.boundary_edges.end()),
                            info.boundary_edges.end());
  return info;
}

//! Interior edges whose two endpoints are boundary vertices (sorted edge ids of et).
std::vector<int> bad_edges(const BoundaryInfo& info,
                           const core::EdgeTopology<core::CellType::Tetra>& et) {
  std::vector<int> bad;
  for (int e = 0; e < et.num_edges(); ++e) {
    const auto& ab = et.edges[e];
    if (info.is_boundary_vertex[ab[0]] && info.is_boundary_vertex[ab[1]] &&
        !info.is_boundary_edge(ab[0], ab[1]))
      bad.push_back(e);
  }
  return bad;
}

void push_cell(TetMesh& m, const Tet& t, int label) {
  m.cells.push_back(t);
  if (!m.labels.empty()) m.labels.push_back(label);
}

//! What TetGen returned, copied out of its tetgenio (or out of the child process).
struct TetgenOutput {
  std::vector<double> points;  //!< 3 per point
  std::vector<int> tets;       //!< 4 per tet
  int error = 0;               //!< TetGen's error code (thrown as an int), 0: none
};

//! Write all of `size` bytes (false on a closed pipe or another error).
bool write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

//! Run TetGen in a child process and read its output back through a pipe. TetGen 1.5 as Debian
//! builds it checks its invariants with assert(): on some degenerate inputs (a triangular
//! bipyramid split into coplanar triangles) it aborts the whole process, which no exception can
//! catch. In a child, the abort is the child's, and the parent reports it as a failure.
TetgenOutput run_tetgen_isolated(const std::string& switches, tetgenio& in) {
  int fds[2];
  if (::pipe(fds) != 0) throw core::GeometryError("TetGen: cannot create a pipe to its process");
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw core::GeometryError("TetGen: cannot start its process");
  }
  if (pid == 0) {  // the child: TetGen, the result into the pipe, and out without cleanup
    ::close(fds[0]);
    // Ended with the parent (an interrupted run exits at once; its TetGen must not go on).
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(1);
    const int devnull = ::open("/dev/null", O_WRONLY);  // its assert() message is not ours to print
    if (devnull >= 0) ::dup2(devnull, STDERR_FILENO);
    std::array<std::int64_t, 4> header{0, 0, 0, 0};  // error, points, tets, corners
    tetgenio out;
    try {
      std::vector<char> sw(switches.begin(), switches.end());
      sw.push_back('\0');
      ::tetrahedralize(sw.data(), &in, &out);
      header = {0, out.numberofpoints, out.numberoftetrahedra, out.numberofcorners};
    } catch (int code) {
      header[0] = code == 0 ? -1 : code;
    }
    bool ok = write_all(fds[1], header.data(), sizeof(header));
    if (ok && header[0] == 0) {
      ok = write_all(fds[1], out.pointlist, sizeof(REAL) * 3 * static_cast<std::size_t>(header[1])) &&
           write_all(fds[1], out.tetrahedronlist,
                     sizeof(int) * static_cast<std::size_t>(header[2] * header[3]));
    }
    ::_exit(ok ? 0 : 1);
  }
  ::close(fds[1]);
  std::vector<char> bytes;
  std::array<char, 1 << 16> chunk{};
  for (;;) {
    const ssize_t n = ::read(fds[0], chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.insert(bytes.end(), chunk.data(), chunk.data() + n);
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw TetgenFailed(fmt::format("TetGen stopped on one of its internal checks (signal {}) on this surface",
                                   WTERMSIG(status)));
  std::array<std::int64_t, 4> header{};
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.size() < sizeof(header))
    throw core::GeometryError("TetGen's process ended without its result");
  std::memcpy(header.data(), bytes.data(), sizeof(header));
  TetgenOutput result;
  result.error = static_cast<int>(header[0]);
  if (result.error != 0) return result;
  const std::size_t points = 3 * static_cast<std::size_t>(header[1]);
  const std::size_t corners = static_cast<std::size_t>(header[2] * header[3]);
  if (header[3] != 4 || bytes.size() != sizeof(header) + sizeof(REAL) * points + sizeof(int) * corners)
    throw core::GeometryError("TetGen's process returned a result of the wrong size");
  result.points.resize(points);
  result.tets.resize(corners);
  std::memcpy(result.points.data(), bytes.data() + sizeof(header), sizeof(REAL) * points);
  std::memcpy(result.tets.data(), bytes.data() + sizeof(header) + sizeof(REAL) * points, sizeof(int) * corners);
  return result;
}

std::string tetgen_reason(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 2:
      return "internal error";
    case 3:
      return "the surface self-intersects";
    case 4:
      return "a very small input feature size was detected";
    case 5:
      return "two very close input facets were detected";
    case 10:
      return "input error";
    default:
      return fmt::format("error code {}", code);
  }
}

//! A point of the surface, written for a message: "(x, y, z)" (or "an unknown place").
std::string where(const std::optional<core::Vec3>& p) {
  return p ? fmt::format("({:.6g}, {:.6g}, {:.6g})", p->x(), p->y(), p->z())
           : std::string("an unknown place");
}

//! The centre of the first triangle (in file order) of zero area.
std::optional<core::Vec3> first_zero_area(const core::TriMesh& m) {
  for (const core::Tri& t : m.cells) {
    const core::Vec3 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] ||
        0.5 * (b - a).cross(c - a).norm() <= 1e-12 * longest)
      return (a + b + c) / 3.0;
  }
  return std::nullopt;
}

//! The midpoint of the first edge (in the order of the triangles) whose number of triangles
//! satisfies `count_is`.
template <class Pred>
std::optional<core::Vec3> first_edge_used(const core::TriMesh& m, Pred count_is) {
  std::map<std::pair<int, int>, int> uses;
  for (const core::Tri& t : m.cells)
    for (int e = 0; e < 3; ++e) ++uses[std::minmax(t[e], t[(e + 1) % 3])];
  for (const core::Tri& t : m.cells)
    for (int e = 0; e < 3; ++e) {
      const auto key = std::minmax(t[e], t[(e + 1) % 3]);
      if (count_is(uses[key])) return (m.points[key.first] + m.points[key.second]) / 2.0;
    }
  return std::nullopt;
}

//! The first vertex whose triangles form more than one fan (joined through shared edges).
std::optional<core::Vec3> first_pinched_vertex(const core::TriMesh& m) {
  std::vector<std::vector<int>> around(m.points.size());
  for (std::size_t t = 0; t < m.cells.size(); ++t)
    for (const int v : m.cells[t])
      around[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));
  for (std::size_t v = 0; v < around.size(); ++v) {
    const std::vector<int>& fan = around[v];
    if (fan.size() < 2) continue;
    // Grow one fan from the first triangle through edges at v; any triangle left out is a second.
    std::vector<char> reached(fan.size(), 0);
    reached[0] = 1;
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t i = 0; i < fan.size(); ++i) {
        if (reached[i]) continue;
        for (std::size_t k = 0; k < fan.size() && !reached[i]; ++k) {
          if (!reached[k]) continue;
          int shared = 0;  // vertices the two triangles share besides v
          for (const int a : m.cells[static_cast<std::size_t>(fan[i])])
            for (const int b : m.cells[static_cast<std::size_t>(fan[k])])
              shared += a == b && a != static_cast<int>(v);
          if (shared > 0) reached[i] = grew = true;
        }
      }
    }
    if (std::find(reached.begin(), reached.end(), 0) != reached.end()) return m.points[v];
  }
  return std::nullopt;
}

//! Whether the ray p + t d (t > 0) crosses triangle (a, b, c) (Moller-Trumbore).
bool ray_crosses(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double& t) {
  const Vec3 e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return false;
  const Vec3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  t = e2.dot(q) / det;
  return t > 0.0;
}

//! Whether p is strictly inside the closed shell made of `faces` of m (CGAL's exact side test;
//! a hand-made ray parity miscounts rays through edges).
bool inside_shell(const core::TriMesh& m, const std::vector<int>& faces, const Vec3& p) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh shell;
  std::map<int, Mesh::Vertex_index> vertex;
  for (const int f : faces)
    for (const int v : m.cells[static_cast<std::size_t>(f)])
      if (!vertex.count(v)) {
        const Vec3& q = m.points[static_cast<std::size_t>(v)];
        vertex[v] = shell.add_vertex({q.x(), q.y(), q.z()});
      }
  for (const int f : faces) {
    const core::Tri& t = m.cells[static_cast<std::size_t>(f)];
    shell.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]);
  }
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> side(shell);
  return side(Kernel::Point_3(p.x(), p.y(), p.z())) == CGAL::ON_BOUNDED_SIDE;
}

//! The triangles of each connected shell (through shared edges).
std::vector<std::vector<int>> shells(const core::TriMesh& m) {
  std::vector<int> parent(m.cells.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  std::map<std::pair<int, int>, int> first;
  for (std::size_t f = 0; f < m.cells.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const auto key = std::minmax(m.cells[f][e], m.cells[f][(e + 1) % 3]);
      const auto [it, added] = first.emplace(key, static_cast<int>(f));
      if (!added) parent[static_cast<std::size_t>(find(static_cast<int>(f)))] = find(it->second);
    }
  std::map<int, std::vector<int>> by_root;
  for (std::size_t f = 0; f < m.cells.size(); ++f) by_root[find(static_cast<int>(f))].push_back(static_cast<int>(f));
  std::vector<std::vector<int>> out;
  for (auto& [root, faces] : by_root) out.push_back(std::move(faces));
  return out;
}

//! A point inside each cavity of the solid: TetGen fills every closed region unless told which
//! are holes. A shell inside an odd number of other shells bounds a cavity; its point is half
//! way from one of its triangles to the next surface crossed on the cavity's side.
std::vector<Vec3> cavity_points(const core::TriMesh& m) {
  const std::vector<std::vector<int>> parts = shells(m);
  std::vector<Vec3> points;
  if (parts.size() < 2) return points;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const Vec3& probe = m.points[m.cells[static_cast<std::size_t>(parts[i].front())][0]];
    int depth = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) depth += k != i && inside_shell(m, parts[k], probe) ? 1 : 0;
    if (depth % 2 == 0) continue;
    const core::Tri& t = m.cells[static_cast<std::size_t>(parts[i].front())];
    const Vec3 c = (m.points[t[0]] + m.points[t[1]] + m.points[t[2]]) / 3.0;
    const Vec3 n = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]).normalized();
    for (const double side : {1.0, -1.0}) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t f = 0; f < m.cells.size(); ++f) {
        const core::Tri& g = m.cells[f];
        double hit = 0.0;
        if (ray_crosses(c, side * n, m.points[g[0]], m.points[g[1]], m.points[g[2]], hit) && hit > 1e-12)
          nearest = std::min(nearest, hit);
      }
      if (!std::isfinite(nearest)) continue;
      const Vec3 p = c + side * n * (nearest / 2.0);
      if (inside_shell(m, parts[i], p)) {
        points.push_back(p);
        break;
      }
    }
  }
  return points;
}

}  // namespace

void check_closed_surface(const core::TriMesh& surface) {
  if (surface.cells.empty()) throw core::InputError("the surface has no triangle");
  const auto report = core::analyze_surface(surface);  // throws InputError on bad indices
  // Each refusal says where the first defect is (model coordinates) and what to do about it.
  if (report.degenerate_faces > 0)
    throw core::InputError(fmt::format(
        "the surface has {} triangle(s) of zero area, the first at {}; remove them (MeshLab: "
        "Remove Zero Area Faces) or remesh the surface",
        report.degenerate_faces, where(first_zero_area(surface))));
  if (report.nonmanifold_edges > 0)
    throw core::InputError(fmt::format(
        "the surface is not manifold: {} edge(s) shared by three or more triangles, the first at "
        "{}; "
        "separate the solids that touch there or give one closed solid (--repair wrap joins them)",
        report.nonmanifold_edges, where(first_edge_used(surface, [](int n) { return n > 2; }))));
  if (report.boundary_edges > 0)
    throw core::InputError(fmt::format(
        "the surface is open: {} boundary edge(s) in {} hole(s), the first at {}; close the holes "
        "(--repair holes, or --repair wrap for many small gaps) or give a closed surface",
        report.boundary_edges, report.boundary_loops,
        where(first_edge_used(surface, [](int n) { return n == 1; }))));
  if (report.nonmanifold_vertices > 0)
    throw core::InputError(fmt::format(
        "the surface is not manifold: {} vertex(es) where separate sheets touch, the first at {}; "
        "move the sheets apart there or join them into one solid (--repair wrap)",
        report.nonmanifold_vertices, where(first_pinched_vertex(surface))));
  if (!report.orientable) throw core::InputError("the surface is not orientable");

  // Self-intersection, with exact predicates, on a consistently oriented copy.
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
  core::TriMesh oriented = surface;
  if (!core::orient_consistently(oriented)) throw core::InputError("the surface is not orientable");
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vid;
  vid.reserve(oriented.points.size());
  for (const auto& p : oriented.points) vid.push_back(sm.add_vertex({p.x(), p.y(), p.z()}));
  for (const auto& t : oriented.cells) {
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == SurfaceMesh::null_face())
      throw core::InputError("the surface is not manifold (a triangle cannot be attached)");
  }
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  if (!pairs.empty()) {
    const auto f0 = static_cast<int>(pairs.front().first.idx());
    const auto f1 = static_cast<int>(pairs.front().second.idx());
    const core::Tri& t = oriented.cells[static_cast<std::size_t>(std::min(f0, f1))];
    const Vec3 at = (oriented.points[t[0]] + oriented.points[t[1]] + oriented.points[t[2]]) / 3.0;
    throw core::InputError(fmt::format(
        "the surface self-intersects: {} pair(s) of intersecting triangles (first: {} and {}, near "
        "{}); separate the parts that cross there, or join them into one solid (--repair wrap; or a "
        "boolean union)",
        pairs.size(), std::min(f0, f1), std::max(f0, f1), where(at)));
  }
}

TetrahedralizeResult tetrahedralize(const core::TriMesh& input,
                                    const TetrahedralizeOptions& options) {
  core::TriMesh surface = input;
  core::remove_unreferenced_points(surface);
  check_closed_surface(surface);
  auto& log = core::logger();

  tetgenio in;
  in.firstnumber = 0;
  in.numberofpoints = surface.num_points();
  in.pointlist = new REAL[static_cast<std::size_t>(in.numberofpoints) * 3];
  for (int i = 0; i < in.numberofpoints; ++i)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * i + k] = surface.points[i][k];
  in.numberoffacets = surface.num_cells();
  in.facetlist = new tetgenio::facet[static_cast<std::size_t>(in.numberoffacets)];
  for (int f = 0; f < in.numberoffacets; ++f) {
    tetgenio::facet& fa = in.facetlist[f];
    tetgenio::init(&fa);
    fa.numberofpolygons = 1;
    fa.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fa.polygonlist[0]);
    fa.polygonlist[0].numberofvertices = 3;
    fa.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) fa.polygonlist[0].vertexlist[k] = surface.cells[f][k];
  }

  const std::vector<Vec3> holes = cavity_points(surface);
  if (!holes.empty()) {
    log.info("tetrahedralize: {} cavity(ies) left empty", holes.size());
    in.numberofholes = static_cast<int>(holes.size());
    in.holelist = new REAL[holes.size() * 3];
    for (std::size_t h = 0; h < holes.size(); ++h)
      for (int k = 0; k < 3; ++k) in.holelist[3 * h + static_cast<std::size_t>(k)] = holes[h][k];
  }

  // p: piecewise linear complex, Y: no Steiner point on the surface, Q: quiet, z: 0-based.
  std::string switches = "pYQz";
  if (options.quality > 0.0) switches += fmt::format("q{:.4f}", std::max(1.1, options.quality));
  if (options.max_volume > 0.0) {
    const auto box = core::bounding_box(surface.points);
    const Vec3 ext = box.extent();
    const double vol = options.max_volume * ext.x() * ext.y() * ext.z();
    if (vol > 0.0) switches += fmt::format("a{:.10g}", vol);
  }
  log.info("tetrahedralize: TetGen -{} on {} points, {} triangles", switches, in.numberofpoints,
           in.numberoffacets);
  const TetgenOutput out = run_tetgen_isolated(switches, in);
  if (out.error == 3) throw core::InputError("TetGen: " + tetgen_reason(out.error));
  if (out.error != 0) throw TetgenFailed("TetGen failed: " + tetgen_reason(out.error));
  if (out.tets.empty())
    throw core::GeometryError("TetGen made no tetrahedron (is the surface enclosing a volume?)");

  TetrahedralizeResult result;
  TetMesh& mesh = result.mesh;
  mesh.points.resize(out.points.size() / 3);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    mesh.points[i] = Vec3(out.points[3 * i], out.points[3 * i + 1], out.points[3 * i + 2]);
  mesh.cells.resize(out.tets.size() / 4);
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (std::size_t k = 0; k < 4; ++k) mesh.cells[c][k] = out.tets[4 * c + k];
  core::remove_unreferenced_points(mesh);
  for (auto& t : mesh.cells)
    if (signed_volume6(mesh, t) < 0.0) std::swap(t[2], t[3]);
  result.tetgen_tets = mesh.num_cells();

  // TetGen must have kept the surface: same number of boundary triangles.
  const auto bnd = core::boundary(mesh);
  if (bnd.surface.num_cells() != surface.num_cells())
    throw core::GeometryError(
        fmt::format("TetGen changed the surface ({} boundary triangles instead of {})",
                    bnd.surface.num_cells(), surface.num_cells()));
  if (options.refine) result.refine = refine_boundary(mesh);
  log.info(
      "tetrahedralize: {} tets from TetGen, {} after refinement ({} edge splits, {} tet splits)",
      result.tetgen_tets, mesh.num_cells(), result.refine.split_edges, result.refine.split_tets);
  return result;
}

void prepare_tet_mesh(TetMesh& mesh) {
  if (mesh.cells.empty()) throw core::InputError("the tet mesh has no tetrahedron");
  core::check_indices(mesh);
  core::remove_unreferenced_points(mesh);
  int positive = 0, negative = 0, flat = 0;
  const double scale = core::bounding_box(mesh.points).diagonal();
  const double eps = 1e-14 * scale * scale * scale;
  for (const auto& t : mesh.cells) {
    const double v = signed_volume6(mesh, t);
    if (std::abs(v) <= eps)
      ++flat;
    else if (v > 0)
      ++positive;
    else
      ++negative;
  }
  if (flat > 0) throw core::InputError(fmt::format("the tet mesh has {} flat tetrahedra", flat));
  if (positive > 0 && negative > 0)
    throw core::InputError(
        fmt::format("the tet mesh mixes orientations: {} positive and {} inverted tetrahedra",
                    positive, negative));
  if (negative > 0)
    for (auto& t : mesh.cells) std::swap(t[2], t[3]);
  core::TetBoundary bnd;
  try {
    bnd = core::boundary(mesh);
  } catch (const core::GeometryError& e) {
    throw core::InputError(std::string("the tet mesh is not manifold: ") + e.what());
  }
  const auto report = core::analyze_surface(bnd.surface);
  if (!report.closed || !report.manifold)
    throw core::InputError(fmt::format(
        "the boundary of the tet mesh is not a closed manifold surface ({} boundary edges, {} "
        "non-manifold edges, {} non-manifold vertices)",
        report.boundary_edges, report.nonmanifold_edges, report.nonmanifold_vertices));
}

RefineStats refine_boundary(TetMesh& mesh) {
  RefineStats stats;
  // 1. Split interior edges joining two boundary vertices, in rounds of edges sharing no tet.
  for (;;) {
    const BoundaryInfo info = boundary_info(mesh);
    const auto et = core::unique_edges(mesh);
    const std::vector<int> bad = bad_edges(info, et);
    if (bad.empty()) break;
    const auto ec = core::edge_cells(et);
    std::vector<char> used(mesh.cells.size(), 0);
    for (const int e : bad) {
      const auto cells = ec[e];
      if (std::any_of(cells.begin(), cells.end(), [&](int c) { return used[c] != 0; })) continue;
      const int a = et.edges[e][0];
      const int b = et.edges[e][1];
      const int m = mesh.num_points();
      mesh.points.push_back(0.5 * (mesh.points[a] + mesh.points[b]));
      for (const int c : cells) {
        used[c] = 1;
        const Tet t = mesh.cells[c];
        Tet t1 = t;
        Tet t2 = t;
        for (int k = 0; k < 4; ++k) {
          if (t[k] == b) t1[k] = m;
          if (t[k] == a) t2[k] = m;
        }
        mesh.cells[c] = t1;
        push_cell(mesh, t2, mesh.labels.empty() ? 0 : mesh.labels[c]);
      }
      ++stats.split_edges;
    }
  }
  // 2. Split tets with several boundary facets at their centroid (after step 1, all their edges
  // are boundary edges, so the four new tets each hold one of the old faces).
  const BoundaryInfo info = boundary_info(mesh);
  const int n = mesh.num_cells();
  for (int c = 0; c < n; ++c) {
    if (info.boundary_faces_of_cell[c] < 2) continue;
    const Tet t = mesh.cells[c];
    const int m = mesh.num_points();
    mesh.points.push_back(
        0.25 * (mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]] + mesh.points[t[3]]));
    const int label = mesh.labels.empty() ? 0 : mesh.labels[c];
    // Replacing one vertex by an interior point keeps the orientation.
    for (int k = 0; k < 4; ++k) {
      Tet tk = t;
      tk[k] = m;
      if (k == 0)
        mesh.cells[c] = tk;
      else
        push_cell(mesh, tk, label);
    }
    ++stats.split_tets;
  }
  return stats;
}

BoundaryDefects boundary_defects(const TetMesh& mesh) {
  const BoundaryInfo info = boundary_info(mesh);
  const auto et = core::unique_edges(mesh);
  BoundaryDefects d;
  d.interior_edges_between_boundary_vertices = static_cast<int>(bad_edges(info, et).size());
  for (const int k : info.boundary_faces_of_cell)
    if (k >= 2) ++d.tets_with_several_boundary_facets;
  return d;
}

}  // namespace polycube::construct
