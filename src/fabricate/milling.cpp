//! Whether a part can be milled (see milling.h).
#include "fabricate/milling.h"

#include "core/errors.h"

#include <embree3/rtcore.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace polycube::fabricate {

namespace {

using core::Vec3;

//! A triangle is side-on or facing the tool when n . d <= this (unit vectors).
constexpr double kSideOn = 1e-9;
//! The sample is lifted off the surface by this fraction of the bounding-box diagonal.
constexpr double kLift = 1e-5;

//! Per-triangle geometry of a part.
struct Triangles {
  std::vector<Vec3> normal;  //!< #T unit outward normals (zero for a degenerate triangle)
  std::vector<Vec3> sample;  //!< #T barycentres lifted along the normal
  std::vector<double> area;  //!< #T
  double total_area = 0.0;
};

//! Bounding box of the points: centre and diagonal.
struct Box {
  Vec3 centre = Vec3::Zero();
  double diagonal = 0.0;
};

Box bounding_box(const core::TriMesh& m) {
  if (m.points.empty()) return {};
  Vec3 lo = m.points.front(), hi = m.points.front();
  for (const Vec3& p : m.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {0.5 * (lo + hi), (hi - lo).norm()};
}

Triangles triangles(const core::TriMesh& m, double lift) {
  Triangles out;
  const std::size_t n = m.cells.size();
  out.normal.resize(n);
  out.sample.resize(n);
  out.area.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& c = m.cells[t];
    const Vec3 &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
    const Vec3 cross = (b - a).cross(d - a);
    const double len = cross.norm();
    out.area[t] = 0.5 * len;
    out.normal[t] = len > 0 ? Vec3(cross / len) : Vec3::Zero();
    out.sample[t] = (a + b + d) / 3.0 + lift * out.normal[t];
    out.total_area += out.area[t];
  }
  return out;
}

//! Casts segments against the part's surface with Embree (one thread, so the tree and the
//! answers do not depend on the machine's load).
class SegmentCaster {
 public:
  explicit SegmentCaster(const core::TriMesh& m) {
    const Box box = bounding_box(m);
    centre_ = box.centre;
    reach_ = 1.5 * box.diagonal;
    device_ = rtcNewDevice("threads=1");
    if (!device_) throw core::Error("milling: Embree could not create a device");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.points.size()));
    auto* f = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.cells.size()));
    if (!v || !f) {
      rtcReleaseGeometry(geom);
      fail("allocating the buffers");
    }
    // Centred on the bounding box so that single precision keeps ~1e-7 of the diagonal.
    for (std::size_t i = 0; i < m.points.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(m.points[i][k] - centre_[k]);
    for (std::size_t t = 0; t < m.cells.size(); ++t)
      for (int k = 0; k < 3; ++k) f[3 * t + k] = static_cast<unsigned>(m.cells[t][k]);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) fail("building the tree");
  }
  ~SegmentCaster() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  SegmentCaster(const SegmentCaster&) = delete;
  SegmentCaster& operator=(const SegmentCaster&) = delete;

  //! Whether the segment coming along unit `d` from outside the part to `target` hits it.
  [[nodiscard]] bool blocked(const Vec3& target, const Vec3& d) const {
    const Vec3 o = target - centre_ - reach_ * d;
    RTCRay ray{};
    ray.org_x = static_cast<float>(o.x());
    ray.org_y = static_cast<float>(o.y());
    ray.org_z = static_cast<float>(o.z());
    ray.dir_x = static_cast<float>(d.x());
    ray.dir_y = static_cast<float>(d.y());
    ray.dir_z = static_cast<float>(d.z());
    ray.tnear = 0.0f;
    ray.tfar = static_cast<float>(reach_);
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar < 0.0f;  // set to -inf on a hit
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    const RTCError e = rtcGetDeviceError(device_);
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
    throw core::Error("milling: Embree failed " + what + " (error " +
                      std::to_string(static_cast<int>(e)) + ")");
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  Vec3 centre_;
  double reach_ = 0.0;  //!< longer than any segment inside the bounding box
};

//! The rule of milling.h: side-on or facing the tool travelling along `d`, and nothing between
//! the outside and the lifted sample.
bool reaches(const SegmentCaster& caster, const Triangles& tris, std::size_t t, const Vec3& d) {
  return tris.normal[t].dot(d) <= kSideOn && !caster.blocked(tris.sample[t], d);
}

//! `directions` unit vectors evenly spaced in the plane orthogonal to unit `axis`, the first
//! along the coordinate axis least aligned with it (projected).
std::vector<Vec3> tool_directions(const Vec3& axis, int directions) {
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(axis[k]) < std::abs(axis[least])) least = k;
  const Vec3 u = (Vec3::Unit(least) - axis[least] * axis).normalized();
  const Vec3 v = axis.cross(u);
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(directions));
  for (int i = 0; i < directions; ++i) {
    const double angle = 2.0 * M_PI * i / directions;
    out.push_back(std::cos(angle) * u + std::sin(angle) * v);
  }
  return out;
}

