//! Files of a decomposition (see parts_output.h).
#include "pipeline/parts_output.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "io/mesh_io.h"
#include "io/three_mf.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

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

//! The part standing on its best base, ready for a slicer.
std::string print_file(std::size_t i) { return fmt::format("print/part_{:02d}.stl", i); }

Vec3 centroid(const core::TriMesh& m) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : m.points) c += p;
  return m.points.empty() ? c : Vec3(c / static_cast<double>(m.points.size()));
}

//! All non-empty parts in one mesh, each moved away from the centre, with per-triangle fields.
core::MeshData exploded(const Fabrication& f) {
  const fabricate::Decomposition& d = f.decomposition;
  Vec3 centre = Vec3::Zero();
  double volume = 0.0;
  for (const auto& p : d.parts.parts) {
    centre += p.volume * centroid(p.mesh);
    volume += p.volume;
  }
  if (volume > 0) centre /= volume;
  core::MeshData out;
  core::Field id{"part_id", {}}, side{"flat_side", {}}, overhang{"overhang", {}},
      three{"not_3axis", {}}, four{"not_4axis", {}}, red{"red", {}}, green{"green", {}},
      blue{"blue", {}};
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    const Vec3 shift = kExplode * (centroid(p.mesh) - centre);
    const int base = static_cast<int>(out.points.size());
    for (const Vec3& x : p.mesh.points) out.points.push_back(x + shift);
    const auto rgb = part_colour(i);
    const int best = f.prints[i].best;
    const std::vector<std::uint8_t> over =
        best < 0 ? std::vector<std::uint8_t>(p.mesh.cells.size(), 0)
                 : fabricate::support_marks(p.mesh, p.sides[static_cast<std::size_t>(best)].normal,
                                            f.print.overhang_degrees);
    for (std::size_t t = 0; t < p.mesh.cells.size(); ++t) {
      const auto& tri = p.mesh.cells[t];
      out.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
      id.values.push_back(static_cast<double>(i));
      side.values.push_back(p.triangle_side.empty() || p.triangle_side[t] < 0 ? 0.0 : 1.0);
      overhang.values.push_back(over[t]);
      const auto& cls = f.mills[i].best_three_axis.triangle;
      three.values.push_back(cls.empty() ? 0.0 : (cls[t] == 1 || cls[t] == 2) ? 1.0 : 0.0);
      const auto& reached = f.mills[i].four_axis.reached;
      four.values.push_back(reached.empty() || reached[t] ? 0.0 : 1.0);
      red.values.push_back(rgb[0]);
      green.values.push_back(rgb[1]);
      blue.values.push_back(rgb[2]);
    }
  }
  out.cell_data = {std::move(id),   std::move(side), std::move(overhang), std::move(three),
                   std::move(four), std::move(red),  std::move(green),    std::move(blue)};
  return out;
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

double percent(double fraction) { return 100.0 * fraction; }

}  // namespace

nlohmann::json support_json(const fabricate::Standing& s) {
  return {{"support_percent", percent(s.support_fraction)},
          {"needs_support", s.needs_support()},
          {"keels", s.keels},
          {"keel_length", s.keel_length},
          {"tips", s.tips}};
}

double Fabrication::parts_support_fraction() const {
  double over = 0.0, area = 0.0;
  for (const fabricate::PartPrint& p : prints) {
    area += p.area;
    if (p.best >= 0) over += p.sides[static_cast<std::size_t>(p.best)].overhang_area;
  }
  return area > 0 ? over / area : 0.0;
}

//! Area-weighted mean over the parts of a per-part fraction.
template <class Fraction>
double area_weighted(const Fabrication& f, Fraction fraction) {
  double sum = 0.0, area = 0.0;
  for (std::size_t i = 0; i < f.mills.size(); ++i) {
    area += f.prints[i].area;
    sum += f.prints[i].area * fraction(f.mills[i]);
  }
  return area > 0 ? sum / area : 0.0;
}

