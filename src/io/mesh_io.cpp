#include "io/mesh_io.h"

#include "core/errors.h"
#include "core/log.h"
#include "io/formats.h"
#include "io/parse.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace polycube::io {

namespace fs = std::filesystem;
using core::InputError;
using core::MeshData;

namespace {

std::string errno_text() { return std::strerror(errno); }

//! The whole file, or InputError for a missing file, a folder, or an unreadable file.
std::string read_file(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(name, 0, "no such file");
  if (fs::is_directory(st)) throw InputError(name, 0, "is a directory, not a file");
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(name, 0, "cannot open: " + errno_text());
  std::string bytes;
  if (fs::is_regular_file(st)) {
    const auto size = fs::file_size(path, ec);
    if (!ec) bytes.reserve(size);
  }
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof(buf));
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = errno_text();
      ::close(fd);
      throw InputError(name, 0, "cannot read: " + why);
    }
    bytes.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return bytes;
}

//! Write bytes to a temporary file next to \p path, then rename it over \p path.
void write_bytes_atomic(const fs::path& path, std::string_view bytes) {
  static std::atomic<unsigned> counter{0};
  const std::string name = path.string();
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw core::OutputError(name, 0, "is a directory, cannot write a file there");
  fs::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec))
    throw core::OutputError(name, 0, "cannot write: folder '" + dir.string() + "' does not exist");
  std::string tmp_name(1, '.');  // built piecewise: GCC 12 warns falsely on "." + string
  tmp_name += path.filename().string();
  tmp_name += ".tmp.";
  tmp_name += std::to_string(::getpid());
  tmp_name += '.';
  tmp_name += std::to_string(counter++);
  const fs::path tmp = dir / tmp_name;
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw core::OutputError(name, 0, "cannot create a file in '" + dir.string() + "': " + errno_text());
  auto abandon = [&](const std::string& why) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw core::OutputError(name + ": write failed: " + why);
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      abandon(errno_text());
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    const std::string why = errno_text();
    ::unlink(tmp.c_str());
    throw core::OutputError(name + ": write failed: " + why);
  }
  if (::rename(tmp.c_str(), name.c_str()) != 0) {
    const std::string why = errno_text();
    ::unlink(tmp.c_str());
    throw core::OutputError(name + ": cannot replace the file: " + why);
  }
}

template <class Cells>
void check_cells(const Cells& cells, std::size_t n_points, const std::vector<int>& labels, const char* kind,
                 const std::string& name) {
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (const int v : cells[c])
      if (v < 0 || static_cast<std::size_t>(v) >= n_points)
        throw InputError(name, 0,
                         std::string(kind) + " " + std::to_string(c) + " refers to vertex " + std::to_string(v) +
                             " out of range (0.." + std::to_string(static_cast<long long>(n_points) - 1) + ")");
  if (!labels.empty() && labels.size() != cells.size())
    throw InputError(name, 0,
                     std::string(kind) + " labels: " + std::to_string(labels.size()) + " for " +
                         std::to_string(cells.size()) + " elements");
}

void check_fields(const std::vector<core::Field>& fields, std::size_t n, const char* where,
                  const std::string& name) {
  for (const core::Field& f : fields) {
    if (f.name.empty()) throw InputError(name, 0, std::string(where) + " field without a name");
    if (f.values.size() != n)
      throw InputError(name, 0,
                       std::string(where) + " field '" + f.name + "' has " + std::to_string(f.values.size()) +
                           " values for " + std::to_string(n) + " entities");
    for (const double v : f.values)
      if (!std::isfinite(v))
        throw InputError(name, 0, std::string(where) + " field '" + f.name + "' has a non-finite value");
  }
}

bool any_nonzero(const std::vector<int>& v) {
  return std::any_of(v.begin(), v.end(), [](int x) { return x != 0; });
}

bool has_cell_labels(const MeshData& d) {
  return !d.triangle_labels.empty() || !d.quad_labels.empty() || !d.tet_labels.empty() ||
         !d.hex_labels.empty() || !d.edge_labels.empty();
}

//! Labels worth a warning when dropped (all-zero labels carry nothing).
bool has_meaningful_cell_labels(const MeshData& d) {
  return any_nonzero(d.triangle_labels) || any_nonzero(d.quad_labels) || any_nonzero(d.tet_labels) ||
         any_nonzero(d.hex_labels) || any_nonzero(d.edge_labels);
}

