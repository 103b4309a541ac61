// Round trips of every format in memory and on disk, and the readers' tolerance of real-world
// variants (hand-written files).
#include "core/errors.h"
#include "core/log.h"
#include "fixtures.h"
#include "io/mesh_io.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace polycube::io {
namespace {

using test::expect_points_near;

core::MeshData round_trip(const core::MeshData& d, Format f, bool binary = false, bool double_precision = false) {
  WriteOptions o;
  o.binary = binary;
  o.double_precision = double_precision;
  const std::string bytes = write_mesh_to_string(d, f, o, "test");
  return read_mesh_from_memory(bytes, f, "test");
}

std::string bytes_of(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (auto p : parts) s += p;
  return s;
}

template <class T>
void append(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

// --- round trips ------------------------------------------------------------------------------

struct SurfaceCase {
  Format format;
  bool binary;
  bool double_precision = false;
  double tolerance = 1e-12;  //!< relative: text and doubles keep every digit, binary PLY is float by default
};

class SurfaceRoundTrip : public ::testing::TestWithParam<SurfaceCase> {};

TEST_P(SurfaceRoundTrip, KeepsCountsConnectivityAndCoordinates) {
  const SurfaceCase c = GetParam();
  for (const core::MeshData& d : {test::mixed_surface(), test::cube_quads()}) {
    const core::MeshData r = round_trip(d, c.format, c.binary, c.double_precision);
    EXPECT_EQ(r.triangles, d.triangles);
    EXPECT_EQ(r.quads, d.quads);
    EXPECT_TRUE(r.tets.empty() && r.hexes.empty());
    expect_points_near(r.points, d.points, c.tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceRoundTrip,
                         ::testing::Values(SurfaceCase{Format::Obj, false}, SurfaceCase{Format::Off, false},
                                           SurfaceCase{Format::Ply, false}, SurfaceCase{Format::Ply, true, false, 0x1p-24},
                                           SurfaceCase{Format::Ply, true, true},
                                           SurfaceCase{Format::Medit, false}, SurfaceCase{Format::Vtk, false},
                                           SurfaceCase{Format::Msh, false}));

TEST(StlRoundTrip, SinglePrecisionAndQuadsSplit) {
  for (const bool binary : {false, true}) {
    const core::MeshData d = test::mixed_surface();
    const core::MeshData r = round_trip(d, Format::Stl, binary);
    // Quads become two triangles; vertices are merged back to the same count.
    ASSERT_EQ(r.triangles.size(), d.triangles.size() + 2 * d.quads.size());
    EXPECT_TRUE(r.quads.empty());
    EXPECT_EQ(r.points.size(), d.points.size());
    // Triangle by triangle, same corner positions to single precision (one float ulp: the
    // ASCII path rounds to float, prints the shortest decimal, and parses it as a double).
    std::vector<core::Tri> expected = d.triangles;
    for (const core::Quad& q : d.quads) {
      expected.push_back({q[0], q[1], q[2]});
      expected.push_back({q[0], q[2], q[3]});
    }
    for (std::size_t t = 0; t < expected.size(); ++t)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) {
          const double a = d.points[expected[t][c]][k];
          const double b = r.points[r.triangles[t][c]][k];
          EXPECT_LE(std::abs(a - b), 0x1p-23 * std::max(1.0, std::abs(a))) << "binary=" << binary;
        }
  }
}

TEST(VolumeRoundTrip, MeditKeepsEverythingItCanHold) {
  const core::MeshData d = test::volume_mesh();
  const core::MeshData r = round_trip(d, Format::Medit);
  expect_points_near(r.points, d.points, 1e-12);
  EXPECT_EQ(r.edges, d.edges);
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.quads, d.quads);
  EXPECT_EQ(r.tets, d.tets);
  EXPECT_EQ(r.hexes, d.hexes);
  EXPECT_EQ(r.edge_labels, d.edge_labels);
  EXPECT_EQ(r.triangle_labels, d.triangle_labels);
  EXPECT_EQ(r.quad_labels, d.quad_labels);
  EXPECT_EQ(r.tet_labels, d.tet_labels);
  EXPECT_EQ(r.hex_labels, d.hex_labels);
  EXPECT_EQ(r.point_labels, d.point_labels);
  EXPECT_TRUE(r.point_data.empty() && r.cell_data.empty());  // MEDIT has no place for fields
}

TEST(VolumeRoundTrip, VtkKeepsCellsLabelsAndFields) {
  const core::MeshData d = test::volume_mesh();
  const core::MeshData r = round_trip(d, Format::Vtk);
  expect_points_near(r.points, d.points, 1e-12);
  EXPECT_TRUE(r.edges.empty());  // VTK cells here are 2D/3D only
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.quads, d.quads);
  EXPECT_EQ(r.tets, d.tets);
  EXPECT_EQ(r.hexes, d.hexes);
  EXPECT_EQ(r.triangle_labels, d.triangle_labels);
  EXPECT_EQ(r.quad_labels, d.quad_labels);
  EXPECT_EQ(r.tet_labels, d.tet_labels);
  EXPECT_EQ(r.hex_labels, d.hex_labels);
  EXPECT_EQ(r.point_labels, d.point_labels);
  ASSERT_EQ(r.point_data.size(), 1u);
  ASSERT_EQ(r.cell_data.size(), 1u);
  EXPECT_EQ(r.point_data[0].name, "temperature");
  EXPECT_EQ(r.cell_data[0].name, "quality");
  ASSERT_EQ(r.point_data[0].values.size(), d.point_data[0].values.size());
  ASSERT_EQ(r.cell_data[0].values.size(), d.cell_data[0].values.size());
  for (std::size_t i = 0; i < d.point_data[0].values.size(); ++i)
    EXPECT_DOUBLE_EQ(r.point_data[0].values[i], d.point_data[0].values[i]);
  for (std::size_t i = 0; i < d.cell_data[0].values.size(); ++i)
    EXPECT_DOUBLE_EQ(r.cell_data[0].values[i], d.cell_data[0].values[i]);
}

TEST(VolumeRoundTrip, MshKeepsCellsEdgesAndLabels) {
  const core::MeshData d = test::volume_mesh();
  const core::MeshData r = round_trip(d, Format::Msh);
  expect_points_near(r.points, d.points, 1e-12);
  EXPECT_EQ(r.edges, d.edges);
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.quads, d.quads);
  EXPECT_EQ(r.tets, d.tets);
  EXPECT_EQ(r.hexes, d.hexes);
  EXPECT_EQ(r.edge_labels, d.edge_labels);
  EXPECT_EQ(r.triangle_labels, d.triangle_labels);
  EXPECT_EQ(r.quad_labels, d.quad_labels);
  EXPECT_EQ(r.tet_labels, d.tet_labels);
  EXPECT_EQ(r.hex_labels, d.hex_labels);

