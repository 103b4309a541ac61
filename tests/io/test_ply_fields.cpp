// PLY point and cell data: vertex and face properties round trip, colours as uchar, the cell
// order kept through fanned polygons, and (with python3-vtk9) VTK's own PLY reader seeing the
// face colours.
#include "core/errors.h"
#include "fixtures.h"
#include "io/mesh_io.h"

#include "support/files.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace polycube::io {
namespace {

namespace fs = std::filesystem;
using polycube::test::slurp;
using test::expect_points_near;

//! The mixed surface (8 triangles, 1 quad) with a face colour, a scalar face field and a
//! vertex field.
core::MeshData coloured_surface() {
  core::MeshData d = test::mixed_surface();
  const std::size_t n = d.num_cells();
  core::Field red{"red", {}}, green{"green", {}}, blue{"blue", {}}, quality{"quality", {}};
  for (std::size_t c = 0; c < n; ++c) {
    red.values.push_back(static_cast<double>((37 * c) % 256));
    green.values.push_back(c % 2 == 0 ? 255.0 : 0.0);
    blue.values.push_back(static_cast<double>(c));
    quality.values.push_back(1.0 / (static_cast<double>(c) + 3.0));
  }
  d.cell_data = {red, green, blue, quality};
  core::Field temperature{"temperature", {}};
  for (const core::Vec3& p : d.points) temperature.values.push_back(p.x() / 7.0 - p.z());
  d.point_data = {temperature};
  return d;
}

//! \p a read back from \p b written: exact (shortest decimals, or raw doubles), or each value
//! rounded to float when the file holds floats (binary PLY's default).
void expect_same_fields(const std::vector<core::Field>& a, const std::vector<core::Field>& b, bool as_float = false) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t f = 0; f < a.size(); ++f) {
    EXPECT_EQ(a[f].name, b[f].name);
    std::vector<double> expected = b[f].values;
    if (as_float)
      for (double& v : expected) v = static_cast<double>(static_cast<float>(v));
    EXPECT_EQ(a[f].values, expected) << a[f].name;
  }
}

std::string header_of(const std::string& ply) { return ply.substr(0, ply.find("end_header")); }

//! ASCII, binary with doubles, binary with floats (binary's default).
enum class PlyKind { Ascii, BinaryDouble, BinaryFloat };

WriteOptions options_of(PlyKind k) {
  WriteOptions o;
  o.binary = k != PlyKind::Ascii;
  o.double_precision = k == PlyKind::BinaryDouble;
  return o;
}

class PlyFields : public ::testing::TestWithParam<PlyKind> {};

TEST_P(PlyFields, RoundTripKeepsPointAndCellData) {
  const core::MeshData d = coloured_surface();
  const bool as_float = GetParam() == PlyKind::BinaryFloat;
  const std::string ply = write_mesh_to_string(d, Format::Ply, options_of(GetParam()));
  const std::string header = header_of(ply);
  const std::string real = as_float ? "float" : "double";
  for (const std::string& line :
       {std::string("property uchar red\n"), std::string("property uchar green\n"), std::string("property uchar blue\n"),
        "property " + real + " quality\n", "property " + real + " temperature\n", "property " + real + " x\n"})
    EXPECT_NE(header.find(line), std::string::npos) << line << header;

  const core::MeshData r = read_mesh_from_memory(ply, Format::Ply, "t.ply");
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.quads, d.quads);
  expect_same_fields(r.cell_data, d.cell_data, as_float);
  expect_same_fields(r.point_data, d.point_data, as_float);
}

TEST_P(PlyFields, RoundTripThroughAFile) {
  test::TempDir dir("ply_fields");
  const fs::path file = dir / "coloured.ply";
  const core::MeshData d = coloured_surface();
  write_mesh(file, d, options_of(GetParam()));
  const core::MeshData r = read_mesh(file);
  expect_same_fields(r.cell_data, d.cell_data, GetParam() == PlyKind::BinaryFloat);
  expect_same_fields(r.point_data, d.point_data, GetParam() == PlyKind::BinaryFloat);
}

INSTANTIATE_TEST_SUITE_P(AsciiAndBinary, PlyFields,
                         ::testing::Values(PlyKind::Ascii, PlyKind::BinaryDouble, PlyKind::BinaryFloat),
                         [](const auto& p) {
                           return p.param == PlyKind::Ascii ? "Ascii" : p.param == PlyKind::BinaryDouble ? "BinaryDouble" : "BinaryFloat";
                         });

