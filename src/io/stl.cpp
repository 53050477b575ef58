#include "aggpack/io/stl.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

void put_float(std::ostream& out, double value) {
  const auto f = static_cast<float>(value);
  char bytes[4];
  std::memcpy(bytes, &f, 4);  // STL is little-endian; so is every platform we build on
  out.write(bytes, 4);
}

}  // namespace

void write_stl(const std::string& path, const std::vector<ConvexPolyhedron>& bodies,
               const StlOptions& options) {
  require_positive("stl scale", options.scale);
  // A line break in the name would end the ASCII "solid" line early.
  if (options.solid_name.find_first_of("\r\n") != std::string::npos) {
    throw InvalidInput("stl solid_name", "a name with a line break", "one line of text");
  }
  std::size_t triangle_count = 0;
  for (const auto& body : bodies) triangle_count += body.triangle_count();
  if (options.encoding == StlEncoding::kBinary && triangle_count > 0xFFFFFFFFULL) {
    throw InvalidInput("stl triangles", std::to_string(triangle_count), "<= 2^32-1 for binary STL");
  }
  AtomicFile file(path, options.overwrite);
  auto& out = file.stream();
  const double scale = options.scale;
  if (options.encoding == StlEncoding::kBinary) {
    char header[80] = {};
    std::snprintf(header, sizeof header, "binary STL from aggpack %s, %s", AGGPACK_VERSION,
                  options.solid_name.c_str());
    out.write(header, 80);
    const auto count = static_cast<std::uint32_t>(triangle_count);
    out.write(reinterpret_cast<const char*>(&count), 4);
    const char attribute[2] = {0, 0};
    for (const auto& body : bodies) {
      const auto& vertices = body.vertices();
      for (std::size_t f = 0; f < body.triangle_count(); ++f) {
        const Vec3 normal = body.face_normal(f);
        for (int axis = 0; axis < 3; ++axis) put_float(out, normal[axis]);
        for (auto index : body.triangles()[f]) {
          for (int axis = 0; axis < 3; ++axis) put_float(out, vertices[index][axis] * scale);
        }
        out.write(attribute, 2);
      }
    }
  } else {
    char line[256];
    out << "solid " << options.solid_name << '\n';
    for (const auto& body : bodies) {
      const auto& vertices = body.vertices();
      for (std::size_t f = 0; f < body.triangle_count(); ++f) {
        const Vec3 n = body.face_normal(f);
        std::snprintf(line, sizeof line, "  facet normal %.9e %.9e %.9e\n    outer loop\n", n.x(),
                      n.y(), n.z());
        out << line;
        for (auto index : body.triangles()[f]) {
          const Vec3 v = vertices[index] * scale;
          std::snprintf(line, sizeof line, "      vertex %.9e %.9e %.9e\n", v.x(), v.y(), v.z());
          out << line;
        }
        out << "    endloop\n  endfacet\n";
      }
    }
    out << "endsolid " << options.solid_name << '\n';
  }
  file.commit();
}

StlMesh read_stl(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError("cannot read " + path + ": it is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  StlMesh mesh;
  // Binary when the size matches the facet count; ASCII files start with "solid" and do not.
  if (content.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, content.data() + 80, 4);
    if (content.size() == 84 + 50ULL * count) {
      const char* cursor = content.data() + 84;
      auto get = [&cursor]() {
        float f = 0;
        std::memcpy(&f, cursor, 4);
        cursor += 4;
        return static_cast<double>(f);
      };
      for (std::uint32_t i = 0; i < count; ++i) {
        Vec3 normal;
        for (int axis = 0; axis < 3; ++axis) normal[axis] = get();
        std::array<Vec3, 3> triangle;
        for (auto& v : triangle) {
          for (int axis = 0; axis < 3; ++axis) v[axis] = get();
        }
        cursor += 2;
        mesh.normals.push_back(normal);
        mesh.triangles.push_back(triangle);
      }
      return mesh;
    }
  }
  if (content.rfind("solid", 0) != 0) {
    throw FormatError(path + ": not an STL file (binary size mismatch and no 'solid' header)");
  }
  std::istringstream text(content);
  std::string word;
  text >> word;  // solid
  std::getline(text, word);
  bool has_end = false;
  while (text >> word) {
    if (word == "endsolid") {
      has_end = true;
      break;
    }
    if (word != "facet") throw FormatError(path + ": expected 'facet', found '" + word + "'");
    Vec3 normal;
    std::string keyword;
    text >> keyword >> normal.x() >> normal.y() >> normal.z();
    if (!text || keyword != "normal") throw FormatError(path + ": malformed facet normal line");
    text >> keyword >> word;
    if (!text || keyword != "outer" || word != "loop") {
      throw FormatError(path + ": expected 'outer loop'");
    }
    std::array<Vec3, 3> triangle;
    for (auto& v : triangle) {
      text >> keyword >> v.x() >> v.y() >> v.z();
      if (!text || keyword != "vertex") throw FormatError(path + ": malformed vertex line");
    }
    text >> keyword >> word;  // endloop endfacet
    if (!text || keyword != "endloop" || word != "endfacet") {
      throw FormatError(path + ": malformed facet (truncated?)");
    }
    mesh.normals.push_back(normal);
    mesh.triangles.push_back(triangle);
  }
  if (!has_end) throw FormatError(path + ": missing 'endsolid' (truncated file)");
  return mesh;
}

}  // namespace aggpack
