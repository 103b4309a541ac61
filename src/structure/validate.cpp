#include "structure/validate.h"

#include "core/elements.h"
#include "core/errors.h"
#include "core/polycube_map.h"

#include <Eigen/Geometry>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace polycube::structure {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using core::Vec3;

Kernel::Point_3 cgal_point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

//! Collects offending element descriptions, keeping only the first few.
struct Listing {
  int count = 0;
  std::vector<std::string> items;
  void add(int max_listed, const std::string& s) {
    if (count++ < max_listed) items.push_back(s);
  }
  [[nodiscard]] std::string joined() const {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (i > 0) out += ", ";
      out += items[i];
    }
    if (count > static_cast<int>(items.size())) out += ", ...";
    return out;
  }
};

std::string plural(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}

//! Orientation checks in one space.
void check_orientation(const core::PolycubeMap& map, const std::vector<Vec3>& pos,
                       const char* space, const ValidateOptions& opt, int& inverted, int& flat,
                       std::vector<std::string>& failures) {
  Listing inv;
  Listing fl;
  for (int t = 0; t < map.num_tets(); ++t) {
    const auto& c = map.tets[static_cast<std::size_t>(t)];
    const auto o = CGAL::orientation(cgal_point(pos[c[0]]), cgal_point(pos[c[1]]),
                                     cgal_point(pos[c[2]]), cgal_point(pos[c[3]]));
    if (o == CGAL::NEGATIVE)
      inv.add(opt.max_listed, "tet " + std::to_string(t));
    else if (o == CGAL::COPLANAR)
      fl.add(opt.max_listed, "tet " + std::to_string(t));
  }
  inverted = inv.count;
  flat = fl.count;
  if (inv.count > 0) {
    std::string msg = plural(inv.count, "tet is", "tets are") + " inverted in " + space +
                      " space (" + inv.joined() + ")";
    if (inv.count == map.num_tets())
      msg += "; every tet is negatively oriented: the vertex order is mirrored";
    failures.push_back(msg);
  }
  if (fl.count > 0)
    failures.push_back(plural(fl.count, "tet is", "tets are") + " flat (zero volume) in " + space +
                       " space (" + fl.joined() + ")");
}

}  // namespace

