//! 3MF through lib3mf 1.8's C interface. Every object lib3mf hands out is a new instance the
//! caller must release; Handle does that, so no path (error or not) leaks one. The package is
//! built in memory and written with write_text_atomic, so the file appears whole or not at all.
#include "io/three_mf.h"

#include "core/errors.h"
#include "core/log.h"
#include "io/mesh_io.h"

#include <array>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

// After the standard headers: lib3mf's platform headers define SAL macros (_In_, _Out_, ...).
#include <Model/COM/NMR_DLLInterfaces.h>

namespace polycube::io {

namespace {

namespace fs = std::filesystem;
using core::InputError;

//! Owns one lib3mf instance and releases it, also while an exception unwinds.
class Handle {
 public:
  Handle() = default;
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : h_(std::exchange(other.h_, nullptr)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      h_ = std::exchange(other.h_, nullptr);
    }
    return *this;
  }
  //! For lib3mf's out parameters: drops what is held, then receives the new instance.
  NMR::PLib3MFBase** out() {
    reset();
    return &h_;
  }
  [[nodiscard]] NMR::PLib3MFBase* get() const { return h_; }

 private:
  void reset() {
    if (h_ != nullptr) NMR::lib3mf_release(h_);
    h_ = nullptr;
  }
  NMR::PLib3MFBase* h_ = nullptr;
};

//! Whether a failure is the file's fault (reading: InputError) or lib3mf's (writing: Error).
enum class Direction { Read, Write };

//! lib3mf's message for the last failure of \p on, with its error code.
std::string lib3mf_message(NMR::PLib3MFBase* on, LIB3MFRESULT result) {
  DWORD code = 0;
  LPCSTR text = nullptr;
  char hex[32];
  if (on != nullptr && NMR::lib3mf_getlasterror(on, &code, &text) == LIB3MF_OK && text != nullptr &&
      *text != '\0') {
    std::snprintf(hex, sizeof(hex), "0x%x", code);
    return std::string(text) + " (lib3mf error " + hex + ")";
  }
  std::snprintf(hex, sizeof(hex), "0x%x", static_cast<unsigned>(result));
  return std::string("lib3mf error ") + hex;
}

//! Throw a one-line error "file: 3MF what failed: lib3mf's message" unless \p result is OK.
//! \param on the instance whose function was called (it holds the error text), or nullptr.
void check(LIB3MFRESULT result, NMR::PLib3MFBase* on, const std::string& file, Direction dir,
           const char* what) {
  if (result == LIB3MF_OK) return;
  const std::string why = std::string("3MF: ") + what + " failed: " + lib3mf_message(on, result);
  if (dir == Direction::Read) throw InputError(file, 0, why);
  throw core::Error(file + ": " + why);
}

//! "object 2 ('lid')": how messages name an object.
std::string object_label(std::size_t i, const std::string& name) {
  std::string s = "object " + std::to_string(i);
  if (!name.empty()) s += " ('" + name + "')";
  return s;
}

// --- writing ------------------------------------------------------------------------------

//! Refuse, before anything is built, data a 3MF file cannot hold.
void check_objects(const std::vector<ThreeMfObject>& objects, const std::string& file) {
  if (objects.empty())
    throw InputError(file, 0, "nothing to write: no objects (a 3MF file needs at least one)");
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  constexpr std::size_t kDwordMax = std::numeric_limits<DWORD>::max();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const core::TriMesh& m = objects[i].mesh;
    const std::string who = object_label(i, objects[i].name);
    if (m.cells.empty()) throw InputError(file, 0, who + " has no triangles");
    if (m.points.size() > kDwordMax || m.cells.size() > kDwordMax)
      throw InputError(file, 0, who + " has more vertices or triangles than 3MF can index");
    for (std::size_t v = 0; v < m.points.size(); ++v)
      if (!m.points[v].allFinite() || m.points[v].cwiseAbs().maxCoeff() > kFloatMax)
        throw InputError(file, 0,
                         who + ": vertex " + std::to_string(v) +
                             " is not finite or exceeds the single-precision range of 3MF");
    for (std::size_t t = 0; t < m.cells.size(); ++t) {
      const core::Tri& c = m.cells[t];
      for (const int v : c)
        if (v < 0 || static_cast<std::size_t>(v) >= m.points.size())
          throw InputError(file, 0,
                           who + ": triangle " + std::to_string(t) + " refers to vertex " +
                               std::to_string(v) + " out of range");
      // The 3MF core specification forbids it, and lib3mf's own message would not say which.
      if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
        throw InputError(file, 0,
                         who + ": triangle " + std::to_string(t) +
                             " repeats a vertex (3MF has no degenerate triangles)");
    }
  }
}

