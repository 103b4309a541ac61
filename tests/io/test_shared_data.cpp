// The shared models (../shared/data, see its README) load with exactly the listed counts, and
// survive a round trip through every format that can hold them. Skipped when absent.
#include "fixtures.h"
#include "io/mesh_io.h"

#include <gtest/gtest.h>

namespace polycube::io {
namespace {

namespace fs = std::filesystem;

struct Model {
  const char* path;
  std::size_t vertices, triangles, quads, tets, hexes;
};

// Counts from ../shared/data/README.md.
constexpr Model kModels[] = {
    {"surface/bunny.obj", 14290, 28576, 0, 0, 0},
    {"surface/rocker-arm.obj", 10044, 20088, 0, 0, 0},
    {"surface/fandisk.obj", 6475, 12946, 0, 0, 0},
    {"surface/moai.obj", 20000, 39996, 0, 0, 0},
    {"surface/max-planck.obj", 27002, 54000, 0, 0, 0},
    {"surface/3holes.obj", 1987, 3982, 0, 0, 0},
    {"surface/B0.obj", 9984, 19964, 0, 0, 0},
    {"surface/cube_minus_sphere.obj", 2066, 4128, 0, 0, 0},
    {"surface/torus.obj", 768, 1536, 0, 0, 0},
    {"tet/B0.mesh", 999, 0, 0, 4365, 0},
    {"tet/S3.mesh", 9009, 0, 0, 43220, 0},
    {"tet/cup.mesh", 7379, 10000, 0, 30196, 0},
    {"tet/sphere.mesh", 4505, 2880, 0, 24013, 0},
    {"hex/rockerarm.mesh", 12751, 0, 4076, 0, 10600},
    {"hex/ellipsoid.mesh", 7293, 0, 0, 0, 6816},
};

class SharedModel : public ::testing::TestWithParam<Model> {};

TEST_P(SharedModel, LoadsWithReadmeCounts) {
  const Model& m = GetParam();
  const fs::path path = fs::path(POLYCUBE_DATA_DIR) / m.path;
  if (!fs::exists(path)) GTEST_SKIP() << path << " absent";
  const core::MeshData d = read_mesh(path);
  EXPECT_EQ(d.points.size(), m.vertices);
  EXPECT_EQ(d.triangles.size(), m.triangles);
  EXPECT_EQ(d.quads.size(), m.quads);
  EXPECT_EQ(d.tets.size(), m.tets);
  EXPECT_EQ(d.hexes.size(), m.hexes);
}

TEST_P(SharedModel, RoundTripsThroughCompatibleFormats) {
  const Model& m = GetParam();
  const fs::path path = fs::path(POLYCUBE_DATA_DIR) / m.path;
  if (!fs::exists(path)) GTEST_SKIP() << path << " absent";
  const core::MeshData d = read_mesh(path);
  const bool volume = m.tets + m.hexes > 0;
  const std::vector<Format> formats = volume ? std::vector<Format>{Format::Medit, Format::Vtk, Format::Msh}
                                             : std::vector<Format>{Format::Obj, Format::Off, Format::Ply, Format::Medit};
  for (const Format f : formats) {
    SCOPED_TRACE(format_name(f));
    const core::MeshData r = read_mesh_from_memory(write_mesh_to_string(d, f), f, "memory");
    EXPECT_EQ(r.triangles, d.triangles);
    EXPECT_EQ(r.quads, d.quads);
    EXPECT_EQ(r.tets, d.tets);
    EXPECT_EQ(r.hexes, d.hexes);
    test::expect_points_near(r.points, d.points, 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Data, SharedModel, ::testing::ValuesIn(kModels),
                         [](const ::testing::TestParamInfo<Model>& p) {
                           std::string n = p.param.path;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace polycube::io
