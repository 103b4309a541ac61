//! Reading the input of the construction (see input.h).
#include "pipeline/input.h"

#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"

#include <fmt/format.h>

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

namespace {

//! The construction, its InputErrors naming the file.
construct::ConstructResult construct_named(const ConstructInput& input, const std::filesystem::path& path,
                                           const construct::ConstructOptions& options) {
  try {
    if (input.tets) return construct::construct_polycube(*input.tets, options);
    return construct::construct_polycube(*input.surface, options);
  } catch (const core::InputError& e) {
    throw core::InputError(path.string(), 0, e.what());
  }
}

}  // namespace

construct::ConstructResult construct_from_input(const ConstructInput& input,
                                                const std::filesystem::path& path,
                                                const construct::ConstructOptions& options) {
  try {
    return construct_named(input, path, options);
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

construct::ConstructResult construct_with_wrap_fallback(ConstructInput& input, const std::filesystem::path& path,
                                                        const construct::ConstructOptions& options,
                                                        const repair::RepairOptions& wrap_settings,
                                                        bool wrap_fallback, bool inject_unwrapped_failure,
                                                        WrapFallback& fallback) {
  fallback = {};
  const bool may_wrap = wrap_fallback && input.surface && !input.wrapped;
  std::string first_failure;
  const bool injected = inject_unwrapped_failure && input.surface && !input.wrapped;
  if (!may_wrap && !injected) return construct_from_input(input, path, options);
  try {
    if (injected) throw construct::NotCertified("injected failure (--inject-failure construct-unwrapped)", {}, {}, {});
    return construct_named(input, path, options);
  } catch (const construct::NotCertified& e) {
    if (!may_wrap) throw;
    first_failure = e.what();
  }
  core::logger().warn("construct: no attempt could be certified ({}); constructing the surface's alpha wrap instead "
                      "(it closes slits and gaps thinner than the tets; the mesh then fits the wrap)",
                      first_failure);
  core::TriMesh wrapped = *input.surface;
  repair::RepairOptions wrap;
  wrap.wrap = true;
  wrap.wrap_alpha = wrap_settings.wrap_alpha;
  wrap.wrap_offset = wrap_settings.wrap_offset;
  const repair::RepairReport report = repair::repair_surface(wrapped, wrap);
  construct::check_closed_surface(wrapped);
  input.unwrapped = std::move(*input.surface);
  input.surface = wrapped;
  input.target = std::move(wrapped);
  input.wrapped = true;
  input.distances = {};
  fallback.taken = fmt::format("alpha wrap ({} triangles; ball {:.3g}, offset {:.3g} model units)",
                               report.wrap_triangles, report.wrap_alpha, report.wrap_offset);
  fallback.why = first_failure;
  try {
    return construct_named(input, path, options);
  } catch (const construct::NotCertified& e) {
    throw construct::NotCertified(fmt::format("{}; its alpha wrap: {}", first_failure, e.what()), e.map(),
                                  e.boundary(), e.labels());
  }
}

}  // namespace polycube::pipeline