std::vector<NMR::MODELMESHVERTEX> to_vertices(const core::TriMesh& m) {
  std::vector<NMR::MODELMESHVERTEX> out(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v)
    for (int k = 0; k < 3; ++k) out[v].m_fPosition[k] = static_cast<float>(m.points[v][k]);
  return out;
}

std::vector<NMR::MODELMESHTRIANGLE> to_triangles(const core::TriMesh& m) {
  std::vector<NMR::MODELMESHTRIANGLE> out(m.cells.size());
  for (std::size_t t = 0; t < m.cells.size(); ++t)
    for (int k = 0; k < 3; ++k) out[t].m_nIndices[k] = static_cast<DWORD>(m.cells[t][k]);
  return out;
}

//! A UUID derived from the object's geometry and its place in the file (FNV-1a over both, in two
//! independent 64-bit lanes), in the 8-4-4-4-12 form with the version-4 and variant bits set.
//! lib3mf would draw random ones: with these, the same parts give the same file, byte for byte.
std::string content_uuid(std::size_t index, const ThreeMfObject& object, std::uint64_t salt) {
  std::array<std::uint64_t, 2> h{0xcbf29ce484222325ULL ^ salt, 0x84222325cbf29ce4ULL ^ ~salt};
  const auto mix = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint64_t& x : h) x = (x ^ b[i]) * 0x100000001b3ULL + (&x == &h[1] ? 0x9e37 : 0);
  };
  mix(&index, sizeof index);
  mix(object.name.data(), object.name.size());
  for (const core::Vec3& p : object.mesh.points) mix(p.data(), 3 * sizeof(double));
  for (const auto& t : object.mesh.cells) mix(t.data(), 3 * sizeof(int));
  std::array<unsigned char, 16> u{};
  for (int i = 0; i < 16; ++i) u[i] = static_cast<unsigned char>(h[i / 8] >> (8 * (i % 8)));
  u[6] = static_cast<unsigned char>((u[6] & 0x0f) | 0x40);
  u[8] = static_cast<unsigned char>((u[8] & 0x3f) | 0x80);
  std::string out;
  static const char* hex = "0123456789abcdef";
  for (int i = 0; i < 16; ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) out += '-';
    out += hex[u[i] >> 4];
    out += hex[u[i] & 15];
  }
  return out;
}

//! Builds one 3MF model: a base-material group holding one colour per object, then per object
//! a mesh object using its colour and a build item placing it as it is.
class ModelBuilder {
 public:
  explicit ModelBuilder(std::string file) : file_(std::move(file)) {
    check(NMR::lib3mf_createmodel(model_.out()), nullptr, file_, Direction::Write,
          "creating a model");
    check(NMR::lib3mf_model_setunit(model_.get(), NMR::MODELUNIT_MILLIMETER), model_.get(), file_,
          Direction::Write, "setting the unit");
    check(NMR::lib3mf_model_addbasematerialgroup(model_.get(), materials_.out()), model_.get(),
          file_, Direction::Write, "adding the material group");
    check(NMR::lib3mf_resource_getresourceid(materials_.get(), &material_group_), materials_.get(),
          file_, Direction::Write, "reading the material group id");
  }

  void add(std::size_t i, const ThreeMfObject& object) {
    const std::string label = object.name.empty() ? "part " + std::to_string(i) : object.name;
    const DWORD material = add_material(label, object.rgb);
    Handle mesh;
    check(NMR::lib3mf_model_addmeshobject(model_.get(), mesh.out()), model_.get(), file_,
          Direction::Write, "adding a mesh object");
    if (!object.name.empty())
      check(NMR::lib3mf_object_setnameutf8(mesh.get(), object.name.c_str()), mesh.get(), file_,
            Direction::Write, "naming an object");
    check(NMR::lib3mf_object_setuuidutf8(mesh.get(), content_uuid(i, object, 1).c_str()),
          mesh.get(), file_, Direction::Write, "setting an object's UUID");
    std::vector<NMR::MODELMESHVERTEX> vertices = to_vertices(object.mesh);
    std::vector<NMR::MODELMESHTRIANGLE> triangles = to_triangles(object.mesh);
    check(NMR::lib3mf_meshobject_setgeometry(mesh.get(), vertices.data(),
                                             static_cast<DWORD>(vertices.size()), triangles.data(),
                                             static_cast<DWORD>(triangles.size())),
          mesh.get(), file_, Direction::Write, "setting an object's geometry");
    Handle properties;
    check(NMR::lib3mf_object_createdefaultpropertyhandler(mesh.get(), properties.out()), mesh.get(),
          file_, Direction::Write, "creating an object's property handler");
    check(NMR::lib3mf_defaultpropertyhandler_setbasematerial(properties.get(), material_group_,
                                                             material),
          properties.get(), file_, Direction::Write, "setting an object's material");
    warn_if_open(mesh, i, object.name);
    Handle item;
    check(NMR::lib3mf_model_addbuilditem(model_.get(), mesh.get(), nullptr, item.out()),
          model_.get(), file_, Direction::Write, "adding a build item");
    check(NMR::lib3mf_builditem_setuuidutf8(item.get(), content_uuid(i, object, 2).c_str()),
          item.get(), file_, Direction::Write, "setting a build item's UUID");
    if (i == 0)
      check(NMR::lib3mf_model_setbuilduuidutf8(model_.get(), content_uuid(i, object, 3).c_str()),
            model_.get(), file_, Direction::Write, "setting the build's UUID");
  }