TEST(PlyFieldsRead, FannedPolygonsAndCellOrder) {
  // A quad, a pentagon (fanned into 3 triangles) and a triangle, in that file order: the
  // MeshData holds the 4 triangles first, then the quad, and the face values follow them.
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "property uchar red\nelement face 3\nproperty int id\nproperty list uchar int "
      "vertex_indices\n"
      "property float w\nend_header\n"
      "0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n0.5 2 0 5\n2 2 0 6\n"
      "10 4 0 1 2 3 0.5\n20 5 0 1 5 4 3 0.25\n30 3 1 5 2 0.125\n";
  const core::MeshData d = read_mesh_from_memory(s, Format::Ply, "t.ply");
  ASSERT_EQ(d.triangles.size(), 4u);
  ASSERT_EQ(d.quads.size(), 1u);
  ASSERT_EQ(d.cell_data.size(), 2u);
  EXPECT_EQ(d.cell_data[0].name, "id");
  EXPECT_EQ(d.cell_data[0].values, (std::vector<double>{20, 20, 20, 30, 10}));
  EXPECT_EQ(d.cell_data[1].name, "w");
  EXPECT_EQ(d.cell_data[1].values, (std::vector<double>{0.25, 0.25, 0.25, 0.125, 0.5}));
  ASSERT_EQ(d.point_data.size(), 1u);
  EXPECT_EQ(d.point_data[0].name, "red");
  EXPECT_EQ(d.point_data[0].values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
}

TEST(PlyFieldsWrite, NamesAndColoursThatDoNotFit) {
  core::MeshData d = test::mixed_surface();
  const std::size_t n = d.num_cells();
  d.cell_data = {{"red", std::vector<double>(n, 0.5)},  // not 0..255 integers: kept as double
                 {"vertex_indices", std::vector<double>(n, 1.0)},  // a face's own property name
                 {"mean curvature", std::vector<double>(n, 2.0)}};
  d.point_data = {{"x", std::vector<double>(d.points.size(), 3.0)}};
  const std::string ply = write_mesh_to_string(d, Format::Ply);
  const std::string header = header_of(ply);
  EXPECT_NE(header.find("property double red\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property double vertex_indices_data\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property double mean_curvature\n"), std::string::npos) << header;
  EXPECT_NE(header.find("property double x_data\n"), std::string::npos) << header;
  const core::MeshData r = read_mesh_from_memory(ply, Format::Ply, "t.ply");
  ASSERT_EQ(r.cell_data.size(), 3u);
  EXPECT_EQ(r.cell_data[0].values, d.cell_data[0].values);
  EXPECT_EQ(r.point_data.at(0).name, "x_data");
  expect_points_near(r.points, d.points, 1e-12);
}

TEST(PlyFieldsVtk, Vtk9ReadsTheFaceColours) {
  // VTK 9.1's vtkPLYReader (ParaView's) when python3-vtk9 is installed
  if (std::system("/usr/bin/python3 -c 'import vtkmodules.vtkIOPLY' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-vtk9 not installed";
  test::TempDir dir("ply_vtk");
  const core::MeshData d = coloured_surface();
  const fs::path script = dir / "check.py";
  {
    std::ofstream py(script);
    py << "import sys\n"
          "from vtkmodules.vtkIOPLY import vtkPLYReader\n"
          "r = vtkPLYReader(); r.SetFileName(sys.argv[1]); r.Update()\n"
          "if r.GetErrorCode() != 0: sys.exit(2)\n"
          "g = r.GetOutput()\n"
          "rgb = g.GetCellData().GetArray('RGB')\n"
          "print(g.GetNumberOfCells(), g.GetNumberOfPoints(), rgb.GetNumberOfComponents() if rgb "
          "else 0)\n"
          "for c in range(g.GetNumberOfCells() if rgb else 0):\n"
          "    print(*(int(v) for v in rgb.GetTuple(c)))\n";
  }
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const fs::path file = dir / (binary ? "binary.ply" : "ascii.ply");
    WriteOptions o;
    o.binary = binary;
    write_mesh(file, d, o);
    const fs::path out = dir / "vtk_out.txt";
    const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + file.string() +
                            "' > '" + out.string() + "' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(out);
    std::ifstream in(out);
    std::size_t cells = 0, points = 0, components = 0;
    in >> cells >> points >> components;
    EXPECT_EQ(cells, d.num_cells());
    EXPECT_EQ(points, d.points.size());
    ASSERT_EQ(components, 3u);
    for (std::size_t c = 0; c < cells; ++c) {
      int r = -1, g = -1, b = -1;
      in >> r >> g >> b;
      EXPECT_EQ(r, d.cell_data[0].values[c]) << "cell " << c;
      EXPECT_EQ(g, d.cell_data[1].values[c]) << "cell " << c;
      EXPECT_EQ(b, d.cell_data[2].values[c]) << "cell " << c;
    }
  }
}

}  // namespace
}  // namespace polycube::io
