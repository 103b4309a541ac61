#include "io/polycube_map_io.h"

#include "core/elements.h"
#include "core/errors.h"
#include "io/mesh_io.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace polycube::io {

namespace {

std::string tet_string(const core::Tet& t) {
  return "(" + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
         " " + std::to_string(t[3]) + ")";
}

//! Faces of exactly one tet, by tet then local face, in their local (outward) order. Unlike
//! core::boundary this accepts faces shared by three or more tets (they are interior), so an
//! invalid map can still be written for inspection.
std::vector<core::Tri> boundary_triangles(const std::vector<core::Tet>& tets) {
  struct Slot {
    std::array<int, 3> key;
    int slot;
  };
  std::vector<Slot> slots;
  slots.reserve(tets.size() * 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      const auto& lf = core::kTetFaces[static_cast<std::size_t>(k)];
      std::array<int, 3> key{tets[t][lf[0]], tets[t][lf[1]], tets[t][lf[2]]};
      std::sort(key.begin(), key.end());
      slots.push_back({key, static_cast<int>(4 * t) + k});
    }
  std::sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) {
    return a.key != b.key ? a.key < b.key : a.slot < b.slot;
  });
  std::vector<int> single;
  for (std::size_t i = 0; i < slots.size();) {
    std::size_t j = i + 1;
    while (j < slots.size() && slots[j].key == slots[i].key) ++j;
    if (j - i == 1) single.push_back(slots[i].slot);
    i = j;
  }
  std::sort(single.begin(), single.end());
  std::vector<core::Tri> out;
  out.reserve(single.size());
  for (int s : single) {
    const auto& t = tets[static_cast<std::size_t>(s / 4)];
    const auto& lf = core::kTetFaces[static_cast<std::size_t>(s % 4)];
    out.push_back({t[lf[0]], t[lf[1]], t[lf[2]]});
  }
  return out;
}

}  // namespace

core::PolycubeMap read_polycube_map(const std::filesystem::path& model_path,
                                    const std::filesystem::path& polycube_path) {
  const core::MeshData a = read_mesh(model_path);
  const core::MeshData b = read_mesh(polycube_path);
  const std::string an = model_path.string();
  const std::string bn = polycube_path.string();
  if (a.tets.empty())
    throw core::InputError(an + ": no tetrahedra (a polycube map needs a tet mesh)");
  if (b.tets.empty())
    throw core::InputError(bn + ": no tetrahedra (a polycube map needs a tet mesh)");
  if (a.points.size() != b.points.size())
    throw core::InputError(
        "polycube map: vertex counts differ: " + std::to_string(a.points.size()) + " in " + an +
        " but " + std::to_string(b.points.size()) + " in " + bn);
  if (a.tets.size() != b.tets.size())
    throw core::InputError("polycube map: connectivity differs: " + std::to_string(a.tets.size()) +
                           " tets in " + an + " but " + std::to_string(b.tets.size()) + " in " +
                           bn);
  for (std::size_t t = 0; t < a.tets.size(); ++t)
    if (a.tets[t] != b.tets[t])
      throw core::InputError("polycube map: connectivity differs: tet " + std::to_string(t) +
                             " is " + tet_string(a.tets[t]) + " in " + an + " but " +
                             tet_string(b.tets[t]) + " in " + bn);
  core::PolycubeMap map;
  map.tets = a.tets;
  map.model = a.points;
  map.polycube = b.points;
  core::check_map_indices(map);
  return map;
}

void write_polycube_map(const std::filesystem::path& model_path,
                        const std::filesystem::path& polycube_path, const core::PolycubeMap& map) {
  core::check_map_indices(map);
  core::MeshData d;
  d.tets = map.tets;
  d.tet_labels.assign(map.tets.size(), 0);
  for (const core::Tri& tri : boundary_triangles(map.tets)) {
    const core::Vec3& p0 = map.polycube[tri[0]];
    d.triangles.push_back(tri);
    d.triangle_labels.push_back(
        core::dominant_axis_label((map.polycube[tri[1]] - p0).cross(map.polycube[tri[2]] - p0)));
  }
  d.points = map.model;
  write_mesh(model_path, d);
  d.points = map.polycube;
  write_mesh(polycube_path, d);
}

}  // namespace polycube::io
