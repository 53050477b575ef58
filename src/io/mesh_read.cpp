// Particle mesh readers: dispatch by extension, STL (through stl.cpp) joined into an indexed
// mesh, and Wavefront OBJ. PLY is in mesh_read_ply.cpp.

#include "aggpack/io/mesh_read.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unordered_map>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/io/stl.h"
#include "read_failure.h"

namespace aggpack {

namespace {

std::string lower(std::string_view text) {
  std::string result(text);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}

// Vertices keyed by their exact bits: STL repeats a shared corner in every facet, bit for bit.
struct BitsHash {
  std::size_t operator()(const std::array<std::uint64_t, 3>& key) const {
    std::uint64_t h = 1469598103934665603ULL;
    for (const std::uint64_t word : key) h = (h ^ word) * 1099511628211ULL;
    return static_cast<std::size_t>(h);
  }
};

TriangleMesh join_stl(const StlMesh& stl) {
  TriangleMesh mesh;
  std::unordered_map<std::array<std::uint64_t, 3>, std::uint32_t, BitsHash> index;
  index.reserve(stl.triangles.size());
  mesh.triangles.reserve(stl.triangles.size());
  for (const auto& facet : stl.triangles) {
    Triangle triangle{};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& p = facet[k];
      std::array<std::uint64_t, 3> key{};
      for (int axis = 0; axis < 3; ++axis) {
        const double value = p[axis] == 0.0 ? 0.0 : p[axis];  // -0 and +0 are one point
        std::memcpy(&key[static_cast<std::size_t>(axis)], &value, sizeof value);
      }
      const auto [slot, is_new] =
          index.try_emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (is_new) mesh.vertices.push_back(p);
      triangle[k] = slot->second;
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

// One whitespace-separated word of a line, advancing `cursor`.
std::string_view next_word(std::string_view line, std::size_t& cursor) {
  while (cursor < line.size() && (line[cursor] == ' ' || line[cursor] == '\t')) ++cursor;
  const std::size_t start = cursor;
  while (cursor < line.size() && line[cursor] != ' ' && line[cursor] != '\t') ++cursor;
  return line.substr(start, cursor - start);
}

bool to_double(std::string_view word, double& value) {
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size() && std::isfinite(value);
}

TriangleMesh parse_obj(const std::string& content, const std::string& path) {
  TriangleMesh mesh;
  std::size_t line_number = 0;
  // "PATH:LINE: what", the sentence's first two values.
  auto fault = [&](Sentence sentence, std::vector<std::string> values = {}) {
    values.insert(values.begin(), {path, std::to_string(line_number)});
    return FormatError(Wording{sentence, std::move(values)});
  };
  std::vector<std::int64_t> polygon;
  for (std::size_t start = 0; start < content.size();) {
    std::size_t end = content.find('\n', start);
    if (end == std::string::npos) end = content.size();
    std::string_view line(content.data() + start, end - start);
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::size_t cursor = 0;
    const std::string_view keyword = next_word(line, cursor);
    if (keyword.empty() || keyword.front() == '#') continue;
    if (keyword == "v") {
      Vec3 p;
      for (int axis = 0; axis < 3; ++axis) {
        const std::string_view word = next_word(line, cursor);
        if (!to_double(word, p[axis])) {
          throw fault(Sentence::kObjCoordinate, {shortened(word, 40)});
        }
      }
      mesh.vertices.push_back(p);
    } else if (keyword == "f") {
      polygon.clear();
      for (std::string_view word = next_word(line, cursor); !word.empty();
           word = next_word(line, cursor)) {
        // "v", "v/vt", "v//vn" or "v/vt/vn": the vertex index is the first number; negative
        // indices count back from the last vertex read.
        const std::string_view number = word.substr(0, word.find('/'));
        std::int64_t value = 0;
        const auto [stop, error] =
            std::from_chars(number.data(), number.data() + number.size(), value);
        if (error != std::errc() || stop != number.data() + number.size() || value == 0) {
          throw fault(Sentence::kObjFaceIndex, {shortened(word, 40)});
        }
        const auto count = static_cast<std::int64_t>(mesh.vertices.size());
        const std::int64_t index = value > 0 ? value - 1 : count + value;
        if (index < 0 || index >= count) {
          throw fault(Sentence::kObjFaceNoVertex, {std::to_string(value), std::to_string(count)});
        }
        polygon.push_back(index);
      }
      if (polygon.size() < 3) throw fault(Sentence::kObjFaceSmall);
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        mesh.triangles.push_back({static_cast<std::uint32_t>(polygon[0]),
                                  static_cast<std::uint32_t>(polygon[k]),
                                  static_cast<std::uint32_t>(polygon[k + 1])});
      }
    } else if (keyword == "vn" || keyword == "vt" || keyword == "vp" || keyword == "g" ||
               keyword == "o" || keyword == "s" || keyword == "usemtl" || keyword == "mtllib") {
      continue;  // normals, texture, groups and materials do not change the shape
    } else {
      throw fault(Sentence::kObjStatement, {shortened(keyword, 40)});
    }
  }
  if (mesh.triangles.empty()) throw FormatError(Wording{Sentence::kObjNoFaces, {path}});
  return mesh;
}

}  // namespace

bool mesh_file_format(std::string_view path, MeshFileFormat& format) {
  const std::string extension = lower(std::filesystem::path(path).extension().string());
  if (extension == ".stl") {
    format = MeshFileFormat::kStl;
  } else if (extension == ".obj") {
    format = MeshFileFormat::kObj;
  } else if (extension == ".ply") {
    format = MeshFileFormat::kPly;
  } else {
    return false;
  }
  return true;
}

std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error) throw IoError(io_detail::read_failure_wording(path, error.value()));
  if (!std::filesystem::is_regular_file(status)) {
    throw IoError(Wording{Sentence::kReadNotRegular, {path}});
  }
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) throw IoError(Wording{Sentence::kReadSystemError, {path, error.message()}});
  if (size > max_bytes) {
    throw LimitExceeded(Wording{Sentence::kFileSize, {path}},
                        Wording{Sentence::kBytes, {std::to_string(size)}},
                        Wording{Sentence::kAtMostBytes, {std::to_string(max_bytes)}});
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(io_detail::read_failure_wording(path, errno));
  std::string content(size, '\0');
  in.read(content.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uint64_t>(in.gcount()) != size) {
    throw IoError(Wording{Sentence::kReadChanged, {path}});
  }
  return content;
}

TriangleMesh parse_mesh(const std::string& content, MeshFileFormat format,
                        const std::string& path) {
  switch (format) {
    case MeshFileFormat::kStl:
      return join_stl(parse_stl(content, path));
    case MeshFileFormat::kObj:
      return parse_obj(content, path);
    case MeshFileFormat::kPly:
      return io_detail::parse_ply(content, path);
  }
  throw FormatError(Wording{Sentence::kUnknownMeshFormat, {path}});
}

std::string content_hash(std::string_view content) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const char c : content) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  char text[32];
  std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace aggpack
