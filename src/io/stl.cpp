// STL reader: binary or ASCII (the writer is src/io/export_stl.cpp).

#include "aggpack/io/stl.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "aggpack/core/error.h"

namespace aggpack {

StlMesh read_stl(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError(Wording{Sentence::kReadFolder, {path}});
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(Wording{Sentence::kOpenFailed, {path}});
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_stl(content, path);
}

StlMesh parse_stl(const std::string& content, const std::string& path) {
  StlMesh mesh;
  // Binary when the size matches the facet count; ASCII files start with "solid" and do not.
  if (content.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, content.data() + 80, 4);
    if (content.size() == 84 + 50ULL * count) {
      const char* cursor = content.data() + 84;
      mesh.normals.reserve(count);  // the size check above bounds the count by the file
      mesh.triangles.reserve(count);
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
    throw FormatError(Wording{Sentence::kStlNotStl, {path}});
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
    if (word != "facet") throw FormatError(Wording{Sentence::kStlExpectedFacet, {path, word}});
    Vec3 normal;
    std::string keyword;
    text >> keyword >> normal.x() >> normal.y() >> normal.z();
    if (!text || keyword != "normal") throw FormatError(Wording{Sentence::kStlFacetNormal, {path}});
    text >> keyword >> word;
    if (!text || keyword != "outer" || word != "loop") {
      throw FormatError(Wording{Sentence::kStlOuterLoop, {path}});
    }
    std::array<Vec3, 3> triangle;
    for (auto& v : triangle) {
      text >> keyword >> v.x() >> v.y() >> v.z();
      if (!text || keyword != "vertex") {
        throw FormatError(Wording{Sentence::kStlVertexLine, {path}});
      }
    }
    text >> keyword >> word;  // endloop endfacet
    if (!text || keyword != "endloop" || word != "endfacet") {
      throw FormatError(Wording{Sentence::kStlFacetTruncated, {path}});
    }
    mesh.normals.push_back(normal);
    mesh.triangles.push_back(triangle);
  }
  if (!has_end) throw FormatError(Wording{Sentence::kStlNoEnd, {path}});
  return mesh;
}

}  // namespace aggpack
