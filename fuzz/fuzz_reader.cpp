//! libFuzzer target for one mesh reader (the format is chosen at compile time by
//! POLYCUBE_FUZZ_FORMAT, e.g. Obj). Any exception other than core::InputError, any sanitizer
//! report, and any input that reads but does not survive write + read again is a failure.
#include "core/errors.h"
#include "io/mesh_io.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {
constexpr polycube::io::Format kFormat = polycube::io::Format::POLYCUBE_FUZZ_FORMAT;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace polycube;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  core::MeshData d;
  try {
    d = io::read_mesh_from_memory(bytes, kFormat, "fuzz");
  } catch (const core::InputError&) {
    return 0;  // bad input, reported properly
  }
  // What was read must write and read back with the same elements (a writer may refuse what
  // its format cannot hold, with an InputError: that is a proper report too).
  std::string again;
  try {
    again = io::write_mesh_to_string(d, kFormat, {}, "fuzz-write");
  } catch (const core::InputError&) {
    return 0;
  }
  const core::MeshData e = io::read_mesh_from_memory(again, kFormat, "fuzz-again");
  if (e.num_cells() != d.num_cells() || e.points.size() > d.points.size()) __builtin_trap();
  return 0;
}