//! The data reduced to what format \p f holds: refuse elements it cannot hold, drop (with a
//! warning) attributes it cannot hold, split quads for STL.
MeshData fit_to_format(const MeshData& d, Format f, const std::string& name) {
  validate(d, name);
  const detail::Capabilities cap = detail::capabilities(f);
  const std::string fmt = format_name(f);
  auto refuse = [&](std::size_t n, const char* what) {
    throw InputError(name, 0,
                     "a ." + fmt + " file cannot hold " + what + " (the data has " + std::to_string(n) +
                         "); use .mesh, .vtk or .msh");
  };
  if (!d.tets.empty() && !cap.tets) refuse(d.tets.size(), "tetrahedra");
  if (!d.hexes.empty() && !cap.hexes) refuse(d.hexes.size(), "hexahedra");
  if (d.num_cells() == 0)
    throw InputError(name, 0, "nothing to write: the data holds no triangles, quads, tets or hexes");

  MeshData out = d;
  auto drop = [&](const char* what) {
    core::logger().warn("{}: a .{} file cannot hold {}; they are not written", name, fmt, what);
  };
  if (!out.edges.empty() && !cap.edges) {
    drop("edges");
    out.edges.clear();
    out.edge_labels.clear();
  }
  if (has_cell_labels(out) && !cap.cell_labels) {
    if (has_meaningful_cell_labels(out)) drop("element labels");
    out.edge_labels.clear();
    out.triangle_labels.clear();
    out.quad_labels.clear();
    out.tet_labels.clear();
    out.hex_labels.clear();
  }
  if (!out.point_labels.empty() && !cap.point_labels) {
    if (any_nonzero(out.point_labels)) drop("vertex labels");
    out.point_labels.clear();
  }
  if (!out.point_data.empty() && !cap.point_data) {
    drop("point data");
    out.point_data.clear();
  }
  if (!out.cell_data.empty() && !cap.cell_data) {
    drop("cell data");
    out.cell_data.clear();
  }
  if (f == Format::Stl) {
    for (const core::Vec3& p : out.points)
      if (p.cwiseAbs().maxCoeff() > static_cast<double>(std::numeric_limits<float>::max()))
        throw InputError(name, 0, "a coordinate exceeds the single-precision range of STL");
    if (out.triangles.size() + 2 * out.quads.size() > 0xffffffffULL)
      throw InputError(name, 0, "too many triangles for STL");
  }
  if (!out.quads.empty() && !cap.quads) {
    // Only STL gets here (every other surface format holds quads): split each quad 0-2.
    core::logger().info("{}: {} quads split into two triangles each", name, out.quads.size());
    for (const core::Quad& q : out.quads) {
      out.triangles.push_back({q[0], q[1], q[2]});
      out.triangles.push_back({q[0], q[2], q[3]});
    }
    out.quads.clear();
    out.quad_labels.clear();
  }
  return out;
}

bool all_space(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

}  // namespace

namespace detail {
Capabilities capabilities(Format f) {
  Capabilities c;
  switch (f) {
    case Format::Obj:
    case Format::Off:
      c.triangles = c.quads = true;
      break;
    case Format::Ply:
      c.triangles = c.quads = true;
      c.point_data = c.cell_data = true;
      break;
    case Format::Stl:
      c.triangles = true;
      break;
    case Format::Medit:
      c.triangles = c.quads = c.tets = c.hexes = c.edges = true;
      c.cell_labels = c.point_labels = true;
      break;
    case Format::Vtk:
      c.triangles = c.quads = c.tets = c.hexes = true;
      c.cell_labels = c.point_labels = c.point_data = c.cell_data = true;
      break;
    case Format::Msh:
      c.triangles = c.quads = c.tets = c.hexes = c.edges = true;
      c.cell_labels = true;
      break;
  }
  return c;
}
}  // namespace detail

void detail::add_polygon(MeshData& d, const std::vector<int>& poly) {
  if (poly.size() == 3) {
    d.triangles.push_back({poly[0], poly[1], poly[2]});
  } else if (poly.size() == 4) {
    d.quads.push_back({poly[0], poly[1], poly[2], poly[3]});
  } else {
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) d.triangles.push_back({poly[0], poly[i], poly[i + 1]});
  }
}

Format format_from_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return Format::Obj;
  if (ext == ".off") return Format::Off;
  if (ext == ".stl") return Format::Stl;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".mesh") return Format::Medit;
  if (ext == ".vtk") return Format::Vtk;
  if (ext == ".msh") return Format::Msh;
  throw InputError(path.string(), 0,
                   (ext.empty() ? std::string("no file extension") : "unknown file extension " + detail::quote(ext)) +
                       " (supported: .obj .off .stl .ply .mesh .vtk .msh)");
}

const char* format_name(Format f) {
  switch (f) {
    case Format::Obj: return "obj";
    case Format::Off: return "off";
    case Format::Stl: return "stl";
    case Format::Ply: return "ply";
    case Format::Medit: return "mesh";
    case Format::Vtk: return "vtk";
    case Format::Msh: return "msh";
  }
  return "?";
}

