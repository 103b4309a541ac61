//! Files of a decomposition (see parts_output.h).
#include "pipeline/parts_output.h"

#include "core/errors.h"
#include "io/mesh_io.h"
#include "io/three_mf.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>

namespace polycube::pipeline {

namespace {

namespace fs = std::filesystem;
using core::Vec3;

//! How far the exploded view moves each part away from the solid's centre, as a fraction of
//! the part's own offset from it.
constexpr double kExplode = 0.35;

//! A distinct colour per part: hues a golden angle apart, full saturation, bright.
std::array<std::uint8_t, 3> part_colour(std::size_t i) {
  const double h = std::fmod(static_cast<double>(i) * 137.507764, 360.0) / 60.0;
  const double s = 0.65, v = 0.95;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  std::array<double, 3> rgb{};
  switch (static_cast<int>(h)) {
    case 0:
      rgb = {c, x, 0};
      break;
    case 1:
      rgb = {x, c, 0};
      break;
    case 2:
      rgb = {0, c, x};
      break;
    case 3:
      rgb = {0, x, c};
      break;
    case 4:
      rgb = {x, 0, c};
      break;
    default:
      rgb = {c, 0, x};
      break;
  }
  std::array<std::uint8_t, 3> out{};
  for (int k = 0; k < 3; ++k) out[k] = static_cast<std::uint8_t>(std::lround(255 * (rgb[k] + m)));
  return out;
}

std::string part_file(std::size_t i) { return fmt::format("part_{:02d}.stl", i); }

Vec3 centroid(const core::TriMesh& m) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : m.points) c += p;
  return m.points.empty() ? c : Vec3(c / static_cast<double>(m.points.size()));
}

//! All non-empty parts in one mesh, each moved away from the centre, with per-triangle fields.
core::MeshData exploded(const fabricate::Decomposition& d) {
  Vec3 centre = Vec3::Zero();
  double volume = 0.0;
  for (const auto& p : d.parts.parts) {
    centre += p.volume * centroid(p.mesh);
    volume += p.volume;
  }
  if (volume > 0) centre /= volume;
  core::MeshData out;
  core::Field id{"part_id", {}}, side{"flat_side", {}}, red{"red", {}}, green{"green", {}},
      blue{"blue", {}};
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    const Vec3 shift = kExplode * (centroid(p.mesh) - centre);
    const int base = static_cast<int>(out.points.size());
    for (const Vec3& x : p.mesh.points) out.points.push_back(x + shift);
    const auto rgb = part_colour(i);
    for (std::size_t t = 0; t < p.mesh.cells.size(); ++t) {
      const auto& tri = p.mesh.cells[t];
      out.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
      id.values.push_back(static_cast<double>(i));
      side.values.push_back(p.triangle_side.empty() || p.triangle_side[t] < 0 ? 0.0 : 1.0);
      red.values.push_back(rgb[0]);
      green.values.push_back(rgb[1]);
      blue.values.push_back(rgb[2]);
    }
  }
  out.cell_data = {std::move(id), std::move(side), std::move(red), std::move(green),
                   std::move(blue)};
  return out;
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::string part_problem(const fabricate::Part& p) {
  if (p.mesh.cells.empty()) return "empty (its box's material went to a neighbour)";
  if (!p.closed) return "not closed";
  if (!p.outward) return "not outward";
  if (p.self_intersecting) return "self-intersecting";
  return "";
}

int failing_parts(const fabricate::Decomposition& d) {
  int n = 0;
  for (const auto& p : d.parts.parts) n += part_problem(p).empty() ? 0 : 1;
  return n;
}

void check_parts(const fabricate::Decomposition& d, const fabricate::DecomposeOptions& o) {
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const std::string why = part_problem(d.parts.parts[i]);
    if (!why.empty())
      throw core::GeometryError(fmt::format(
          "{} of {} parts fail the checks (part {}: {}); try the input surface as the solid, or "
          "--no-merge",
          failing_parts(d), d.parts.parts.size(), i, why));
  }
  if (d.unfit_parts > 0)
    throw core::GeometryError(fmt::format(
        "{} of {} parts still fit the chamber {:g} x {:g} x {:g} on none of their flat sides after "
        "{} rounds of splitting; give a larger chamber",
        d.unfit_parts, d.parts.parts.size(), o.chamber.x, o.chamber.y, o.chamber.z, d.rounds));
}

