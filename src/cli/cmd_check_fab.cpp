//! `polycube check-fab SURFACE [--overhang D] [--axis PX PY PZ DX DY DZ] [--directions N]
//! [--vtk OUT]`: how a closed surface made elsewhere (a part, a whole model) can be made: support
//! when printed on each of its flat sides (its planar regions of 1 % of the area or more), 3-axis
//! milling on each, 4-axis milling about an axis (thesis §6.5).
#include "cli/app.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "fabricate/flat_sides.h"
#include "fabricate/printing.h"
#include "io/mesh_io.h"
#include "pipeline/parts_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace polycube::cli {

namespace {

struct CheckFabOptions {
  std::string input;
  std::string vtk;
  std::vector<double> axis;
  fabricate::PrintOptions print;
  pipeline::MillOptions mill;
};

nlohmann::json vec(const core::Vec3& v) { return {v.x(), v.y(), v.z()}; }

//! The surface as a part: closed and manifold (else refused), outward (flipped when inward).
fabricate::Part read_part(const std::string& path, bool& flipped) {
  fabricate::Part part;
  part.mesh = io::read_surface(path);
  const core::SurfaceReport r = core::analyze_surface(part.mesh);
  if (!r.closed || !r.manifold || !r.consistently_oriented)
    throw core::InputError(fmt::format(
        "{}: not a closed, manifold, consistently oriented surface ({}); repair it first (e.g. "
        "MeshLab's or PrusaSlicer's repair)",
        path,
        !r.closed     ? "open"
        : !r.manifold ? "non-manifold"
                      : "inconsistent orientation"));
  flipped = core::signed_volume(part.mesh) < 0;
  if (flipped)
    for (auto& t : part.mesh.cells) std::swap(t[1], t[2]);
  part.sides = fabricate::planar_sides(part.mesh, part.triangle_side);
  return part;
}

void run_check_fab(CheckFabOptions o) {
  if (!o.axis.empty()) {
    const core::Vec3 d(o.axis[3], o.axis[4], o.axis[5]);
    if (!(d.norm() > 0))
      throw core::InputError("--axis: the direction (last three numbers) is zero");
    o.mill.axis = fabricate::Axis{{o.axis[0], o.axis[1], o.axis[2]}, d.normalized()};
  }
  bool flipped = false;
  const fabricate::Part part = read_part(o.input, flipped);
  if (flipped) core::logger().warn("{}: the surface faces inward; checked turned outward", o.input);
  const fabricate::PartPrint print = fabricate::check_part_printing(part, o.print);
  const pipeline::PartMill mill = pipeline::mill_part(part, o.mill);
  const fabricate::Standing whole = fabricate::best_axis_standing(part.mesh, o.print);

  nlohmann::json sides = nlohmann::json::array();
  std::string text = fmt::format("{}: {} triangles, {} flat sides\n", o.input,
                                 part.mesh.num_cells(), part.sides.size());
  text += "  side  normal                       area       support %  3-axis unreachable %\n";
  for (std::size_t s = 0; s < part.sides.size(); ++s) {
    const core::Vec3& n = part.sides[s].normal;
    const fabricate::Standing& on = print.sides[s];
    nlohmann::json side = {{"normal", vec(n)},
                           {"area", part.sides[s].area},
                           {"three_axis_unreachable_percent", 100 * mill.three_axis[s]}};
    side.update(pipeline::support_json(on));
    sides.push_back(side);
    const std::string keels =
        on.keels > 0 || on.tips > 0 ? "  also " + fabricate::describe_keels_and_tips(on) : "";
    text += fmt::format("  {:4d}  ({:7.4f} {:7.4f} {:7.4f})  {:11.5g}  {:9.2f}  {:9.2f}{}\n", s,
                        n.x(), n.y(), n.z(), part.sides[s].area, 100 * on.support_fraction,
                        100 * mill.three_axis[s], keels);
  }
  const fabricate::Axis& axis = mill.four_axis.axis;
  text += fmt::format(
      "printing: best side {}; on the best axis of the bounding box ({:g} {:g} {:g} down) {:.2f} "
      "% support\n4-axis about ({:.4g} {:.4g} {:.4g}) + t ({:.4f} {:.4f} {:.4f}), {} directions: "
      "{:.2f} % never reached\n",
      print.best >= 0 ? std::to_string(print.best) : "-", whole.down.x(), whole.down.y(),
      whole.down.z(), 100 * whole.support_fraction, axis.point.x(), axis.point.y(), axis.point.z(),
      axis.direction.x(), axis.direction.y(), axis.direction.z(), o.mill.directions,
      100 * mill.four_axis.unreached);
  const nlohmann::json j = {
      {"input", o.input},
      {"triangles", part.mesh.num_cells()},
      {"flipped", flipped},
      {"overhang_degrees", o.print.overhang_degrees},
      {"flat_sides", sides},
      {"print_base", print.best >= 0 ? nlohmann::json(print.best) : nlohmann::json(nullptr)},
      {"best_axis_support_percent", 100 * whole.support_fraction},
      {"best_axis_down", vec(whole.down)},
      {"three_axis_base", mill.best >= 0 ? nlohmann::json(mill.best) : nlohmann::json(nullptr)},
      {"four_axis",
       {{"point", vec(axis.point)},
        {"direction", vec(axis.direction)},
        {"directions", o.mill.directions},
        {"unreached_percent", 100 * mill.four_axis.unreached}}}};
  if (!o.vtk.empty()) {
    core::MeshData d = core::to_mesh_data(part.mesh);
    const std::vector<std::uint8_t> over =
        print.best < 0 ? std::vector<std::uint8_t>(part.mesh.cells.size(), 0)
                       : fabricate::support_marks(
                             part.mesh, part.sides[static_cast<std::size_t>(print.best)].normal,
                             o.print.overhang_degrees);
    core::Field side{"flat_side", {}}, overhang{"overhang", {}}, three{"not_3axis", {}},
        four{"not_4axis", {}};
    for (std::size_t t = 0; t < part.mesh.cells.size(); ++t) {
      side.values.push_back(part.triangle_side[t]);
      overhang.values.push_back(over[t]);
      const auto& cls = mill.best_three_axis.triangle;
      three.values.push_back(!cls.empty() && (cls[t] == 1 || cls[t] == 2) ? 1.0 : 0.0);
      four.values.push_back(mill.four_axis.reached.empty() || mill.four_axis.reached[t] ? 0.0
                                                                                        : 1.0);
    }
    d.cell_data = {side, overhang, three, four};
    io::write_mesh(o.vtk, d);
    text += fmt::format("wrote {} (cell data flat_side, overhang, not_3axis, not_4axis)\n", o.vtk);
  }
  print_result(j, text);
}

}  // namespace

