#include "core/polycube_map.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace polycube::core {

namespace {

TetMesh mesh_with(const std::vector<Tet>& tets, const std::vector<Vec3>& points) {
  TetMesh m;
  m.points = points;
  m.cells = tets;
  return m;
}

std::string tet_string(const Tet& t) {
  return std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " " +
         std::to_string(t[3]);
}

}  // namespace

const char* label_name(int label) {
  static constexpr const char* kNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  return (label >= 0 && label < 6) ? kNames[label] : "?";
}

const char* axis_name(int axis) {
  static constexpr const char* kNames[3] = {"x", "y", "z"};
  return (axis >= 0 && axis < 3) ? kNames[axis] : "?";
}

Vec3 label_direction(int label) {
  PC_REQUIRE(label >= 0 && label < 6, "label out of range");
  Vec3 d = Vec3::Zero();
  d[label_axis(label)] = (label % 2 == 0) ? 1.0 : -1.0;
  return d;
}

bool faces_label(const std::vector<Vec3>& P, const Tri& t, int label) {
  return (P[t[1]] - P[t[0]]).cross(P[t[2]] - P[t[0]]).dot(label_direction(label)) > 0;
}

int dominant_axis_label(const Vec3& n) {
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(n[a]) > std::abs(n[axis])) axis = a;
  return axis_label(axis, n[axis] < 0.0 ? -1 : 1);
}

TetMesh PolycubeMap::model_mesh() const { return mesh_with(tets, model); }
TetMesh PolycubeMap::polycube_mesh() const { return mesh_with(tets, polycube); }

PolycubeMap make_polycube_map(const TetMesh& model, const TetMesh& polycube) {
  if (model.num_points() != polycube.num_points())
    throw InputError("polycube map: the model has " + std::to_string(model.num_points()) +
                     " vertices but the polycube has " + std::to_string(polycube.num_points()));
  if (model.num_cells() != polycube.num_cells())
    throw InputError("polycube map: connectivity differs: the model has " +
                     std::to_string(model.num_cells()) + " tets but the polycube has " +
                     std::to_string(polycube.num_cells()));
  for (int t = 0; t < model.num_cells(); ++t) {
    const auto& a = model.cells[static_cast<std::size_t>(t)];
    const auto& b = polycube.cells[static_cast<std::size_t>(t)];
    if (a != b)
      throw InputError("polycube map: connectivity differs: tet " + std::to_string(t) + " is (" +
                       tet_string(a) + ") in the model but (" + tet_string(b) +
                       ") in the polycube");
  }
  PolycubeMap map;
  map.tets = model.cells;
  map.model = model.points;
  map.polycube = polycube.points;
  return map;
}

void check_map_indices(const PolycubeMap& map) {
  if (map.model.size() != map.polycube.size())
    throw InputError("polycube map: " + std::to_string(map.model.size()) + " model positions but " +
                     std::to_string(map.polycube.size()) + " polycube positions");
  if (map.tets.empty()) throw InputError("polycube map: no tetrahedra");
  const int nv = map.num_vertices();
  for (int t = 0; t < map.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) {
      const int v = map.tets[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
      if (v < 0 || v >= nv)
        throw InputError("polycube map: tet " + std::to_string(t) + " references vertex " +
                         std::to_string(v) + " outside [0, " + std::to_string(nv) + ")");
    }
  for (int v = 0; v < nv; ++v) {
    if (!map.model[static_cast<std::size_t>(v)].allFinite())
      throw InputError("polycube map: model position of vertex " + std::to_string(v) +
                       " is not finite");
    if (!map.polycube[static_cast<std::size_t>(v)].allFinite())
      throw InputError("polycube map: polycube position of vertex " + std::to_string(v) +
                       " is not finite");
  }
}

}  // namespace polycube::core