  //! The whole package, as the bytes of a .3mf file.
  std::string package() {
    Handle writer;
    check(NMR::lib3mf_model_querywriter(model_.get(), "3mf", writer.out()), model_.get(), file_,
          Direction::Write, "creating the writer");
    ULONG64 size = 0;
    check(NMR::lib3mf_writer_getstreamsize(writer.get(), &size), writer.get(), file_,
          Direction::Write, "measuring the package");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    check(
        NMR::lib3mf_writer_writetobuffer(writer.get(), reinterpret_cast<BYTE*>(bytes.data()), size),
        writer.get(), file_, Direction::Write, "writing the package");
    return bytes;
  }

 private:
  DWORD add_material(const std::string& label, const std::array<std::uint8_t, 3>& rgb) {
    DWORD index = 0;
    check(NMR::lib3mf_basematerial_addmaterialutf8(materials_.get(), label.c_str(), rgb[0], rgb[1],
                                                   rgb[2], &index),
          materials_.get(), file_, Direction::Write, "adding a material");
    // lib3mf 1.8 gives a material added by colour an alpha of 0 (transparent): make it opaque.
    check(NMR::lib3mf_basematerial_setdisplaycolorrgba(materials_.get(), index, rgb[0], rgb[1],
                                                       rgb[2], 255),
          materials_.get(), file_, Direction::Write, "setting a material's colour");
    return index;
  }

  //! Slicers repair or reject a part that is not a closed oriented surface: say so early.
  void warn_if_open(const Handle& mesh, std::size_t i, const std::string& name) const {
    BOOL closed = 0;
    check(NMR::lib3mf_meshobject_ismanifoldandoriented(mesh.get(), &closed), mesh.get(), file_,
          Direction::Write, "checking an object's surface");
    if (closed == 0)
      core::logger().warn("{}: {} is not a closed, consistently oriented surface", file_,
                          object_label(i, name));
  }

  std::string file_;
  Handle model_;
  Handle materials_;
  DWORD material_group_ = 0;
};

// --- reading ------------------------------------------------------------------------------

//! Reads the mesh objects of one loaded model.
class ModelReader {
 public:
  explicit ModelReader(std::string file) : file_(std::move(file)) {
    check(NMR::lib3mf_createmodel(model_.out()), nullptr, file_, Direction::Read,
          "creating a model");
    Handle reader;
    check(NMR::lib3mf_model_queryreader(model_.get(), "3mf", reader.out()), model_.get(), file_,
          Direction::Read, "creating the reader");
    check(NMR::lib3mf_reader_readfromfileutf8(reader.get(), file_.c_str()), reader.get(), file_,
          Direction::Read, "reading the package");
  }

  std::vector<ThreeMfObject> objects() {
    std::vector<ThreeMfObject> out;
    Handle it;
    check(NMR::lib3mf_model_getmeshobjects(model_.get(), it.out()), model_.get(), file_,
          Direction::Read, "listing the mesh objects");
    for (;;) {
      BOOL more = 0;
      check(NMR::lib3mf_resourceiterator_movenext(it.get(), &more), it.get(), file_,
            Direction::Read, "listing the mesh objects");
      if (more == 0) break;
      Handle mesh;
      check(NMR::lib3mf_resourceiterator_getcurrent(it.get(), mesh.out()), it.get(), file_,
            Direction::Read, "listing the mesh objects");
      out.push_back(object(mesh, out.size()));
    }
    return out;
  }

 private:
  ThreeMfObject object(const Handle& mesh, std::size_t i) {
    ThreeMfObject o;
    o.name = name(mesh);
    o.mesh = geometry(mesh, object_label(i, o.name));
    if (const auto rgb = colour(mesh)) o.rgb = *rgb;
    return o;
  }