MapDiagnosis diagnose_map(const core::PolycubeMap& map, const ValidateOptions& options) {
  core::check_map_indices(map);
  MapDiagnosis d;
  d.tets = map.num_tets();
  d.vertices = map.num_vertices();
  const int max_listed = std::max(1, options.max_listed);

  // 1. orientation in both spaces (exact predicates)
  if (options.check_model)
    check_orientation(map, map.model, "model", options, d.inverted_model, d.flat_model, d.failures);
  check_orientation(map, map.polycube, "polycube", options, d.inverted_polycube, d.flat_polycube,
                    d.failures);

  // 2. boundary faces: tet faces of exactly one tet (sort-based, deterministic)
  const int nt = map.num_tets();
  struct Slot {
    std::array<int, 3> key;  // sorted vertex ids
    int slot;                // 4 * tet + local face
  };
  std::vector<Slot> slots(static_cast<std::size_t>(nt) * 4);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) {
      const auto& lf = core::kTetFaces[static_cast<std::size_t>(k)];
      const auto& c = map.tets[static_cast<std::size_t>(t)];
      std::array<int, 3> key{c[lf[0]], c[lf[1]], c[lf[2]]};
      std::sort(key.begin(), key.end());
      slots[static_cast<std::size_t>(4 * t + k)] = {key, 4 * t + k};
    }
  std::sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) {
    return a.key != b.key ? a.key < b.key : a.slot < b.slot;
  });
  std::vector<int> boundary_slots;
  Listing shared;
  for (std::size_t i = 0; i < slots.size();) {
    std::size_t j = i;
    while (j < slots.size() && slots[j].key == slots[i].key) ++j;
    const int n = static_cast<int>(j - i);
    if (n == 1) boundary_slots.push_back(slots[i].slot);
    if (n >= 3) {
      std::string tets;
      for (std::size_t k = i; k < j; ++k) {
        if (k > i) tets += ' ';
        tets += std::to_string(slots[k].slot / 4);
      }
      shared.add(max_listed, "face " + std::to_string(slots[i].key[0]) + "-" +
                                 std::to_string(slots[i].key[1]) + "-" +
                                 std::to_string(slots[i].key[2]) + " in tets " + tets);
    }
    i = j;
  }
  std::sort(boundary_slots.begin(), boundary_slots.end());
  d.boundary_triangles = static_cast<int>(boundary_slots.size());
  d.overshared_faces = shared.count;

  std::vector<core::Tri> tris;
  tris.reserve(boundary_slots.size());
  for (int s : boundary_slots) {
    const auto& c = map.tets[static_cast<std::size_t>(s / 4)];
    const auto& lf = core::kTetFaces[static_cast<std::size_t>(s % 4)];
    tris.push_back({c[lf[0]], c[lf[1]], c[lf[2]]});
  }

  // 3. axis alignment of the polycube boundary triangles
  const core::BoundingBox box = core::bounding_box(map.polycube);
  d.axis_tolerance = options.axis_tolerance * box.diagonal();
  Listing tilted;
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const Vec3& a = map.polycube[tris[f][0]];
    const Vec3& b = map.polycube[tris[f][1]];
    const Vec3& c = map.polycube[tris[f][2]];
    const int axis = core::label_axis(core::dominant_axis_label((b - a).cross(c - a)));
    const double lo = std::min({a[axis], b[axis], c[axis]});
    const double hi = std::max({a[axis], b[axis], c[axis]});
    const double span = hi - lo;
    d.max_axis_deviation = std::max(d.max_axis_deviation, span);
    if (!(span <= d.axis_tolerance))
      tilted.add(max_listed, "triangle " + std::to_string(tris[f][0]) + "-" +
                                 std::to_string(tris[f][1]) + "-" + std::to_string(tris[f][2]) +
                                 " of tet " + std::to_string(boundary_slots[f] / 4) + " spans " +
                                 fmt_double(span) + " along " + core::axis_name(axis));
  }
  d.non_axis_aligned = tilted.count;
  if (tilted.count > 0)
    d.failures.push_back(
        plural(tilted.count, "polycube boundary triangle is", "polycube boundary triangles are") +
        " not axis-aligned (tolerance " + fmt_double(d.axis_tolerance) + " = " +
        fmt_double(options.axis_tolerance) + " of the bounding-box diagonal): " + tilted.joined());

  // 4. closed 2-manifold polycube surface
  if (shared.count > 0)
    d.failures.push_back("the polycube surface is not closed: " +
                         plural(shared.count, "tet face is", "tet faces are") +
                         " shared by more than two tets (" + shared.joined() + ")");
  if (tris.empty()) {
    d.failures.push_back("the polycube surface is empty: every tet face is shared");
  } else {
    struct EdgeSlot {
      std::array<int, 2> key;
      int corner;  // 3 * triangle + local edge
    };
    std::vector<EdgeSlot> es;
    es.reserve(tris.size() * 3);
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = tris[f][k];
        const int b = tris[f][(k + 1) % 3];
        es.push_back({{std::min(a, b), std::max(a, b)}, static_cast<int>(3 * f) + k});
      }
    std::sort(es.begin(), es.end(), [](const EdgeSlot& x, const EdgeSlot& y) {
      return x.key != y.key ? x.key < y.key : x.corner < y.corner;
    });
    // Fans: union (triangle, vertex) corners across manifold edges.
    const std::size_t ncorner = tris.size() * 3;
    std::vector<int> parent(ncorner);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    auto unite = [&](int x, int y) {
      x = find(x);
      y = find(y);
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    };
    auto corner_of = [&](int f, int v) {
      for (int k = 0; k < 3; ++k)
        if (tris[f][k] == v) return 3 * f + k;
      return -1;
    };
    Listing open;
    Listing nonman;
    for (std::size_t i = 0; i < es.size();) {
      std::size_t j = i;
      while (j < es.size() && es[j].key == es[i].key) ++j;
      const int n = static_cast<int>(j - i);
      const std::string name =
          "edge " + std::to_string(es[i].key[0]) + "-" + std::to_string(es[i].key[1]);
      if (n % 2 == 1)
        open.add(max_listed,
                 name + " (" + std::to_string(n) + " triangle" + (n == 1 ? "" : "s") + ")");
      else if (n >= 4)
        nonman.add(max_listed, name + " (" + std::to_string(n) + " triangles)");
      else {
        const int f0 = es[i].corner / 3;
        const int f1 = es[i + 1].corner / 3;
        for (int v : es[i].key) unite(corner_of(f0, v), corner_of(f1, v));
      }
      i = j;
    }
    d.open_edges = open.count;
    d.nonmanifold_edges = nonman.count;
    if (open.count > 0)
      d.failures.push_back("the polycube surface is not closed: " +
                           plural(open.count, "boundary edge has", "boundary edges have") +
                           " an odd number of boundary triangles (" + open.joined() + ")");
    if (nonman.count > 0)
      d.failures.push_back("the polycube surface is not manifold: " +
                           plural(nonman.count, "edge has", "edges have") +
                           " four or more boundary triangles (" + nonman.joined() + ")");
    // Vertices: count distinct fans (roots) among the corners of each vertex.
    std::vector<std::array<int, 2>> vr;  // (vertex, root)
    vr.reserve(ncorner);
    for (std::size_t k = 0; k < ncorner; ++k)
      vr.push_back({tris[k / 3][k % 3], find(static_cast<int>(k))});
    std::sort(vr.begin(), vr.end());
    vr.erase(std::unique(vr.begin(), vr.end()), vr.end());
    Listing pinched;
    for (std::size_t i = 0; i < vr.size();) {
      std::size_t j = i;
      while (j < vr.size() && vr[j][0] == vr[i][0]) ++j;
      if (j - i > 1 && open.count == 0 && nonman.count == 0)
        pinched.add(max_listed,
                    "vertex " + std::to_string(vr[i][0]) + " (" + std::to_string(j - i) + " fans)");
      i = j;
    }
    d.nonmanifold_vertices = pinched.count;
    if (pinched.count > 0)
      d.failures.push_back("the polycube surface is not manifold: " +
                           plural(pinched.count, "vertex joins", "vertices join") +
                           " several separate fans of triangles (" + pinched.joined() + ")");
  }
  return d;
}

void validate_map(const core::PolycubeMap& map, const ValidateOptions& options) {
  const MapDiagnosis d = diagnose_map(map, options);
  if (d.valid()) return;
  std::string msg = "invalid polycube map: ";
  for (std::size_t i = 0; i < d.failures.size(); ++i) {
    if (i > 0) msg += "; ";
    msg += d.failures[i];
  }
  throw core::InputError(msg);
}

}  // namespace polycube::structure
