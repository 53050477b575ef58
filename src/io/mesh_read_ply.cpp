// PLY reader (ASCII, binary_little_endian, binary_big_endian): the vertex element's x, y, z and
// the face element's vertex_indices (or vertex_index) list; every other element and property is
// skipped by its declared type. Counts are checked against the bytes left before allocating.

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/io/mesh_read.h"

namespace aggpack::io_detail {

namespace {

enum class Encoding { kAscii, kLittle, kBig };

struct Property {
  std::string name;
  int size = 0;           // bytes of the value (or of each list item)
  bool is_float = false;  // float / double
  bool is_signed = false;
  bool is_list = false;
  int count_size = 0;  // list: bytes of the count
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

// Size and kind of a PLY scalar type name; 0 if unknown.
int type_size(const std::string& type, bool& is_float, bool& is_signed) {
  is_float = type == "float" || type == "float32" || type == "double" || type == "float64";
  is_signed = is_float || type == "char" || type == "int8" || type == "short" || type == "int16" ||
              type == "int" || type == "int32";
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

class Reader {
 public:
  Reader(const std::string& content, const std::string& path, Encoding encoding, std::size_t start)
      : content_(content), path_(path), encoding_(encoding), cursor_(start) {}

  [[nodiscard]] std::size_t left() const { return content_.size() - cursor_; }

  // One value of a property (its count for a list's count) as a double.
  double value(int size, bool is_float, bool is_signed) {
    if (encoding_ == Encoding::kAscii) return ascii_value();
    if (left() < static_cast<std::size_t>(size)) throw truncated();
    unsigned char bytes[8];
    std::memcpy(bytes, content_.data() + cursor_, static_cast<std::size_t>(size));
    cursor_ += static_cast<std::size_t>(size);
    const bool is_swapped =
        (encoding_ == Encoding::kBig) == (std::endian::native == std::endian::little);
    if (is_swapped) std::reverse(bytes, bytes + size);
    if (is_float) {
      if (size == 4) {
        float f = 0;
        std::memcpy(&f, bytes, 4);
        return f;
      }
      double d = 0;
      std::memcpy(&d, bytes, 8);
      return d;
    }
    std::uint64_t raw = 0;
    for (int k = size - 1; k >= 0; --k) raw = (raw << 8) | bytes[k];
    if (is_signed && size < 8 && (raw >> (8 * size - 1)) != 0) {
      return static_cast<double>(static_cast<std::int64_t>(raw) - (std::int64_t{1} << (8 * size)));
    }
    return static_cast<double>(raw);
  }

  FormatError truncated() const { return FormatError(Wording{Sentence::kPlyTruncated, {path_}}); }

 private:
  double ascii_value() {
    while (cursor_ < content_.size() && std::isspace(static_cast<unsigned char>(content_[cursor_])))
      ++cursor_;
    const std::size_t start = cursor_;
    while (cursor_ < content_.size() &&
           !std::isspace(static_cast<unsigned char>(content_[cursor_])))
      ++cursor_;
    if (start == cursor_) throw truncated();
    double value = 0;
    const auto [end, error] =
        std::from_chars(content_.data() + start, content_.data() + cursor_, value);
    if (error != std::errc() || end != content_.data() + cursor_) {
      throw FormatError(Wording{
          Sentence::kPlyValue,
          {path_, shortened(std::string_view(content_.data() + start, cursor_ - start), 40)}});
    }
    return value;
  }

  const std::string& content_;
  const std::string& path_;
  Encoding encoding_;
  std::size_t cursor_;
};

}  // namespace

TriangleMesh parse_ply(const std::string& content, const std::string& path) {
  const auto header_end = content.find("end_header");
  if (content.rfind("ply", 0) != 0 || header_end == std::string::npos) {
    throw FormatError(Wording{Sentence::kPlyNotPly, {path}});
  }
  std::size_t data_start = content.find('\n', header_end);
  data_start = data_start == std::string::npos ? content.size() : data_start + 1;
  // Header lines.
  Encoding encoding = Encoding::kAscii;
  bool has_format = false;
  std::vector<Element> elements;
  std::size_t line_number = 0;
  for (std::size_t start = 0; start < header_end;) {
    std::size_t end = content.find('\n', start);
    if (end == std::string::npos || end > header_end) end = header_end;
    std::string line = content.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> words;
    for (std::size_t k = 0; k < line.size();) {
      while (k < line.size() && std::isspace(static_cast<unsigned char>(line[k]))) ++k;
      const std::size_t w = k;
      while (k < line.size() && !std::isspace(static_cast<unsigned char>(line[k]))) ++k;
      if (k > w) words.push_back(line.substr(w, k - w));
    }
    // "PATH: PLY header line N: what", the sentence's first two values.
    auto fault = [&](Sentence sentence, std::vector<std::string> values = {}) {
      values.insert(values.begin(), {path, std::to_string(line_number)});
      return FormatError(Wording{sentence, std::move(values)});
    };
    if (words.empty() || words[0] == "ply" || words[0] == "comment" || words[0] == "obj_info")
      continue;
    if (words[0] == "format") {
      if (words.size() < 2) throw fault(Sentence::kPlyFormatWithoutName);
      if (words[1] == "ascii") {
        encoding = Encoding::kAscii;
      } else if (words[1] == "binary_little_endian") {
        encoding = Encoding::kLittle;
      } else if (words[1] == "binary_big_endian") {
        encoding = Encoding::kBig;
      } else {
        throw fault(Sentence::kPlyUnknownFormat, {shortened(words[1], 40)});
      }
      has_format = true;
    } else if (words[0] == "element") {
      std::uint64_t count = 0;
      if (words.size() != 3 ||
          std::from_chars(words[2].data(), words[2].data() + words[2].size(), count).ec !=
              std::errc()) {
        throw fault(Sentence::kPlyElementLine);
      }
      elements.push_back({.name = words[1], .count = count, .properties = {}});
    } else if (words[0] == "property") {
      if (elements.empty()) throw fault(Sentence::kPlyPropertyFirst);
      Property property;
      bool is_float = false;
      bool is_signed = false;
      if (words.size() == 5 && words[1] == "list") {
        bool count_float = false;
        bool count_signed = false;
        property.is_list = true;
        property.count_size = type_size(words[2], count_float, count_signed);
        property.size = type_size(words[3], is_float, is_signed);
        if (property.count_size == 0 || count_float || property.size == 0) {
          throw fault(Sentence::kPlyListTypes, {shortened(words[2] + " " + words[3], 40)});
        }
        property.name = words[4];
      } else if (words.size() == 3) {
        property.size = type_size(words[1], is_float, is_signed);
        if (property.size == 0) throw fault(Sentence::kPlyUnknownType, {shortened(words[1], 40)});
        property.name = words[2];
      } else {
        throw fault(Sentence::kPlyPropertyLine);
      }
      property.is_float = is_float;
      property.is_signed = is_signed;
      elements.back().properties.push_back(property);
    } else {
      throw fault(Sentence::kPlyUnknownKeyword, {shortened(words[0], 40)});
    }
  }
  if (!has_format) throw FormatError(Wording{Sentence::kPlyNoFormat, {path}});

  // Every count is bounded by the bytes left: an ASCII value takes at least 2 bytes, a binary
  // one its size; nothing is reserved beyond that.
  TriangleMesh mesh;
  Reader reader(content, path, encoding, data_start);
  bool has_vertices = false;
  bool has_faces = false;
  for (const Element& element : elements) {
    std::uint64_t min_record = 0;
    for (const Property& p : element.properties) {
      min_record += encoding == Encoding::kAscii
                        ? 2
                        : static_cast<std::uint64_t>(p.is_list ? p.count_size : p.size);
    }
    if (element.count > 0 && min_record > 0 && element.count > reader.left() / min_record) {
      throw FormatError(
          Wording{Sentence::kPlyElementCount,
                  {path, shortened(element.name, 40), std::to_string(element.count)}});
    }
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    std::array<int, 3> axis_of{-1, -1, -1};
    int index_list = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const std::string& name = element.properties[k].name;
      if (is_vertex && !element.properties[k].is_list && name.size() == 1 && name[0] >= 'x' &&
          name[0] <= 'z') {
        axis_of[static_cast<std::size_t>(name[0] - 'x')] = static_cast<int>(k);
      }
      if (is_face && element.properties[k].is_list &&
          (name == "vertex_indices" || name == "vertex_index")) {
        index_list = static_cast<int>(k);
      }
    }
    if (is_vertex) {
      if (axis_of[0] < 0 || axis_of[1] < 0 || axis_of[2] < 0) {
        throw FormatError(Wording{Sentence::kPlyVertexAxes, {path}});
      }
      has_vertices = true;
      mesh.vertices.reserve(element.count);
    }
    if (is_face) {
      if (index_list < 0) {
        throw FormatError(Wording{Sentence::kPlyFaceList, {path}});
      }
      has_faces = true;
      mesh.triangles.reserve(element.count);
    }
    // An element without properties holds no bytes: its entries (any count) are nothing to read.
    if (element.properties.empty()) continue;
    std::vector<std::int64_t> polygon;
    for (std::uint64_t entry = 0; entry < element.count; ++entry) {
      Vec3 point = Vec3::Zero();
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const Property& p = element.properties[k];
        if (!p.is_list) {
          const double value = reader.value(p.size, p.is_float, p.is_signed);
          for (int axis = 0; axis < 3; ++axis) {
            if (axis_of[static_cast<std::size_t>(axis)] == static_cast<int>(k)) point[axis] = value;
          }
          continue;
        }
        const double count = reader.value(p.count_size, false, false);
        if (!(count >= 0) || count != std::floor(count) ||
            count > static_cast<double>(reader.left())) {
          throw FormatError(Wording{
              Sentence::kPlyListCount,
              {path, format_value(count), shortened(element.name, 40), std::to_string(entry)}});
        }
        const bool is_indices = static_cast<int>(k) == index_list;
        if (is_indices) polygon.clear();
        for (std::uint64_t item = 0; item < static_cast<std::uint64_t>(count); ++item) {
          const double value = reader.value(p.size, p.is_float, p.is_signed);
          if (is_indices) {
            if (!(value >= 0) || value != std::floor(value) || value > 4294967295.0) {
              throw FormatError(Wording{Sentence::kPlyFaceIndex,
                                        {path, std::to_string(entry), format_value(value)}});
            }
            polygon.push_back(static_cast<std::int64_t>(value));
          }
        }
        if (is_indices) {
          if (polygon.size() < 3) {
            throw FormatError(Wording{Sentence::kPlyFaceSmall, {path, std::to_string(entry)}});
          }
          for (std::size_t v = 1; v + 1 < polygon.size(); ++v) {
            mesh.triangles.push_back({static_cast<std::uint32_t>(polygon[0]),
                                      static_cast<std::uint32_t>(polygon[v]),
                                      static_cast<std::uint32_t>(polygon[v + 1])});
          }
        }
      }
      if (is_vertex) {
        if (!point.allFinite()) {
          throw FormatError(Wording{Sentence::kPlyVertexFinite, {path, std::to_string(entry)}});
        }
        mesh.vertices.push_back(point);
      }
    }
  }
  if (!has_vertices || !has_faces) {
    throw FormatError(Wording{Sentence::kPlyNeedsElements, {path}});
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (const std::uint32_t v : mesh.triangles[f]) {
      if (v >= mesh.vertices.size()) {
        throw FormatError(Wording{Sentence::kPlyFaceVertex,
                                  {path, std::to_string(v), std::to_string(mesh.vertices.size())}});
      }
    }
  }
  return mesh;
}

}  // namespace aggpack::io_detail