double Fabrication::parts_three_axis_fraction() const {
  return area_weighted(*this, [](const PartMill& m) { return m.best_three_axis.unreachable; });
}

double Fabrication::parts_four_axis_fraction() const {
  return area_weighted(*this, [](const PartMill& m) { return m.four_axis.unreached; });
}

PartMill mill_part(const fabricate::Part& p, const MillOptions& o) {
  PartMill m;
  for (std::size_t s = 0; s < p.sides.size(); ++s) {
    std::vector<int> base;
    for (std::size_t t = 0; t < p.triangle_side.size(); ++t)
      if (p.triangle_side[t] == static_cast<int>(s)) base.push_back(static_cast<int>(t));
    fabricate::ThreeAxis r = fabricate::three_axis(p.mesh, p.sides[s].normal, base);
    m.three_axis.push_back(r.unreachable);
    if (m.best < 0 || r.unreachable < m.best_three_axis.unreachable) {
      m.best = static_cast<int>(s);
      m.best_three_axis = std::move(r);
    }
  }
  const fabricate::Axis axis = o.axis ? *o.axis : fabricate::choose_axis(p.mesh, o.directions);
  m.four_axis = fabricate::four_axis(p.mesh, axis, o.directions);
  return m;
}

Fabrication fabricate_solid(const core::PolycubeMap& map, const core::TriMesh& solid,
                            const fabricate::DecomposeOptions& options,
                            const fabricate::PrintOptions& print, const MillOptions& mill) {
  Fabrication f;
  f.decomposition = fabricate::decompose(map, solid, options);
  f.options = options;
  f.print = print;
  f.print.chamber = options.chamber;
  const core::Stopwatch clock;
  f.mill = mill;
  for (const fabricate::Part& p : f.decomposition.parts.parts) {
    f.prints.push_back(fabricate::check_part_printing(p, f.print));
    f.mills.push_back(p.mesh.cells.empty() ? PartMill{} : mill_part(p, mill));
  }
  f.whole = fabricate::best_axis_standing(solid, f.print);
  f.check_seconds = clock.seconds();
  return f;
}

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