void register_check_fab(CLI::App& app) {
  auto opts = std::make_shared<CheckFabOptions>();
  CLI::App* sub = app.add_subcommand(
      "check-fab",
      "How a closed surface can be made (thesis §6.5): support needed printed on each of its "
      "flat sides, 3-axis milling with the stock on each, 4-axis milling about an axis");
  sub->add_option("surface", opts->input, "Closed surface (.stl .obj .off .ply), e.g. a part")
      ->required();
  sub->add_option("--overhang", opts->print.overhang_degrees,
                  "Steepest overhang printed without support, in degrees from the vertical")
      ->capture_default_str()
      ->check(cli::in_range(0.0, 90.0));
  sub->add_option("--axis", opts->axis,
                  "The 4-axis rotation axis, PX PY PZ DX DY DZ (default: chosen, the principal "
                  "direction of the normals that lets the tool reach most)")
      ->expected(6);
  sub->add_option("--directions", opts->mill.directions,
                  "4-axis tool directions evenly spaced about the axis")
      ->capture_default_str()
      ->check(cli::in_range(1, 3600));
  sub->add_option("--vtk", opts->vtk,
                  "Write the surface with per-triangle fields flat_side, overhang (1 an "
                  "overhanging face, 2 along a keel or at a tip, on the best side), not_3axis, "
                  "not_4axis (ParaView)");
  sub->callback([opts] { run_check_fab(*opts); });
}

}  // namespace polycube::cli