double area_fraction(const Triangles& tris, const std::vector<std::uint8_t>& flags,
                     std::uint8_t value) {
  double a = 0.0;
  for (std::size_t t = 0; t < flags.size(); ++t)
    if (flags[t] == value) a += tris.area[t];
  return tris.total_area > 0 ? a / tris.total_area : 0.0;
}

//! four_axis on a built caster (choose_axis tries several axes on one tree).
FourAxis check_four_axis(const SegmentCaster& caster, const Triangles& tris, const Axis& axis,
                         int directions) {
  FourAxis out;
  out.axis = {axis.point, axis.direction.normalized()};
  // Degenerate triangles carry no area: reported reached.
  out.reached.assign(tris.area.size(), 0);
  for (std::size_t t = 0; t < tris.area.size(); ++t)
    if (tris.area[t] == 0.0) out.reached[t] = 1;
  // thesis §6.5.3: per rotation, a ray through each barycentre; a triangle reached once is done.
  for (const Vec3& d : tool_directions(out.axis.direction, directions))
    for (std::size_t t = 0; t < tris.area.size(); ++t)
      if (!out.reached[t] && reaches(caster, tris, t, d)) out.reached[t] = 1;
  out.unreached = area_fraction(tris, out.reached, 0);
  return out;
}

}  // namespace

ThreeAxis three_axis(const core::TriMesh& part, const Vec3& down,
                     const std::vector<int>& base_triangles) {
  PC_REQUIRE(down.norm() > 0, "three_axis: zero down direction");
  const Vec3 d = down.normalized();  // the tool travels downwards
  ThreeAxis out;
  out.triangle.assign(part.cells.size(), ThreeAxis::kReachable);
  for (const int t : base_triangles) {
    PC_REQUIRE(t >= 0 && t < part.num_cells(), "three_axis: base triangle out of range");
    out.triangle[static_cast<std::size_t>(t)] = ThreeAxis::kBase;
  }
  if (part.cells.empty()) return out;

  const Triangles tris = triangles(part, kLift * bounding_box(part).diagonal);
  const SegmentCaster caster(part);
  for (std::size_t t = 0; t < part.cells.size(); ++t) {
    std::uint8_t& c = out.triangle[t];
    if (c == ThreeAxis::kBase || tris.area[t] == 0.0) continue;
    // thesis §6.5.2: normals more than 90° from the milling direction are not a height field.
    if (tris.normal[t].dot(d) > kSideOn)
      c = ThreeAxis::kTurnedAway;
    else if (!reaches(caster, tris, t, d))
      c = ThreeAxis::kOccluded;
  }
  out.height_field_unreachable = area_fraction(tris, out.triangle, ThreeAxis::kTurnedAway);
  out.occluded = area_fraction(tris, out.triangle, ThreeAxis::kOccluded);
  out.unreachable = out.height_field_unreachable + out.occluded;
  return out;
}

FourAxis four_axis(const core::TriMesh& part, const Axis& axis, int directions) {
  PC_REQUIRE(axis.direction.norm() > 0, "four_axis: zero axis direction");
  PC_REQUIRE(directions >= 1, "four_axis: no tool direction");
  if (part.cells.empty()) return {{axis.point, axis.direction.normalized()}, 0.0, {}};
  const Triangles tris = triangles(part, kLift * bounding_box(part).diagonal);
  const SegmentCaster caster(part);
  return check_four_axis(caster, tris, axis, directions);
}

Axis choose_axis(const core::TriMesh& part, int directions) {
  PC_REQUIRE(directions >= 1, "choose_axis: no tool direction");
  Axis best;
  if (part.cells.empty()) return best;
  // Area-weighted centroid and normal covariance.
  const Triangles tris = triangles(part, kLift * bounding_box(part).diagonal);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Vec3 centroid = Vec3::Zero();
  for (std::size_t t = 0; t < part.cells.size(); ++t) {
    const auto& c = part.cells[t];
    cov += tris.area[t] * tris.normal[t] * tris.normal[t].transpose();
    centroid += tris.area[t] / 3.0 * (part.points[c[0]] + part.points[c[1]] + part.points[c[2]]);
  }
  if (tris.total_area > 0) best.point = centroid / tris.total_area;

  // Principal directions, smallest eigenvalue first; keep the first with the least unreached.
  const SegmentCaster caster(part);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    Vec3 dir = eig.eigenvectors().col(k).normalized();
    int big = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(dir[i]) > std::abs(dir[big])) big = i;
    if (dir[big] < 0) dir = -dir;
    const double unreached = check_four_axis(caster, tris, {best.point, dir}, directions).unreached;
    if (unreached < least) {
      least = unreached;
      best.direction = dir;
    }
  }
  return best;
}

}  // namespace polycube::fabricate
