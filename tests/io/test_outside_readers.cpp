// Outside tools read what we write: meshio (python3-meshio) every format, Gmsh the formats it
// knows (.msh, .mesh, .ply, .stl, .vtk), VTK 9 (python3-vtk9) writes a version 5.1 file that we
// read. Each test skips cleanly when its tool is not installed (scripts/packages-ci.txt has them).
#include "io/fixtures.h"
#include "io/mesh_io.h"

#include "support/files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <string>

namespace polycube::io {
namespace {

namespace fs = std::filesystem;
using polycube::test::quoted;

//! Run a shell command; its stdout, or nullopt when it exits non-zero.
std::optional<std::string> output_of(const std::string& command) {
  FILE* p = popen(command.c_str(), "r");
  if (!p) return std::nullopt;
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  return pclose(p) == 0 ? std::optional(out) : std::nullopt;
}

bool have_meshio() { return output_of("/usr/bin/python3 -c 'import meshio' 2>/dev/null").has_value(); }
bool have_gmsh() { return output_of("gmsh --version >/dev/null 2>&1").has_value(); }
bool have_vtk() { return output_of("/usr/bin/python3 -c 'import vtkmodules.vtkIOLegacy' 2>/dev/null").has_value(); }

struct Written {
  std::string file;
  core::MeshData data;
  WriteOptions options;
};

//! Every kind of file our commands write: volume meshes with labels and fields, surfaces of
//! triangles and quads, binary STL and PLY.
std::vector<Written> files_we_write() {
  core::MeshData volume = test::volume_mesh();
  core::MeshData mixed = test::mixed_surface();
  core::MeshData triangles = mixed;
  triangles.quads.clear();
  triangles.points.resize(6);
  core::MeshData quads = test::cube_quads();
  core::Field sj{"scaled_jacobian", {0.1, 0.2, 0.3, 0.4, 0.5, 0.6}};
  quads.cell_data.push_back(sj);
  return {{"volume.mesh", volume, {}},        {"volume.vtk", volume, {}},         {"volume.msh", volume, {}},
          {"mixed.obj", mixed, {}},           {"mixed.ply", mixed, {}},           {"mixed.vtk", mixed, {}},
          {"mixed.msh", mixed, {}},           {"mixed.mesh", mixed, {}},          {"quads.ply", quads, {}},
          {"quads.vtk", quads, {}},           {"triangles.off", triangles, {}},   {"triangles.stl", triangles, {}},
          {"triangles_b.stl", triangles, {.binary = true}},                      {"triangles_b.ply", triangles, {.binary = true}},
          {"triangles_d.ply", triangles, {.binary = true, .double_precision = true}}};
}

//! Cells of each type as meshio names them.
std::map<std::string, std::size_t> meshio_cells(const core::MeshData& d, bool with_edges) {
  std::map<std::string, std::size_t> c;
  if (with_edges && !d.edges.empty()) c["line"] = d.edges.size();
  if (!d.triangles.empty()) c["triangle"] = d.triangles.size();
  if (!d.quads.empty()) c["quad"] = d.quads.size();
  if (!d.tets.empty()) c["tetra"] = d.tets.size();
  if (!d.hexes.empty()) c["hexahedron"] = d.hexes.size();
  return c;
}

}  // namespace

// meshio reads every format we write with the counts we wrote. Not written here because
// meshio 5 cannot read them (its limits, not the files'): OFF with quads (its OFF reader takes
// triangles only) and binary PLY with face properties (it reads them as columns, not per face).
TEST(OutsideReaders, MeshioReadsEveryFormatWeWrite) {
  if (!have_meshio()) GTEST_SKIP() << "python3-meshio not installed";
  test::TempDir dir("meshio");
  for (const Written& w : files_we_write()) {
    SCOPED_TRACE(w.file);
    write_mesh(dir / w.file, w.data, w.options);
    const auto out = output_of("/usr/bin/python3 '" POLYCUBE_IO_TEST_DIR "/meshio_counts.py' " + quoted(dir / w.file));
    ASSERT_TRUE(out.has_value()) << "meshio could not read " << w.file;
    const nlohmann::json j = nlohmann::json::parse(*out);
    const bool stl = w.file.ends_with(".stl");  // STL has no shared vertices: meshio merges none
    if (!stl) {
      EXPECT_EQ(j["points"].get<std::size_t>(), w.data.points.size());
    }
    const bool edges = w.file.ends_with(".msh") || w.file.ends_with(".mesh");  // our .vtk holds no edges
    using Counts = std::map<std::string, std::size_t>;
    EXPECT_EQ(j["cells"].get<Counts>(), meshio_cells(w.data, edges)) << *out;
    if (w.file.ends_with(".vtk")) {
      for (const core::Field& f : w.data.cell_data) {
        EXPECT_NE(out->find('"' + f.name + '"'), std::string::npos) << *out;
      }
    }
    if (w.file.ends_with(".msh") && !w.data.tet_labels.empty()) {
      EXPECT_NE(out->find("gmsh:physical"), std::string::npos) << *out;
    }
  }
}

// Gmsh reads our .msh, .mesh, PLY, STL and VTK files: it saves what it read as MSH 4.1, which
// we read back with the counts we wrote. (Gmsh 4.8 reads neither OBJ nor OFF; of a PLY it
// reads triangles only, each face's first three vertices, and binary ones only with float
// coordinates, our default.)
TEST(OutsideReaders, GmshReadsOurMshMeshPlyStlAndVtk) {
  if (!have_gmsh()) GTEST_SKIP() << "gmsh not installed";
  test::TempDir dir("gmsh");
  for (const Written& w : files_we_write()) {
    if (w.file.ends_with(".obj") || w.file.ends_with(".off") || w.file == "triangles_d.ply") continue;
    if (w.file.ends_with(".ply") && !w.data.quads.empty()) continue;  // Gmsh takes 3 vertices of each face
    SCOPED_TRACE(w.file);
    write_mesh(dir / w.file, w.data, w.options);
    const fs::path back = dir / (w.file + ".gmsh.msh");
    const auto out = output_of("gmsh -v 1 " + quoted(dir / w.file) + " -0 -save_all -format msh41 -o " + quoted(back) +
                               " 2>&1");
    ASSERT_TRUE(out.has_value() && fs::exists(back)) << "gmsh could not read " << w.file << ": " << out.value_or("");
    const core::MeshData r = read_mesh(back);
    EXPECT_EQ(r.triangles.size(), w.data.triangles.size());
    EXPECT_EQ(r.quads.size(), w.data.quads.size());
    EXPECT_EQ(r.tets.size(), w.data.tets.size());
    EXPECT_EQ(r.hexes.size(), w.data.hexes.size());
  }
}

// VTK 9 writes legacy version 5.1 by default (ParaView too): we read it with the same cells,
// labels and fields as the version 3.0 file it was made from.
TEST(OutsideReaders, WeReadTheVersion51FilesVtkWrites) {
  if (!have_vtk()) GTEST_SKIP() << "python3-vtk9 not installed";
  test::TempDir dir("vtk51");
  const core::MeshData d = test::volume_mesh();
  write_mesh(dir / "ours.vtk", d);
  const std::string script =
      "import sys\n"
      "from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader, vtkUnstructuredGridWriter\n"
      "r = vtkUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.ReadAllScalarsOn(); r.ReadAllFieldsOn(); r.Update()\n"
      "w = vtkUnstructuredGridWriter(); w.SetInputData(r.GetOutput()); w.SetFileName(sys.argv[2]); w.Write()\n";
  ASSERT_TRUE(output_of("/usr/bin/python3 -c \"" + script + "\" " + quoted(dir / "ours.vtk") + " " + quoted(dir / "vtk.vtk")));
  std::ifstream in(dir / "vtk.vtk");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# vtk DataFile Version 5.1");
  const core::MeshData r = read_mesh(dir / "vtk.vtk");
  EXPECT_EQ(r.hexes, d.hexes);
  EXPECT_EQ(r.tets, d.tets);
  EXPECT_EQ(r.triangles, d.triangles);
  EXPECT_EQ(r.quads, d.quads);
  EXPECT_EQ(r.hex_labels, d.hex_labels);
  EXPECT_EQ(r.tet_labels, d.tet_labels);
  test::expect_points_near(r.points, d.points, 1e-9);
  ASSERT_EQ(r.cell_data.size(), d.cell_data.size());
  for (std::size_t i = 0; i < d.cell_data[0].values.size(); ++i)
    EXPECT_NEAR(r.cell_data[0].values[i], d.cell_data[0].values[i], 1e-9);
}

}  // namespace polycube::io
