//! Reading the input of the construction (see input.h).
#include "pipeline/input.h"

#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"

namespace polycube::pipeline {

ConstructInput read_construct_input(const std::filesystem::path& path, const repair::RepairOptions& repairs) {
  const std::string name = path.string();
  const io::Format format = io::format_from_path(name);
  ConstructInput in;
  try {
    if (io::is_volume_format(format)) {
      const core::MeshData data = io::read_mesh(name);
      if (!data.tets.empty()) {
        core::TetMesh mesh = core::tets_of(data);
        mesh.labels.clear();
        core::check_indices(mesh);
        try {
          in.target = core::boundary(mesh).surface;
        } catch (const core::GeometryError& e) {
          throw core::InputError(e.what());
        }
        in.target.labels.clear();
        in.tets = std::move(mesh);
        return in;
      }
      if (!data.hexes.empty())
        throw core::InputError("hexahedral meshes are not accepted; give a surface or a tet mesh");
      core::TriMesh surface = core::triangles_of(data);
      surface.labels.clear();
      if (surface.cells.empty()) throw core::InputError("the file holds no triangle and no tet");
      in.surface = std::move(surface);
    } else {
      in.surface = io::read_surface(name);
    }
    const repair::RepairReport repaired = repair::repair_surface(*in.surface, repairs);
    in.repairs = repaired.lines();
    in.wrapped = repaired.wrapped;
    for (const std::string& line : in.repairs) core::logger().warn("{}: {}", name, line);
    construct::check_closed_surface(*in.surface);
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    if (what.find(name) != std::string::npos) throw;  // the reader already named the file
    throw core::InputError(name, 0, what);
  }
  in.target = *in.surface;
  return in;
}

construct::ConstructResult construct_from_input(const ConstructInput& input,
                                                const std::filesystem::path& path,
                                                const construct::ConstructOptions& options) {
  try {
    if (input.tets) return construct::construct_polycube(*input.tets, options);
    return construct::construct_polycube(*input.surface, options);
  } catch (const core::InputError& e) {
    throw core::InputError(path.string(), 0, e.what());
  } catch (const construct::NotCertified& e) {
    // Where every attempt left a few tets folded, the cause is often a detail thinner than the
    // tets (a slit, a narrow gap) that no chart layout opens; the alpha wrap closes it.
    if (!input.surface || input.wrapped) throw;
    throw construct::NotCertified(std::string(e.what()) +
                                      "; a surface with slits or gaps thinner than its tets may construct after "
                                      "--repair wrap (which closes them; the mesh then fits the wrap)",
                                  e.map(), e.boundary(), e.labels());
  }
}

}  // namespace polycube::pipeline
