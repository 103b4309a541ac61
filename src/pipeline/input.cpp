//! Reading the input of the construction (see input.h).
#include "pipeline/input.h"

#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"
#include "repair/thin_gaps.h"

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

namespace {

//! Replace the input's surface and target by the surface's alpha wrap (the surface as read kept
//! in `unwrapped`); what was done, for the report.
std::string wrap_input(ConstructInput& input, const repair::RepairOptions& settings) {
  core::TriMesh wrapped = *input.surface;
  repair::RepairOptions wrap;
  wrap.wrap = true;
  wrap.wrap_alpha = settings.wrap_alpha;
  wrap.wrap_offset = settings.wrap_offset;
  const repair::RepairReport report = repair::repair_surface(wrapped, wrap);
  construct::check_closed_surface(wrapped);
  input.unwrapped = std::move(*input.surface);
  input.surface = wrapped;
  input.target = std::move(wrapped);
  input.wrapped = true;
  input.distances = {};
  return fmt::format("alpha wrap ({} triangles; ball {:.3g}, offset {:.3g} model units)", report.wrap_triangles,
                     report.wrap_alpha, report.wrap_offset);
}

//! Undo wrap_input().
void unwrap_input(ConstructInput& input) {
  input.surface = std::move(*input.unwrapped);
  input.unwrapped.reset();
  input.target = *input.surface;
  input.wrapped = false;
  input.distances = {};
}

}  // namespace

construct::ConstructResult construct_with_wrap_fallback(ConstructInput& input, const std::filesystem::path& path,
                                                        const construct::ConstructOptions& options,
                                                        const repair::RepairOptions& wrap_settings,
                                                        bool wrap_fallback, bool inject_unwrapped_failure,
                                                        WrapFallback& fallback) {
  fallback = {};
  const bool as_read = input.surface && !input.wrapped;
  const bool may_wrap = wrap_fallback && as_read;
  const bool injected = inject_unwrapped_failure && as_read;
  if (!may_wrap && !injected) return construct_from_input(input, path, options);

  // 1. The first attempt on the surface as read, the whole plan unless the surface has gaps the
  //    wrap closes: then a failing first attempt is followed by the wrap (at the first attempt's
  //    usual deadline, half the budget), the likelier remedy, and the plan's other attempts only
  //    come after the wrap failed too.
  const repair::ThinGaps gaps = may_wrap ? repair::gaps_the_wrap_closes(*input.surface, wrap_settings) : repair::ThinGaps{};
  const bool wrap_early = gaps.vertices > 0 && options.max_attempts > 1;
  construct::ConstructOptions first = options;
  if (wrap_early) {
    first.max_attempts = 1;
    if (first.time_limit > 0) first.time_limit = 0.5 * options.time_limit;
    core::logger().info("construct: {}, which the alpha wrap closes; if the first attempt fails, the wrap is "
                        "constructed before the other attempts",
                        gaps.line());
  }
  std::string first_failure;
  try {
    if (injected) throw construct::NotCertified("injected failure (--inject-failure construct-unwrapped)", {}, {}, {});
    // A test's failed first attempt (ConstructOptions::inject_failed_attempts) alone in the plan
    // would still be certified as the best one: it fails here as a real one does.
    if (wrap_early && first.inject_failed_attempts > 0)
      throw construct::NotCertified("injected failure of the first attempt (--inject-failure construct-attempt-1)",
                                    {}, {}, {});
    return construct_named(input, path, first);
  } catch (const construct::NotCertified& e) {
    if (!may_wrap) throw;
    first_failure = e.what();
  }

  // 2. The alpha wrap, with the whole plan and budget.
  core::logger().warn("construct: {} could not be certified ({}); constructing the surface's alpha wrap instead (it "
                      "closes slits and gaps thinner than the tets; the mesh then fits the wrap)",
                      wrap_early ? "the first attempt" : "no attempt", first_failure);
  fallback.taken = wrap_input(input, wrap_settings);
  fallback.why = first_failure;
  construct::ConstructOptions on_wrap = options;
  on_wrap.inject_failed_attempts = 0;  // the tests' failures are the surface as read's
  std::string wrap_failure;
  try {
    return construct_named(input, path, on_wrap);
  } catch (const construct::NotCertified& e) {
    if (!wrap_early) throw construct::NotCertified(fmt::format("{}; its alpha wrap: {}", first_failure, e.what()),
                                                   e.map(), e.boundary(), e.labels());
    wrap_failure = e.what();
  }

  // 3. The whole plan on the surface as read (its first attempt again).
  core::logger().warn("construct: the alpha wrap could not be certified either ({}); the planned attempts on the "
                      "surface as read",
                      wrap_failure);
  unwrap_input(input);
  fallback = {};
  try {
    return construct_named(input, path, options);
  } catch (const construct::NotCertified& e) {
    throw construct::NotCertified(fmt::format("{}; its alpha wrap: {}", e.what(), wrap_failure), e.map(), e.boundary(),
                                  e.labels());
  }
}

}  // namespace polycube::pipeline
