// SPDX-License-Identifier: GPL-2.0-or-later
#include "animate/vtk_writer.hpp"

#include <cstdint>
#include <cstring>

#include "kanegen/runtime/text.hpp"

namespace kanegen::animate {
namespace {

/// VTK's inline binary array: a UInt32 byte count, then the values, all in
/// one base64 block (header_type UInt32, byte order of this machine, which
/// the file header states).
template <class T>
std::string encoded(const std::vector<T>& values) {
  const std::uint32_t size = static_cast<std::uint32_t>(values.size() * sizeof(T));
  std::vector<unsigned char> bytes(sizeof size + size);
  std::memcpy(bytes.data(), &size, sizeof size);
  if (size) std::memcpy(bytes.data() + sizeof size, values.data(), size);
  return base64(bytes);
}

template <class T>
std::string data_array(const char* type, const char* name, int components, const std::vector<T>& values) {
  return std::string("        <DataArray type=\"") + type + "\" Name=\"" + name + "\" NumberOfComponents=\"" +
         std::to_string(components) + "\" format=\"binary\">" + encoded(values) + "</DataArray>\n";
}

std::vector<double> flat(const std::vector<std::array<double, 3>>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const auto& x : v) out.insert(out.end(), x.begin(), x.end());
  return out;
}

bool little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* const alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (n > 1 ? std::uint32_t{bytes[i + 1]} << 8 : 0) |
                            (n > 2 ? std::uint32_t{bytes[i + 2]} : 0);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += n > 1 ? alphabet[(v >> 6) & 63] : '=';
    out += n > 2 ? alphabet[v & 63] : '=';
  }
  return out;
}

std::string vtu_text(const Scene& scene) {
  std::vector<std::int32_t> connectivity, offsets, cell_body;
  std::vector<std::uint8_t> types;
  for (const Scene::Cell& c : scene.cells) {
    connectivity.insert(connectivity.end(), c.points.begin(), c.points.end());
    offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
    types.push_back(static_cast<std::uint8_t>(c.type));
    cell_body.push_back(c.body);
  }
  std::string s =
      std::string(
          "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"") +
      (little_endian() ? "LittleEndian" : "BigEndian") + "\" header_type=\"UInt32\">\n";
  s += "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" + std::to_string(scene.points.size()) +
       "\" NumberOfCells=\"" + std::to_string(scene.cells.size()) + "\">\n";
  s += "      <PointData Vectors=\"displacement\">\n";
  s += data_array("Float64", "displacement", 3, flat(scene.displacement));
  s += data_array("Float64", "joint_axis", 3, flat(scene.joint_axis));
  s += data_array("Int32", "body", 1, scene.point_body);
  s += data_array("Int32", "kind", 1, scene.point_kind);
  s += "      </PointData>\n      <CellData Scalars=\"body\">\n";
  s += data_array("Int32", "body", 1, cell_body);
  s += "      </CellData>\n      <Points>\n";
  s += data_array("Float64", "Points", 3, flat(scene.points));
  s += "      </Points>\n      <Cells>\n";
  s += data_array("Int32", "connectivity", 1, connectivity);
  s += data_array("Int32", "offsets", 1, offsets);
  s += data_array("UInt8", "types", 1, types);
  s += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return s;
}

std::string pvd_text(const std::vector<std::pair<double, std::string>>& frames) {
  std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [time, file] : frames)
    s +=
        "    <DataSet timestep=\"" + runtime::format_double(time) + "\" part=\"0\" file=\"" + file + "\"/>\n";
  return s + "  </Collection>\n</VTKFile>\n";
}

}  // namespace kanegen::animate