void check_parts(const Fabrication& f) {
  const fabricate::Decomposition& d = f.decomposition;
  const fabricate::DecomposeOptions& o = f.options;
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

nlohmann::json parts_json(const Fabrication& f) {
  const fabricate::Decomposition& d = f.decomposition;
  const fabricate::DecomposeOptions& o = f.options;
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    const fabricate::Box& b = d.plan.partition.boxes[static_cast<std::size_t>(p.box)];
    nlohmann::json sides = nlohmann::json::array();
    const fabricate::PartPrint& print = f.prints[i];
    const PartMill& mill = f.mills[i];
    for (std::size_t k = 0; k < p.sides.size(); ++k) {
      nlohmann::json side(
          {{"cut", p.sides[k].cut},
           {"normal", vec(p.sides[k].normal)},
           {"area", p.sides[k].area},
           {"fits_chamber", print.sides[k].fits},
           {"three_axis_base",
            mill.best >= 0 ? nlohmann::json(mill.best) : nlohmann::json(nullptr)},
           {"three_axis_unreachable_percent",
            mill.best >= 0 ? nlohmann::json(percent(mill.best_three_axis.unreachable))
                           : nlohmann::json(nullptr)},
           {"three_axis_occluded_percent",
            mill.best >= 0 ? nlohmann::json(percent(mill.best_three_axis.occluded))
                           : nlohmann::json(nullptr)},
           {"four_axis",
            {{"point", vec(mill.four_axis.axis.point)},
             {"direction", vec(mill.four_axis.axis.direction)},
             {"unreached_percent", percent(mill.four_axis.unreached)}}},
           {"three_axis_unreachable_percent",
            k < f.mills[i].three_axis.size() ? nlohmann::json(percent(f.mills[i].three_axis[k]))
                                             : nlohmann::json(nullptr)}});
      side.update(support_json(print.sides[k]));
      sides.push_back(side);
    }
    const std::string why = part_problem(p);
    nlohmann::json part = {
        {"file", p.mesh.cells.empty() ? nlohmann::json(nullptr) : nlohmann::json(part_file(i))},
        {"print_file", p.mesh.cells.empty() || print.best < 0 ? nlohmann::json(nullptr)
                                                              : nlohmann::json(print_file(i))},
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
        {"base", print.best >= 0 ? nlohmann::json(print.best) : nlohmann::json(nullptr)},
        {"three_axis_base", mill.best >= 0 ? nlohmann::json(mill.best) : nlohmann::json(nullptr)},
        {"three_axis_unreachable_percent",
         mill.best >= 0 ? nlohmann::json(percent(mill.best_three_axis.unreachable))
                        : nlohmann::json(nullptr)},
        {"three_axis_occluded_percent", mill.best >= 0
                                            ? nlohmann::json(percent(mill.best_three_axis.occluded))
                                            : nlohmann::json(nullptr)},
        {"four_axis",
         {{"point", vec(mill.four_axis.axis.point)},
          {"direction", vec(mill.four_axis.axis.direction)},
          {"unreached_percent", percent(mill.four_axis.unreached)}}}};
    if (print.best >= 0)
      part.update(support_json(print.sides[static_cast<std::size_t>(print.best)]));
    else
      part["support_percent"] = part["needs_support"] = nullptr;
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
           {{"partition", d.partition_seconds},
            {"cuts", d.cut_seconds},
            {"decomposition", d.seconds},
            {"checks", f.check_seconds}}},
          {"printing",
           {{"overhang_degrees", f.print.overhang_degrees},
            {"whole_support_percent", percent(f.whole.support_fraction)},
            {"whole_down", vec(f.whole.down)},
            {"parts_support_percent", percent(f.parts_support_fraction())}}},
          {"milling",
           {{"directions", f.mill.directions},
            {"axis", f.mill.axis ? nlohmann::json({{"point", vec(f.mill.axis->point)},
                                                   {"direction", vec(f.mill.axis->direction)}})
                                 : nlohmann::json("chosen per part")},
            {"parts_three_axis_unreachable_percent", percent(f.parts_three_axis_fraction())},
            {"parts_four_axis_unreached_percent", percent(f.parts_four_axis_fraction())}}},
          {"parts", list}};
}