  // Without labels, no $Entities: the read-back has no labels either.
  core::MeshData plain = d;
  plain.edge_labels.clear();
  plain.triangle_labels.clear();
  plain.quad_labels.clear();
  plain.tet_labels.clear();
  plain.hex_labels.clear();
  const core::MeshData p = round_trip(plain, Format::Msh);
  EXPECT_EQ(p.tets, d.tets);
  EXPECT_TRUE(p.tet_labels.empty() && p.hex_labels.empty());
}

TEST(VolumeRoundTrip, WritingIsDeterministic) {
  const core::MeshData d = test::volume_mesh();
  for (const Format f : {Format::Medit, Format::Vtk, Format::Msh})
    EXPECT_EQ(write_mesh_to_string(d, f), write_mesh_to_string(d, f));
}

TEST(Writers, RefuseWhatTheFormatCannotHold) {
  const core::MeshData d = test::volume_mesh();
  for (const Format f : {Format::Obj, Format::Off, Format::Stl, Format::Ply})
    EXPECT_THROW(write_mesh_to_string(d, f), core::InputError) << format_name(f);
  core::MeshData bad = test::mixed_surface();
  bad.triangles[0][1] = 99;
  EXPECT_THROW(write_mesh_to_string(bad, Format::Medit), core::InputError);
  bad = test::mixed_surface();
  bad.points[2].y() = std::nan("");
  EXPECT_THROW(write_mesh_to_string(bad, Format::Obj), core::InputError);
  EXPECT_THROW(write_mesh_to_string(core::MeshData{}, Format::Obj), core::InputError);
  bad = test::mixed_surface();
  bad.points[0].x() = 1e300;  // fine in double, not in STL's single precision
  EXPECT_NO_THROW(write_mesh_to_string(bad, Format::Ply));
  EXPECT_THROW(write_mesh_to_string(bad, Format::Stl), core::InputError);
}