  std::string name(const Handle& mesh) {
    ULONG needed = 0;
    check(NMR::lib3mf_object_getnameutf8(mesh.get(), nullptr, 0, &needed), mesh.get(), file_,
          Direction::Read, "reading an object's name");
    std::string s(static_cast<std::size_t>(needed) + 1, '\0');
    check(
        NMR::lib3mf_object_getnameutf8(mesh.get(), s.data(), static_cast<ULONG>(s.size()), &needed),
        mesh.get(), file_, Direction::Read, "reading an object's name");
    s.resize(s.find('\0'));
    return s;
  }

  core::TriMesh geometry(const Handle& mesh, const std::string& who) {
    DWORD n_vertices = 0, n_triangles = 0;
    check(NMR::lib3mf_meshobject_getvertexcount(mesh.get(), &n_vertices), mesh.get(), file_,
          Direction::Read, "reading an object's vertices");
    check(NMR::lib3mf_meshobject_gettrianglecount(mesh.get(), &n_triangles), mesh.get(), file_,
          Direction::Read, "reading an object's triangles");
    std::vector<NMR::MODELMESHVERTEX> vertices(n_vertices);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(n_triangles);
    if (n_vertices > 0)
      check(NMR::lib3mf_meshobject_getvertices(mesh.get(), vertices.data(), n_vertices, nullptr),
            mesh.get(), file_, Direction::Read, "reading an object's vertices");
    if (n_triangles > 0)
      check(NMR::lib3mf_meshobject_gettriangleindices(mesh.get(), triangles.data(), n_triangles,
                                                      nullptr),
            mesh.get(), file_, Direction::Read, "reading an object's triangles");
    core::TriMesh m;
    m.points.reserve(n_vertices);
    for (const NMR::MODELMESHVERTEX& v : vertices)
      m.points.emplace_back(v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]);
    m.cells.reserve(n_triangles);
    for (const NMR::MODELMESHTRIANGLE& t : triangles) {
      core::Tri c{};
      for (int k = 0; k < 3; ++k) {
        if (t.m_nIndices[k] >= n_vertices)
          throw InputError(file_, 0,
                           who + ": a triangle refers to vertex " +
                               std::to_string(t.m_nIndices[k]) + " out of range");
        c[k] = static_cast<int>(t.m_nIndices[k]);
      }
      m.cells.push_back(c);
    }
    return m;
  }

  //! The object's display colour: its base material's, or its default colour; none otherwise.
  std::optional<std::array<std::uint8_t, 3>> colour(const Handle& mesh) {
    Handle properties;
    check(NMR::lib3mf_object_createdefaultpropertyhandler(mesh.get(), properties.out()), mesh.get(),
          file_, Direction::Read, "reading an object's properties");
    NMR::eModelPropertyType type = NMR::MODELPROPERTYTYPE_NONE;
    check(NMR::lib3mf_defaultpropertyhandler_getpropertytype(properties.get(), &type),
          properties.get(), file_, Direction::Read, "reading an object's properties");
    if (type == NMR::MODELPROPERTYTYPE_BASEMATERIALS) {
      DWORD group = 0, index = 0;
      check(NMR::lib3mf_defaultpropertyhandler_getbasematerial(properties.get(), &group, &index),
            properties.get(), file_, Direction::Read, "reading an object's material");
      Handle materials;
      check(NMR::lib3mf_model_getbasematerialbyid(model_.get(), group, materials.out()),
            model_.get(), file_, Direction::Read, "reading a material group");
      BYTE r = 0, g = 0, b = 0, a = 0;
      check(NMR::lib3mf_basematerial_getdisplaycolor(materials.get(), index, &r, &g, &b, &a),
            materials.get(), file_, Direction::Read, "reading a material's colour");
      return std::array<std::uint8_t, 3>{r, g, b};
    }
    if (type == NMR::MODELPROPERTYTYPE_COLOR) {
      NMR::MODELMESHCOLOR_SRGB c{};
      check(NMR::lib3mf_defaultpropertyhandler_getcolor(properties.get(), 0, &c), properties.get(),
            file_, Direction::Read, "reading an object's colour");
      return std::array<std::uint8_t, 3>{c.m_Red, c.m_Green, c.m_Blue};
    }
    return std::nullopt;
  }

  std::string file_;
  Handle model_;
};

}  // namespace

void write_3mf(const fs::path& path, const std::vector<ThreeMfObject>& objects) {
  const std::string file = path.string();
  check_objects(objects, file);
  ModelBuilder model(file);
  for (std::size_t i = 0; i < objects.size(); ++i) model.add(i, objects[i]);
  write_text_atomic(path, model.package());
}

std::vector<ThreeMfObject> read_3mf(const fs::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(file, 0, "no such file");
  if (fs::is_directory(st)) throw InputError(file, 0, "is a directory, not a file");
  return ModelReader(file).objects();
}

}  // namespace polycube::io