std::string parts_table(const Fabrication& f) {
  const fabricate::Decomposition& d = f.decomposition;
  std::string text = fmt::format(
      "{} boxes in the polycube's partition, {} parts; solid volume {:.6g}, parts {:.6g}\n",
      d.boxes, d.parts.parts.size(), d.parts.solid_volume, d.parts.volume_sum);
  text +=
      "  part  box  triangles      volume    size (bounding box)        sides  base  %3DPPS   "
      "%3AM   %4AM  check\n";
  std::vector<std::string> starred;  // parts that need support where their fraction does not say
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    Vec3 size = Vec3::Zero();
    if (!p.mesh.points.empty()) size = core::bounding_box(p.mesh.points).extent();
    const std::string why = part_problem(p);
    const fabricate::PartPrint& print = f.prints[i];
    std::string support = "-";
    if (print.best >= 0) {
      const fabricate::Standing& on = print.sides[static_cast<std::size_t>(print.best)];
      support = fmt::format("{:.2f}", percent(on.support_fraction));
      if (on.keels > 0 || on.tips > 0) {
        support += "*";
        starred.push_back(fmt::format("part {}: {}", i, fabricate::describe_keels_and_tips(on)));
      }
    }
    const PartMill& mill = f.mills[i];
    const std::string three =
        mill.best < 0 ? std::string("-")
                      : fmt::format("{:.2f}", percent(mill.best_three_axis.unreachable));
    text += fmt::format(
        "  {:4d} {:4d} {:10d} {:11.6g}  {:8.4g} {:8.4g} {:8.4g}  {:5d}  {:>4}  {:>6}  {:>5}  "
        "{:5.2f}  {}\n",
        i, p.box, p.mesh.num_cells(), p.volume, size.x(), size.y(), size.z(), p.sides.size(),
        print.best >= 0 ? std::to_string(print.best) : "-", support, three,
        percent(mill.four_axis.unreached), why.empty() ? "ok" : why);
  }
  if (!starred.empty())
    text += fmt::format(
        "  * also needs support under edges or points with nothing within the printer's angle "
        "below them (keels, tips pointing down): {}\n",
        fmt::join(starred, "; "));
  text += fmt::format(
      "support (overhang beyond {:g} degrees, % of the surface): in one piece {:.2f} "
      "(%3DPST), in parts {:.2f} (%3DPPST)\n",
      f.print.overhang_degrees, percent(f.whole.support_fraction),
      percent(f.parts_support_fraction()));
  text += fmt::format(
      "milling (% of the surface the tool cannot reach): 3-axis on the best side {:.2f}, 4-axis "
      "with {} directions {:.2f}\n",
      percent(f.parts_three_axis_fraction()), f.mill.directions,
      percent(f.parts_four_axis_fraction()));
  return text;
}

int remove_earlier_parts(const fs::path& dir) {
  int removed = 0;
  std::error_code ec;
  const auto remove = [&](const fs::path& p) { removed += fs::remove(p, ec) ? 1 : 0; };
  for (const char* name : {"parts.3mf", "exploded.ply", "exploded.vtk", "parts.json"})
    remove(dir / name);
  for (const fs::path& folder : {dir, dir / "print"}) {
    if (!fs::is_directory(folder, ec)) continue;
    std::vector<fs::path> parts;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file() && name.starts_with("part_") && name.ends_with(".stl"))
        parts.push_back(entry.path());
    }
    for (const fs::path& p : parts) remove(p);
  }
  return removed;
}

std::vector<fs::path> write_parts(const fs::path& dir, const Fabrication& f) {
  const fabricate::Decomposition& d = f.decomposition;
  // A folder written before holds the earlier decomposition's parts: fewer parts now would
  // leave some of them behind, looking like parts of this one.
  if (const int removed = remove_earlier_parts(dir); removed > 0)
    core::logger().info("fabricate: removed {} files of an earlier decomposition in {}", removed,
                        dir.string());
  fs::create_directories(dir);
  std::vector<fs::path> files;
  std::vector<io::ThreeMfObject> objects;
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    if (p.mesh.cells.empty()) continue;
    files.push_back(dir / part_file(i));
    io::write_mesh(files.back(), core::to_mesh_data(p.mesh), {.binary = true});
    objects.push_back({fmt::format("part {:02d}", i), p.mesh, part_colour(i)});
    const int base = f.prints[i].best;
    if (base < 0) continue;
    files.push_back(dir / print_file(i));
    fs::create_directories(files.back().parent_path());
    const fabricate::Standing& on = f.prints[i].sides[static_cast<std::size_t>(base)];
    io::write_mesh(files.back(), core::to_mesh_data(fabricate::stand_on_bed(p.mesh, on.down)),
                   {.binary = true});
  }
  if (!objects.empty()) {
    files.push_back(dir / "parts.3mf");
    io::write_3mf(files.back(), objects);
  }
  const core::MeshData view = exploded(f);
  for (const char* name : {"exploded.ply", "exploded.vtk"}) {
    files.push_back(dir / name);
    io::write_mesh(files.back(), view);
  }
  files.push_back(dir / "parts.json");
  io::write_text_atomic(files.back(), parts_json(f).dump(2) + "\n");
  return files;
}

}  // namespace polycube::pipeline