TEST(Writers, LabelingIsOneLabelPerLine) {
  test::TempDir dir("labeling");
  write_labeling(dir / "labeling.txt", {0, 5, 2, 3});
  std::ifstream in(dir / "labeling.txt", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "0\n5\n2\n3\n");
  EXPECT_THROW(write_labeling(dir / "bad.txt", {0, 6}), core::InternalError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.txt"));
}

TEST(Writers, AtomicAndNoLeftovers) {
  test::TempDir dir("atomic");
  const auto target = dir / "m.mesh";
  write_mesh(target, test::volume_mesh());
  write_mesh(target, test::volume_mesh());  // overwrite
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(e.path().filename(), "m.mesh");
  }
  EXPECT_EQ(files, 1);
  // Refused content and a missing folder: InputError, and nothing created.
  EXPECT_THROW(write_mesh(dir / "v.obj", test::volume_mesh()), core::InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "v.obj"));
  EXPECT_THROW(write_mesh(dir / "no" / "such" / "m.mesh", test::volume_mesh()), core::InputError);
  EXPECT_THROW(write_mesh(dir.path(), test::volume_mesh()), core::InputError);
  write_text_atomic(dir / "a.txt", "1\n2\n");
  std::ifstream in(dir / "a.txt");
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(all, "1\n2\n");
}

TEST(Formats, FromPathIsCaseInsensitive) {
  EXPECT_EQ(format_from_path("a/B.OBJ"), Format::Obj);
  EXPECT_EQ(format_from_path("x.Mesh"), Format::Medit);
  EXPECT_EQ(format_from_path("x.msh"), Format::Msh);
  EXPECT_THROW(format_from_path("x.meshb"), core::InputError);
  EXPECT_THROW(format_from_path("noext"), core::InputError);
  EXPECT_TRUE(is_volume_format(Format::Vtk));
  EXPECT_FALSE(is_volume_format(Format::Stl));
}

TEST(ReadSurface, SplitsQuadsAndKeepsLabels) {
  test::TempDir dir("surface");
  core::MeshData d = test::mixed_surface();
  d.triangle_labels.assign(d.triangles.size(), 4);
  d.quad_labels = {8};
  write_mesh(dir / "s.mesh", d);
  const core::TriMesh m = read_surface(dir / "s.mesh");
  ASSERT_EQ(m.cells.size(), d.triangles.size() + 2);
  EXPECT_EQ(m.cells.back(), (core::Tri{6, 8, 9}));
  ASSERT_EQ(m.labels.size(), m.cells.size());
  EXPECT_EQ(m.labels.back(), 8);
  write_mesh(dir / "t.mesh", core::to_mesh_data(core::tets_of(test::volume_mesh())));
  EXPECT_THROW(read_surface(dir / "t.mesh"), core::InputError);
}

// --- reader variants --------------------------------------------------------------------------

