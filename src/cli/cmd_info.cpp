//! `polycube info FILE`: counts, bounding box, closed/manifold/genus, components, and for volume
//! meshes the element orientation summary.
#include "cli/app.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "quality/scaled_jacobian.h"
#include "repair/repair.h"
#include "repair/thin_gaps.h"

#include <fmt/format.h>

#include <memory>
#include <sstream>

namespace polycube::cli {

namespace {

struct InfoOptions {
  std::string input;
  repair::RepairOptions repair;
};

nlohmann::json surface_json(const core::SurfaceReport& r) {
  return {{"vertices", r.vertices},
          {"faces", r.faces},
          {"edges", r.edges},
          {"components", r.components},
          {"closed", r.closed},
          {"manifold", r.manifold},
          {"orientable", r.orientable},
          {"consistently_oriented", r.consistently_oriented},
          {"boundary_edges", r.boundary_edges},
          {"boundary_loops", r.boundary_loops},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"degenerate_faces", r.degenerate_faces},
          {"isolated_vertices", r.isolated_vertices},
          {"euler_characteristic", r.euler_characteristic},
          {"genus", r.genus}};
}

std::string surface_text(const core::SurfaceReport& r, const char* indent) {
  std::string genus = r.genus >= 0 ? std::to_string(r.genus) : std::string("undefined");
  std::string s = fmt::format(
      "{0}closed {1}, manifold {2}, orientable {3}, consistently oriented {4}\n"
      "{0}components {5}, Euler characteristic {6}, genus {7}\n",
      indent, r.closed ? "yes" : "no", r.manifold ? "yes" : "no", r.orientable ? "yes" : "no",
      r.consistently_oriented ? "yes" : "no", r.components, r.euler_characteristic, genus);
  if (!r.closed)
    s += fmt::format("{}boundary edges {} in {} loop(s)\n", indent, r.boundary_edges,
                     r.boundary_loops);
  if (r.nonmanifold_edges + r.nonmanifold_vertices > 0)
    s += fmt::format("{}non-manifold edges {}, non-manifold vertices {}\n", indent,
                     r.nonmanifold_edges, r.nonmanifold_vertices);
  if (r.degenerate_faces > 0)
    s += fmt::format("{}degenerate faces {}\n", indent, r.degenerate_faces);
  if (r.isolated_vertices > 0)
    s += fmt::format("{}isolated vertices {}\n", indent, r.isolated_vertices);
  return s;
}

template <class Mesh>
void add_volume(nlohmann::json& j, std::string& text, const char* key, const char* what,
                const Mesh& m) {
  const core::VolumeReport r = core::analyze_volume(m);
  j[key] = {{"cells", r.cells},
            {"faces", r.faces},
            {"boundary_faces", r.boundary_faces},
            {"nonmanifold_faces", r.nonmanifold_faces},
            {"components", r.components},
            {"inverted_cells", r.inverted_cells},
            {"euler_characteristic", r.euler_characteristic},
            {"boundary", surface_json(r.boundary)}};
  text += fmt::format(
      "{}: {} components, {} inverted, {} boundary faces{}\n", what, r.components, r.inverted_cells,
      r.boundary_faces,
      r.nonmanifold_faces ? fmt::format(", {} NON-MANIFOLD faces", r.nonmanifold_faces) : "");
  // Element quality (Verdict scaled Jacobian; degenerate elements count as invalid).
  quality::ScaledJacobianOptions so;
  so.keep_values = false;
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(m, so);
  j[key]["scaled_jacobian"] = scaled_jacobian_json(sj);
  text += fmt::format("  scaled Jacobian: min {:.4f}, average {:.4f}, {} inverted, {} invalid\n",
                      sj.min, sj.average, sj.inverted, sj.invalid);
  text += "  boundary surface:\n" + surface_text(r.boundary, "    ");
  j["genus"] = r.boundary.genus;
}

//! Gaps of a closed surface narrower than the alpha wrap's ball (repair/thin_gaps.h): where the
//! construction may fail, and what `run` wraps when it does.
void add_thin_gaps(nlohmann::json& j, std::string& text, const core::TriMesh& surface, const repair::RepairOptions& o) {
  const repair::ThinGaps g = repair::gaps_the_wrap_closes(surface, o);
  nlohmann::json sites = nlohmann::json::array();
  for (const core::Vec3& p : g.sites) sites.push_back({p.x(), p.y(), p.z()});
  j["thin_gaps"] = {{"width", g.width}, {"vertices", g.vertices}, {"narrowest", g.narrowest}, {"sites", sites}};
  if (g.vertices > 0)
    text += "  " + g.line() + ", which the alpha wrap closes: a construction that fails there may succeed on the "
            "wrap (run tries it)\n";
}

void run_info(const InfoOptions& o) {
  const core::MeshData d = io::read_mesh(o.input);
  nlohmann::json j;
  std::string text;
  const core::BoundingBox bb = core::bounding_box(d.points);
  j["file"] = o.input;
  j["format"] = io::format_name(io::format_from_path(o.input));
  j["vertices"] = d.points.size();
  j["edges_block"] = d.edges.size();
  j["triangles"] = d.triangles.size();
  j["quads"] = d.quads.size();
  j["tetrahedra"] = d.tets.size();
  j["hexahedra"] = d.hexes.size();
  j["bbox"] = {{"min", {bb.min.x(), bb.min.y(), bb.min.z()}},
               {"max", {bb.max.x(), bb.max.y(), bb.max.z()}},
               {"diagonal", bb.diagonal()}};
  text += fmt::format("{} ({})\n", o.input, j["format"].get<std::string>());
  text += fmt::format("vertices {}, triangles {}, quads {}, tetrahedra {}, hexahedra {}\n",
                      d.points.size(), d.triangles.size(), d.quads.size(), d.tets.size(),
                      d.hexes.size());
  text += fmt::format(
      "bounding box [{:.6g}, {:.6g}, {:.6g}] - [{:.6g}, {:.6g}, {:.6g}], diagonal {:.6g}\n",
      bb.min.x(), bb.min.y(), bb.min.z(), bb.max.x(), bb.max.y(), bb.max.z(), bb.diagonal());

  // Volume elements take precedence: their boundary is the shape. Otherwise the surface blocks.
  if (!d.hexes.empty()) add_volume(j, text, "hexahedra_report", "hex mesh", core::hexes_of(d));
  if (!d.tets.empty()) add_volume(j, text, "tetrahedra_report", "tet mesh", core::tets_of(d));
  if (d.tets.empty() && d.hexes.empty()) {
    if (!d.triangles.empty()) {
      // The surface as construct and run see it: after the repairs that never move it.
      core::TriMesh surface = core::triangles_of(d);
      const repair::RepairReport repaired = repair::repair_surface(surface, o.repair);
      std::vector<std::string> repairs = repaired.lines(true);
      j["repairs"] = repairs;
      if (!repairs.empty()) {
        text +=
            "repairs (run, construct and fabricate apply them on load; the figures below are after "
            "them):\n";
        for (const std::string& line : repairs) text += "  " + line + "\n";
      }
      const core::SurfaceReport r = core::analyze_surface(surface);
      j["surface"] = surface_json(r);
      j["genus"] = r.genus;
      text += "triangle surface:\n" + surface_text(r, "  ");
      if (r.closed && r.manifold && r.consistently_oriented) add_thin_gaps(j, text, surface, o.repair);
    }
    if (!d.quads.empty()) {
      const core::SurfaceReport r = core::analyze_surface(core::quads_of(d));
      j["quad_surface"] = surface_json(r);
      if (d.triangles.empty()) j["genus"] = r.genus;
      text += "quad surface:\n" + surface_text(r, "  ");
    }
  }
  print_result(j, text);
}

}  // namespace

void register_info(CLI::App& app) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info",
                                     "Counts, bounding box, closed/manifold/orientable checks, "
                                     "genus and components of a mesh file, and for a surface the repairs "
                                     "construct and run would apply, with where (the first places of each), and the gaps "
                                     "narrower than the alpha wrap's ball, which run wraps when its construction fails");
  sub->add_option("file", opts->input, "Mesh file (.obj .off .stl .ply .mesh .vtk .msh)")
      ->required();
  add_expert_options(*sub, add_repair_options(*sub, opts->repair));
  sub->callback([opts] { run_info(*opts); });
}

}  // namespace polycube::cli