nlohmann::json parts_json(const fabricate::Decomposition& d, const fabricate::DecomposeOptions& o) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    const fabricate::Box& b = d.plan.partition.boxes[static_cast<std::size_t>(p.box)];
    nlohmann::json sides = nlohmann::json::array();
    for (const auto& s : p.sides)
      sides.push_back({{"cut", s.cut}, {"normal", vec(s.normal)}, {"area", s.area}});
    const std::string why = part_problem(p);
    nlohmann::json part = {
        {"file", p.mesh.cells.empty() ? nlohmann::json(nullptr) : nlohmann::json(part_file(i))},
        {"box", p.box},
        {"box_polycube",
         {{"lo", vec(fabricate::box_corner(d.grid, b, 0, 0, 0))},
          {"hi", vec(fabricate::box_corner(d.grid, b, 1, 1, 1))}}},
        {"triangles", p.mesh.num_cells()},
        {"volume", p.volume},
        {"components", p.components},
        {"closed", p.closed},
        {"outward", p.outward},
        {"self_intersecting", p.self_intersecting},
        {"ok", why.empty()},
        {"problem", why.empty() ? nlohmann::json(nullptr) : nlohmann::json(why)},
        {"flat_sides", sides},
        {"base", d.base[i] >= 0 ? nlohmann::json(d.base[i]) : nlohmann::json(nullptr)}};
    if (!p.mesh.points.empty()) {
      const core::BoundingBox bb = core::bounding_box(p.mesh.points);
      part["bounding_box"] = {{"min", vec(bb.min)}, {"max", vec(bb.max)}};
    }
    list.push_back(part);
  }
  nlohmann::json chamber = nullptr;
  if (o.chamber.limited()) chamber = {o.chamber.x, o.chamber.y, o.chamber.z};
  return {{"boxes", d.boxes},
          {"merge", o.merge},
          {"chamber", chamber},
          {"parts_count", d.parts.parts.size()},
          {"cuts", d.plan.cuts.size()},
          {"pinwheel_splits", d.plan.split_boxes},
          {"chamber_rounds", d.rounds},
          {"chamber_planes", d.chamber_planes},
          {"unfit_parts", d.unfit_parts},
          {"failing_parts", failing_parts(d)},
          {"solid_volume", d.parts.solid_volume},
          {"parts_volume", d.parts.volume_sum},
          {"seconds",
           {{"partition", d.partition_seconds}, {"cuts", d.cut_seconds}, {"total", d.seconds}}},
          {"parts", list}};
}

std::string parts_table(const fabricate::Decomposition& d) {
  std::string text = fmt::format(
      "{} boxes in the polycube's partition, {} parts; solid volume {:.6g}, parts {:.6g}\n",
      d.boxes, d.parts.parts.size(), d.parts.solid_volume, d.parts.volume_sum);
  text += "  part  box  triangles      volume    size (bounding box)        sides  base  check\n";
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    Vec3 size = Vec3::Zero();
    if (!p.mesh.points.empty()) size = core::bounding_box(p.mesh.points).extent();
    const std::string why = part_problem(p);
    text += fmt::format(
        "  {:4d} {:4d} {:10d} {:11.6g}  {:8.4g} {:8.4g} {:8.4g}  {:5d}  {:>4}  {}\n", i, p.box,
        p.mesh.num_cells(), p.volume, size.x(), size.y(), size.z(), p.sides.size(),
        d.base[i] >= 0 ? std::to_string(d.base[i]) : "-", why.empty() ? "ok" : why);
  }
  return text;
}

std::vector<fs::path> write_parts(const fs::path& dir, const fabricate::Decomposition& d,
                                  const fabricate::DecomposeOptions& o) {
  fs::create_directories(dir);
  std::vector<fs::path> files;
  std::vector<io::ThreeMfObject> objects;
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    if (p.mesh.cells.empty()) continue;
    files.push_back(dir / part_file(i));
    io::write_mesh(files.back(), core::to_mesh_data(p.mesh));
    objects.push_back({fmt::format("part {:02d}", i), p.mesh, part_colour(i)});
  }
  if (!objects.empty()) {
    files.push_back(dir / "parts.3mf");
    io::write_3mf(files.back(), objects);
  }
  const core::MeshData view = exploded(d);
  for (const char* name : {"exploded.ply", "exploded.vtk"}) {
    files.push_back(dir / name);
    io::write_mesh(files.back(), view);
  }
  files.push_back(dir / "parts.json");
  io::write_text_atomic(files.back(), parts_json(d, o).dump(2) + "\n");
  return files;
}

}  // namespace polycube::pipeline