TEST(Obj, NegativeIndicesSlashesPolygonsAndIgnoredStatements) {
  const std::string s =
      "# comment\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nv 0.5 1.5 0\n"
      "vt 0 0\nvn 0 0 1\ng group\nusemtl m\ns off\n"
      "f 1/1/1 2/1/1 3/1/1\nf -5//1 -3//1 -2//1   # relative\nf 1 2 3 5 4\nl 1 2\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Obj, "t.obj");
  ASSERT_EQ(d.points.size(), 5u);
  EXPECT_EQ(d.points[2], core::Vec3(1, 1, 0));
  // The pentagon is fan-triangulated: 3 triangles from its first vertex.
  const std::vector<core::Tri> expected{{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 4}, {0, 4, 3}};
  EXPECT_EQ(d.triangles, expected);
  EXPECT_TRUE(d.quads.empty());
}

TEST(Obj, StatementsOBJDoesNotDefineAreSkippedWithOneWarningPerKind) {
  std::ostringstream log;
  core::set_logger(std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  // A UTF-8 byte order mark, a vendor extension and a curve statement around a clean triangle.
  const std::string s = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nc 1 2\nv 0 1 0\nxyz_ext a b\nc 3\nf 1 2 3\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Obj, "t.obj");
  core::set_logger(nullptr);
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.points[0], core::Vec3(0, 0, 0));
  EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
  const std::string text = log.str();
  EXPECT_NE(text.find("skipped 2 line(s) with the statement 'c'"), std::string::npos) << text;
  EXPECT_NE(text.find("skipped 1 line(s) with the statement 'xyz_ext'"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;
  // Only unknown statements and no face: not an OBJ file, one error.
  EXPECT_THROW(read_mesh_from_memory("hello world\nthis is prose\n", Format::Obj, "t.obj"), core::InputError);
  // A BOM before any text format's content is ignored.
  EXPECT_EQ(read_mesh_from_memory("\xEF\xBB\xBFOFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", Format::Off, "x")
                .triangles.size(),
            1u);
}

TEST(Off, VariantsCommentsAndColours) {
  const std::string s =
      "COFF # coloured\n# a comment line\n\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n"
      "0 1 0 9 9 9 255\n3 0 1 2 0.5 0.5 0.5\n4 0 1 2 3\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Off, "t.off");
  EXPECT_EQ(d.points.size(), 4u);
  EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
  EXPECT_EQ(d.quads, (std::vector<core::Quad>{{0, 1, 2, 3}}));
  const core::MeshData one_line = read_mesh_from_memory("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", Format::Off, "x");
  EXPECT_EQ(one_line.triangles.size(), 1u);
}

TEST(Stl, BinaryStartingWithSolidAndExactMerging) {
  std::string s = "solid but actually binary";
  s.resize(80, ' ');
  append(s, std::uint32_t{2});
  const float tris[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1, 0, -0.0f, 1, 0}};
  for (const auto& t : tris) {
    for (const float v : t) append(s, v);
    append(s, std::uint16_t{0});
  }
  const core::MeshData d = read_mesh_from_memory(s, Format::Stl, "t.stl");
  EXPECT_EQ(d.triangles.size(), 2u);
  EXPECT_EQ(d.points.size(), 4u);  // (1,0,0) and (0,1,0) shared; -0 equals +0
  EXPECT_EQ(d.triangles[1], (core::Tri{1, 3, 2}));

  const std::string ascii =
      "solid a\nfacet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid a\nsolid b\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n"
      "endfacet\nendsolid b\n";
  const core::MeshData a = read_mesh_from_memory(ascii, Format::Stl, "a.stl");
  EXPECT_EQ(a.triangles.size(), 2u);
  EXPECT_EQ(a.points.size(), 4u);
}

