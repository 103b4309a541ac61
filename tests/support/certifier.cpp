#include "support/certifier.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <map>

namespace polycube::test {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using core::Vec3;

Verdict independent_check(const std::vector<core::Tet>& tets, const std::vector<Vec3>& model,
                          const std::vector<Vec3>& poly, const std::vector<core::Tri>& tris,
                          const std::vector<int>& labels) {
  Verdict v;
  auto P = [](const Vec3& p) { return K::Point_3(p.x(), p.y(), p.z()); };
  std::map<std::array<int, 3>, int> face_count;
  std::map<std::array<int, 3>, std::array<int, 3>> outward;  // sorted face -> outward order
  for (const auto& t : tets) {
    if (CGAL::orientation(P(model[t[0]]), P(model[t[1]]), P(model[t[2]]), P(model[t[3]])) != CGAL::POSITIVE)
      ++v.bad_model;
    if (CGAL::orientation(P(poly[t[0]]), P(poly[t[1]]), P(poly[t[2]]), P(poly[t[3]])) != CGAL::POSITIVE)
      ++v.bad_polycube;
    const std::array<std::array<int, 3>, 4> faces{{{t[1], t[2], t[3]}, {t[0], t[3], t[2]}, {t[0], t[1], t[3]}, {t[0], t[2], t[1]}}};
    for (const auto& of : faces) {
      std::array<int, 3> k = of;
      std::sort(k.begin(), k.end());
      outward[k] = of;
    }
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      int k = 0;
      for (int i = 0; i < 4; ++i)
        if (i != skip) f[k++] = t[i];
      std::sort(f.begin(), f.end());
      ++face_count[f];
    }
  }
  std::map<std::array<int, 3>, int> label_of;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    std::array<int, 3> f{tris[i][0], tris[i][1], tris[i][2]};
    std::sort(f.begin(), f.end());
    label_of[f] = labels[i];
  }
  for (const auto& [f, n] : face_count) {
    if (n != 1) continue;
    ++v.boundary_faces;
    auto it = label_of.find(f);
    if (it == label_of.end()) {
      ++v.unlabeled;
      continue;
    }
    const int a = it->second / 2;
    if (!(poly[f[0]][a] == poly[f[1]][a] && poly[f[1]][a] == poly[f[2]][a])) ++v.off_plane;
    // Facing: the outward order of the face (from its tet) projected on the chart plane must
    // turn counter-clockwise seen from the label's direction (exact 2D orientation).
    const auto& o = outward.at(f);
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    using P2 = K::Point_2;
    const auto turn = CGAL::orientation(P2(poly[o[0]][b], poly[o[0]][c]), P2(poly[o[1]][b], poly[o[1]][c]),
                                        P2(poly[o[2]][b], poly[o[2]][c]));
    const bool plus = it->second % 2 == 0;
    if (turn != (plus ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN)) ++v.wrong_facing;
  }
  return v;
}

bool certified(const Verdict& v) {
  return v.bad_model == 0 && v.bad_polycube == 0 && v.off_plane == 0 && v.unlabeled == 0 && v.wrong_facing == 0 &&
         v.boundary_faces > 0;
}

}  // namespace polycube::test
