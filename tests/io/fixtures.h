#pragma once
//! Small meshes built in code for the io tests, and comparison helpers.

#include "core/types.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace polycube::io::test {

//! Coordinates chosen to stress decimal round trips: thirds, tiny, huge, negative zero-ish.
inline core::Vec3 awkward(int i) {
  const double a = 1.0 / 3.0 + i * 0.1;
  return {a * (i % 2 == 0 ? 1.0 : -1.0) * 1e3, 1e-7 * (i + 1) + std::sqrt(2.0), 12345.678901234567 / (i + 1)};
}

//! Unit cube with slightly perturbed corners: 8 points, 6 outward quads.
inline core::MeshData cube_quads() {
  core::MeshData d;
  const int c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) d.points.push_back(core::Vec3(c[i][0], c[i][1], c[i][2]) + 1e-3 * awkward(i) / 1e4);
  d.quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return d;
}

//! Octahedron (6 points, 8 triangles) plus one quad on an extra square: a mixed surface.
inline core::MeshData mixed_surface() {
  core::MeshData d;
  d.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (core::Vec3& p : d.points) p *= 1.0 / 3.0;
  d.points.push_back(awkward(1));
  d.points.push_back(awkward(2));
  d.points.push_back(awkward(3));
  d.points.push_back(awkward(4));
  d.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  d.quads = {{6, 7, 8, 9}};
  return d;
}

//! Two hexes side by side, three tets on top, boundary triangles and quads, edges, labels,
//! point labels, and one point and one cell field.
inline core::MeshData volume_mesh() {
  core::MeshData d;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) d.points.push_back(core::Vec3(i, j, k) + 1e-4 * awkward(i + 3 * j + 6 * k));
  auto id = [](int i, int j, int k) { return i + 3 * j + 6 * k; };
  for (int i = 0; i < 2; ++i)
    d.hexes.push_back({id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 1, 0), id(i, 1, 0), id(i, 0, 1), id(i + 1, 0, 1),
                       id(i + 1, 1, 1), id(i, 1, 1)});
  d.points.push_back({0.5, 0.5, 2.0 + 1.0 / 7.0});
  d.points.push_back({1.5, 0.5, 2.25});
  d.tets = {{id(0, 0, 1), id(1, 0, 1), id(0, 1, 1), 12}, {id(1, 0, 1), id(1, 1, 1), id(0, 1, 1), 12},
            {id(1, 0, 1), id(2, 0, 1), id(1, 1, 1), 13}};
  d.triangles = {{id(0, 0, 1), 12, id(1, 0, 1)}, {id(1, 0, 1), 13, id(2, 0, 1)}};
  d.quads = {{id(0, 0, 0), id(0, 1, 0), id(1, 1, 0), id(1, 0, 0)}, {id(1, 0, 0), id(1, 1, 0), id(2, 1, 0), id(2, 0, 0)}};
  d.edges = {{0, 1}, {1, 2}};
  d.hex_labels = {1, 2};
  d.tet_labels = {3, 3, -4};
  d.triangle_labels = {7, 0};
  d.quad_labels = {5, 5};
  d.edge_labels = {9, 9};
  for (std::size_t i = 0; i < d.points.size(); ++i) d.point_labels.push_back(static_cast<int>(i % 3));
  core::Field pf{"temperature", {}};
  for (const core::Vec3& p : d.points) pf.values.push_back(p.x() * 0.1 + p.z() / 3.0);
  d.point_data.push_back(pf);
  core::Field cf{"quality", {}};
  for (std::size_t c = 0; c < d.num_cells(); ++c) cf.values.push_back(1.0 / (static_cast<double>(c) + 3.0));
  d.cell_data.push_back(cf);
  return d;
}

//! Points equal to a relative tolerance (relative to the coordinate magnitude, floor 1).
inline void expect_points_near(const std::vector<core::Vec3>& a, const std::vector<core::Vec3>& b, double rel) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_LE(std::abs(a[i][k] - b[i][k]), rel * std::max(1.0, std::abs(a[i][k])))
          << "point " << i << " coordinate " << k << ": " << a[i][k] << " vs " << b[i][k];
}

//! Same triangles, compared through their corner positions (vertex numbering may differ).
inline void expect_same_triangles(const core::MeshData& a, const core::MeshData& b, double rel) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t t = 0; t < a.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        const double x = a.points[static_cast<std::size_t>(a.triangles[t][c])][k];
        const double y = b.points[static_cast<std::size_t>(b.triangles[t][c])][k];
        EXPECT_LE(std::abs(x - y), rel * std::max(1.0, std::abs(x))) << "triangle " << t << " corner " << c;
      }
}

//! A fresh temporary folder, removed at destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    std::string name = "polycube_io_";
    name += tag;
    name += '_';
    name += std::to_string(::getpid());
    name += '_';
    name += std::to_string(counter()++);
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::filesystem::path path_;
};

}  // namespace polycube::io::test