TEST(Ply, BinaryWithExtraPropertiesAndElements) {
  for (const bool big : {false, true}) {
    std::string s = bytes_of({"ply\nformat ", big ? "binary_big_endian" : "binary_little_endian",
                              " 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty uchar red\n"
                              "property float y\nproperty double z\nproperty list uchar float junk\n"
                              "element face 2\nproperty uchar flags\nproperty list uint ushort vertex_indices\n"
                              "element material 1\nproperty int id\nend_header\n"});
    auto put = [&](auto v) {
      char b[sizeof(v)];
      std::memcpy(b, &v, sizeof(v));
      if (big) std::reverse(b, b + sizeof(v));
      s.append(b, sizeof(v));
    };
    const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
      put(xy[i][0]);
      put(std::uint8_t{200});
      put(xy[i][1]);
      put(0.25 * i);
      put(std::uint8_t{2});
      put(1.5f);
      put(2.5f);
    }
    put(std::uint8_t{1});
    put(std::uint32_t{3});
    for (const std::uint16_t v : {0, 1, 2}) put(v);
    put(std::uint8_t{1});
    put(std::uint32_t{4});
    for (const std::uint16_t v : {0, 1, 2, 3}) put(v);
    put(std::int32_t{7});
    const core::MeshData d = read_mesh_from_memory(s, Format::Ply, "t.ply");
    ASSERT_EQ(d.points.size(), 4u);
    EXPECT_EQ(d.points[2], core::Vec3(1, 1, 0.5));
    EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
    EXPECT_EQ(d.quads, (std::vector<core::Quad>{{0, 1, 2, 3}}));
  }
}

TEST(Ply, EmptyElementsWithoutProperties) {
  // Found by fuzzing: an element with no properties and a zero count must not divide by zero.
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element nothing 0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_mesh_from_memory(s, Format::Ply, "t.ply").triangles.size(), 1u);
}