bool is_volume_format(Format f) { return f == Format::Medit || f == Format::Vtk || f == Format::Msh; }

void validate(const MeshData& d, const std::string& name) {
  for (std::size_t i = 0; i < d.points.size(); ++i)
    if (!d.points[i].allFinite())
      throw InputError(name, 0, "vertex " + std::to_string(i) + " has a non-finite coordinate");
  const std::size_t n = d.points.size();
  check_cells(d.edges, n, d.edge_labels, "edge", name);
  check_cells(d.triangles, n, d.triangle_labels, "triangle", name);
  check_cells(d.quads, n, d.quad_labels, "quad", name);
  check_cells(d.tets, n, d.tet_labels, "tet", name);
  check_cells(d.hexes, n, d.hex_labels, "hex", name);
  if (!d.point_labels.empty() && d.point_labels.size() != n)
    throw InputError(name, 0,
                     "vertex labels: " + std::to_string(d.point_labels.size()) + " for " + std::to_string(n) +
                         " vertices");
  check_fields(d.point_data, n, "point", name);
  check_fields(d.cell_data, d.num_cells(), "cell", name);
}

MeshData read_mesh_from_memory(std::string_view bytes, Format format, const std::string& name) {
  // A UTF-8 byte order mark, as Windows editors write, is not part of the text (binary STL's
  // 80-byte header may hold anything, so it is left alone there).
  static constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (format != Format::Stl && bytes.starts_with(kBom)) bytes.remove_prefix(kBom.size());
  if (all_space(bytes)) throw InputError(name, 0, "empty file");
  MeshData d;
  switch (format) {
    case Format::Obj: d = detail::read_obj(bytes, name); break;
    case Format::Off: d = detail::read_off(bytes, name); break;
    case Format::Stl: d = detail::read_stl(bytes, name); break;
    case Format::Ply: d = detail::read_ply(bytes, name); break;
    case Format::Medit: d = detail::read_medit(bytes, name); break;
    case Format::Vtk: d = detail::read_vtk(bytes, name); break;
    case Format::Msh: d = detail::read_msh(bytes, name); break;
  }
  if (d.num_cells() == 0) throw InputError(name, 0, "no triangles, quads, tets or hexes in the file");
  validate(d, name);  // the readers check as they go; this is the safety net
  return d;
}

MeshData read_mesh(const fs::path& path) {
  const Format f = format_from_path(path);
  const std::string bytes = read_file(path);
  return read_mesh_from_memory(bytes, f, path.string());
}

std::string write_mesh_to_string(const MeshData& data, Format format, const WriteOptions& options,
                                 const std::string& name) {
  const MeshData d = fit_to_format(data, format, name);
  switch (format) {
    case Format::Obj: return detail::write_obj(d, options);
    case Format::Off: return detail::write_off(d, options);
    case Format::Stl: return detail::write_stl(d, options);
    case Format::Ply: return detail::write_ply(d, options);
    case Format::Medit: return detail::write_medit(d, options);
    case Format::Vtk: return detail::write_vtk(d, options);
    case Format::Msh: return detail::write_msh(d, options);
  }
  return {};
}

void write_mesh(const fs::path& path, const MeshData& data, const WriteOptions& options) {
  const Format f = format_from_path(path);
  const std::string bytes = write_mesh_to_string(data, f, options, path.string());
  write_bytes_atomic(path, bytes);
}

core::TriMesh read_surface(const fs::path& path) {
  const MeshData d = read_mesh(path);
  if (d.triangles.empty() && d.quads.empty())
    throw InputError(path.string(), 0, "holds no surface elements (triangles or quads)");
  core::TriMesh m;
  m.points = d.points;
  m.cells = d.triangles;
  const bool labeled = (d.triangles.empty() || !d.triangle_labels.empty()) && (d.quads.empty() || !d.quad_labels.empty());
  if (labeled) m.labels = d.triangle_labels;
  for (std::size_t q = 0; q < d.quads.size(); ++q) {
    const core::Quad& c = d.quads[q];
    m.cells.push_back({c[0], c[1], c[2]});
    m.cells.push_back({c[0], c[2], c[3]});
    if (labeled) m.labels.insert(m.labels.end(), 2, d.quad_labels[q]);
  }
  return m;
}

void write_text_atomic(const fs::path& path, const std::string& text) { write_bytes_atomic(path, text); }

void write_labeling(const fs::path& path, const std::vector<int>& labels) {
  std::string text;
  text.reserve(labels.size() * 2);
  for (const int l : labels) {
    PC_REQUIRE(l >= 0 && l < 6, "write_labeling: label out of range");
    text += static_cast<char>('0' + l);
    text += '\n';
  }
  write_bytes_atomic(path, text);
}

}  // namespace polycube::io