TEST(Medit, ToleratesLayoutCommentsEmptyAndSkippedBlocks) {
  const std::string s =
      "   MeshVersionFormatted 1\n # comment\n  Dimension\n 3\n\n Vertices\n 4\n"
      "  0 0 0 1\n  1 0 0 1\n  0 1 0 2\n  0 0 1 2\n"
      "Edges\n0\nCorners\n2\n1 2\nRidges 1 1\nRequiredVertices\n1\n4\nNormals\n1\n0 0 1\n"
      "NormalAtVertices\n1\n1 1\nTriangles\n1\n1 2 3 5\nTetrahedra # the only tet\n1\n 1 2 3 4 7\n End\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Medit, "t.mesh");
  EXPECT_EQ(d.points.size(), 4u);
  EXPECT_EQ(d.point_labels, (std::vector<int>{1, 1, 2, 2}));
  EXPECT_TRUE(d.edges.empty());
  EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
  EXPECT_EQ(d.triangle_labels, (std::vector<int>{5}));
  EXPECT_EQ(d.tets, (std::vector<core::Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(d.tet_labels, (std::vector<int>{7}));
}

TEST(Vtk, InterleavedCellsReorderCellDataAndFieldArrays) {
  const std::string s =
      "# vtk DataFile Version 4.2\nwritten by hand\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "FIELD FieldData 1\nTIME 1 1 double\n0.5\n"
      "POINTS 5 float\n0 0 0 1 0 0 0 1 0\n0 0 1 1 1 1\n"
      "CELLS 3 14\n4 0 1 2 3\n3 0 1 2\n4 1 2 3 4\nCELL_TYPES 3\n10\n5\n10\n"
      "CELL_DATA 3\nSCALARS id int\n7 8 9\nVECTORS v double\n1 0 0 0 1 0 0 0 1\n"
      "FIELD arrays 2\nw 1 3 float\n0.1 0.2 0.3\nskip 2 3 int\n1 2 3 4 5 6\n"
      "POINT_DATA 5\nSCALARS label int 1\nLOOKUP_TABLE default\n1 2 3 4 5\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Vtk, "t.vtk");
  EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
  EXPECT_EQ(d.tets, (std::vector<core::Tet>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
  ASSERT_EQ(d.cell_data.size(), 2u);
  EXPECT_EQ(d.cell_data[0].name, "id");
  EXPECT_EQ(d.cell_data[0].values, (std::vector<double>{8, 7, 9}));  // triangle first, then tets
  EXPECT_EQ(d.cell_data[1].name, "w");
  EXPECT_EQ(d.point_labels, (std::vector<int>{1, 2, 3, 4, 5}));
}

// VTK 9 and ParaView write legacy version 5.1: cells as OFFSETS and CONNECTIVITY arrays.
TEST(Vtk, Version51OffsetsAndConnectivity) {
  const std::string s =
      "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 5 float\n0 0 0 1 0 0 0 1 0\n0 0 1 1 1 1\n"
      "CELLS 4 11\nOFFSETS vtktypeint64\n0 4 7 11\nCONNECTIVITY vtktypeint64\n0 1 2 3\n0 1 2\n1 2 3 4\n"
      "CELL_TYPES 3\n10\n5\n10\n"
      "CELL_DATA 3\nFIELD FieldData 1\nlabel 1 3 vtktypeint64\n7 8 9\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Vtk, "t.vtk");
  EXPECT_EQ(d.triangles, (std::vector<core::Tri>{{0, 1, 2}}));
  EXPECT_EQ(d.tets, (std::vector<core::Tet>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
  EXPECT_EQ(d.triangle_labels, (std::vector<int>{8}));
  EXPECT_EQ(d.tet_labels, (std::vector<int>{7, 9}));
  // An offset list that does not end at the connectivity's size is refused with the numbers.
  std::string bad = s;
  bad.replace(bad.find("0 4 7 11"), 8, "0 4 7 10");
  EXPECT_THROW(read_mesh_from_memory(bad, Format::Vtk, "t.vtk"), core::InputError);
}

// Our .msh groups elements into one block per type and label (what meshio and Gmsh expect),
// and the element tags keep the mesh's own order: a round trip gives the cells back in order.
TEST(Msh, BlocksPerTypeAndLabelTagsKeepTheOrder) {
  core::MeshData d = test::volume_mesh();
  d.tet_labels = {3, -4, 3};  // interleaved labels: two blocks, order restored from the tags
  d.triangle_labels = {0, 7};
  const std::string text = write_mesh_to_string(d, Format::Msh, {}, "t.msh");
  const std::size_t elements = text.find("$Elements\n");
  ASSERT_NE(elements, std::string::npos);
  // edges (one label), triangles (2), quads (1), tets (2), hexes (2): 8 blocks.
  EXPECT_EQ(text.compare(elements + 10, 2, "8 "), 0) << text.substr(elements, 40);
  const core::MeshData r = read_mesh_from_memory(text, Format::Msh, "t.msh");
  EXPECT_EQ(r.tets, d.tets);
  EXPECT_EQ(r.tet_labels, d.tet_labels);
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.triangle_labels, d.triangle_labels);
  EXPECT_EQ(r.hexes, d.hexes);
  // Every entity has a physical tag, 0 included.
  const std::string entities = text.substr(text.find("$Entities"), text.find("$EndEntities") - text.find("$Entities"));
  EXPECT_NE(entities.find(" 1 0 0\n"), std::string::npos) << entities;
}

TEST(Msh, SparseTagsSeveralBlocksParametricNodesAndPhysicalGroups) {
  const std::string s =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 5 \"the volume\"\n$EndPhysicalNames\n"
      "$Entities\n1 0 0 1\n1 0 0 0 0\n1 0 0 0 1 1 1 1 5 0\n$EndEntities\n"
      "$Nodes\n2 5 10 100000\n0 1 0 1\n100000\n0 0 0\n3 1 1 4\n10\n20\n30\n40\n1 0 0 0.1 0.2 0.3\n0 1 0 0 0 0\n"
      "0 0 1 0 0 0\n1 1 1 0 0 0\n$EndNodes\n"
      "$Elements\n2 3 1 3\n0 1 15 1\n1 100000\n3 1 4 2\n5 100000 10 20 30\n6 10 20 30 40\n$EndElements\n"
      "$NodeData\n1\n\"x\"\n1\n0.0\n3\n0\n1\n5\n100000 1\n10 1\n20 1\n30 1\n40 1\n$EndNodeData\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Msh, "t.msh");
  ASSERT_EQ(d.points.size(), 5u);
  EXPECT_EQ(d.points[1], core::Vec3(1, 0, 0));
  EXPECT_EQ(d.tets, (std::vector<core::Tet>{{0, 1, 2, 3}, {1, 2, 3, 4}}));
  EXPECT_EQ(d.tet_labels, (std::vector<int>{5, 5}));
}

TEST(Readers, BadInputThrowsInputErrorWithFileAndLine) {
  try {
    read_mesh_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", Format::Obj, "m.obj");
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    EXPECT_STREQ(e.what(), "m.obj:4: vertex index 4 out of range (1..3)");
  }
  EXPECT_THROW(read_mesh("/no/such/file.obj"), core::InputError);
}

}  // namespace
}  // namespace polycube::io

namespace polycube::io {
namespace {

// The small files of tests/data/io (also the fuzzers' seeds) load in every format with the
// same counts, and hexes and tets keep the canonical positive orientation of core/elements.h.
TEST(SampleFiles, SameMeshInEveryFormat) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(POLYCUBE_TEST_DATA_DIR) / "io";
  struct Expect {
    const char* file;
    std::size_t points, triangles, quads, tets, hexes;
  };
  const Expect cases[] = {
      {"box.obj", 12, 0, 10, 0, 0},         {"box.off", 12, 0, 10, 0, 0},         {"box.ply", 12, 0, 10, 0, 0},
      {"box_binary.ply", 12, 0, 10, 0, 0},  {"box.stl", 12, 20, 0, 0, 0},         {"box_binary.stl", 12, 20, 0, 0, 0},
      {"two_hexes.mesh", 12, 0, 10, 0, 2},  {"two_hexes.vtk", 12, 0, 10, 0, 2},   {"two_hexes.msh", 12, 0, 10, 0, 2},
      {"tet.mesh", 5, 2, 0, 2, 0},          {"tet.vtk", 5, 2, 0, 2, 0},           {"tet.msh", 5, 2, 0, 2, 0}};
  for (const Expect& e : cases) {
    SCOPED_TRACE(e.file);
    const core::MeshData d = read_mesh(dir / e.file);
    EXPECT_EQ(d.points.size(), e.points);
    EXPECT_EQ(d.triangles.size(), e.triangles);
    EXPECT_EQ(d.quads.size(), e.quads);
    EXPECT_EQ(d.tets.size(), e.tets);
    EXPECT_EQ(d.hexes.size(), e.hexes);
    for (const core::Hex& h : d.hexes) {
      const auto& p = d.points;
      const double det = (p[h[1]] - p[h[0]]).dot((p[h[3]] - p[h[0]]).cross(p[h[4]] - p[h[0]]));
      EXPECT_GT(det, 0.0);
    }
    for (const core::Tet& t : d.tets) {
      const auto& p = d.points;
      EXPECT_GT((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])), 0.0);
    }
    if (e.hexes > 0) {  // labels survive MEDIT -> VTK ("label" cell data) and -> MSH (physical tags)
      EXPECT_EQ(d.hex_labels, (std::vector<int>{1, 2}));
      EXPECT_EQ(d.quad_labels, (std::vector<int>{1, 1, 2, 2, 3, 3, 4, 5, 5, 6}));
    }
  }
}

}  // namespace
}  // namespace polycube::io
