// Reading the native packing file (HDF5): types and sizes checked before anything is allocated,
// then validate_packing (native_validate.cpp). Writing is in native.cpp.
#include "aggpack/io/native.h"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/isolated.h"
#include "aggpack/core/text.h"
#include "hdf5_util.h"
#include "native_container.h"
#include "native_types.h"
#include "read_failure.h"

namespace aggpack {

namespace {

using hdf5::Handle;
using hdf5::hdf5_reason;
using hdf5::SilenceHdf5Errors;
using native_detail::describe_type;
using native_detail::stored_as;
using native_detail::StoredType;

// ---- reading ----------------------------------------------------------------------------------

// Element type a dataset must have exactly (class, size in bytes, signedness for integers).
struct ElementType {
  H5T_class_t type_class;
  std::size_t size;
  H5T_sign_t sign;  // H5T_SGN_ERROR for floats
  const char* name;
};
// Seconds a variable-length string may take to read (a few bytes: microseconds when sound).
constexpr double kStringReadSeconds = 5.0;

constexpr ElementType kFloat64{H5T_FLOAT, 8, H5T_SGN_ERROR, "float64"};
constexpr ElementType kUint32{H5T_INTEGER, 4, H5T_SGN_NONE, "uint32"};
constexpr ElementType kUint64{H5T_INTEGER, 8, H5T_SGN_NONE, "uint64"};

// Echoed text is cut (with an ellipsis) and its control characters escaped, so that a message
// stays one short line whatever the file holds.
std::string echo(const std::string& text) {
  constexpr std::size_t kMax = 60;
  return text.size() <= kMax ? aggpack::quoted(text)
                             : aggpack::quoted(text.substr(0, kMax)) + "...";
}

class Reader {
 public:
  Reader(std::string path, std::uint64_t file_size)
      : path_(std::move(path)), file_size_(file_size) {}

  // "<file>: <what>" for the file as a whole; "<file>: <field>: <reason>" for one object.
  // (Each a sentence of core/error_words.h, so a front end words it in its own language.)
  [[noreturn]] void fail(Sentence sentence, std::vector<std::string> values) const {
    values.insert(values.begin(), path_);
    throw FormatError(Wording{sentence, std::move(values)});
  }
  [[noreturn]] void fail(const std::string& field, const Wording& reason,
                         const std::vector<WordedValue>& words = {}) const {
    native_detail::fail_field(path_, {Sentence::kText, {field}}, reason, words);
  }
  [[noreturn]] void fail_stored(const std::string& field, const StoredType& stored) const {
    fail(field, stored.reason, stored.words);
  }
  [[noreturn]] void fail_hdf5(const std::string& field, Sentence what) const {
    const Wording words{what, {}};
    FormatError error(
        Wording{Sentence::kFieldCorrupt, {path_, field, english(words), hdf5_reason()}});
    error.word_value(english(words), words);
    throw error;
  }

  // H5Lexists / H5Aexists: < 0 means the lookup itself failed (corrupt metadata), 0 absent.
  bool exists(htri_t status, const std::string& field) const {
    if (status < 0) fail_hdf5(field, Sentence::kHdf5LookUp);
    return status > 0;
  }

  Handle open_group(hid_t parent, const char* name) const {
    const std::string field = std::string("/") + name;
    if (!exists(H5Lexists(parent, name, H5P_DEFAULT), field)) {
      fail(field, {Sentence::kNativeMissingGroup, {}});
    }
    const hid_t id = H5Gopen2(parent, name, H5P_DEFAULT);
    if (id < 0) fail_hdf5(field, Sentence::kHdf5OpenGroup);
    return {id, H5Gclose};
  }

  // `object_path` is "" for the root group, else e.g. "/container".
  Handle open_attribute(hid_t object, const std::string& field, const char* name) const {
    if (!exists(H5Aexists(object, name), field)) {
      fail(field, {Sentence::kNativeMissingAttribute, {}});
    }
    const hid_t id = H5Aopen(object, name, H5P_DEFAULT);
    if (id < 0) fail_hdf5(field, Sentence::kHdf5OpenAttribute);
    return {id, H5Aclose};
  }

  std::string read_attribute_string(hid_t object, const std::string& object_path,
                                    const char* name) const {
    const std::string field = object_path + "/" + name;
    Handle attribute = open_attribute(object, field, name);
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    if (!type.is_valid() || H5Tget_class(type.get()) != H5T_STRING) {
      const Wording stored =
          type.is_valid() ? describe_type(type.get()) : Wording{Sentence::kNativeTypeUnknown, {}};
      fail_stored(field, stored_as(Sentence::kNativeStoredAsNotString, stored, english(stored)));
    }
    Handle space(H5Aget_space(attribute.get()), H5Sclose);
    if (!space.is_valid() || H5Sget_simple_extent_type(space.get()) != H5S_SCALAR) {
      fail(field, {Sentence::kNativeNotScalarString, {}});
    }
    if (H5Tis_variable_str(type.get()) > 0) {
      // Written e.g. by h5py (its default str type: variable-length UTF-8); accepted although
      // aggpack writes fixed-length strings. HDF5 does not convert between character sets, so
      // the memory type takes the stored one.
      Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory_type.get(), H5T_VARIABLE);
      H5Tset_cset(memory_type.get(), H5Tget_cset(type.get()));
      // Its characters live in a global heap, which Debian's HDF5 1.10 reads without bounds
      // checks: a corrupted heap makes H5Aread spin forever or copy terabytes (fuzzing found
      // both, tests/fuzz/crashes). So the read runs in a forked child (the parent's HDF5 state is
      // copied; the read-only file is read with pread), and a crash or hang there is this file's
      // error, not aggpack's.
      const hid_t attribute_id = attribute.get();
      const hid_t memory_type_id = memory_type.get();
      const auto outcome = run_isolated(1,
                                        [&](std::size_t) {
                                          char* text = nullptr;
                                          if (H5Aread(attribute_id, memory_type_id, &text) < 0) {
                                            throw std::runtime_error("cannot read the attribute");
                                          }
                                          std::string value = text == nullptr ? "" : text;
                                          H5free_memory(text);
                                          return value;
                                        },
                                        {.workers = 1, .time_limit = kStringReadSeconds});
      if (!outcome[0].is_done) {
        fail(field, {Sentence::kNativeVariableString, {outcome[0].failure}},
             {{outcome[0].failure, outcome[0].failure_wording}});
      }
      return outcome[0].bytes;
    }
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > file_size_) {
      fail(field,
           {Sentence::kNativeStringBytes, {std::to_string(size), std::to_string(file_size_)}});
    }
    std::vector<char> buffer(size + 1, '\0');
    if (H5Aread(attribute.get(), type.get(), buffer.data()) < 0) {
      fail_hdf5(field, Sentence::kHdf5ReadAttribute);
    }
    const std::size_t length = ::strnlen(buffer.data(), size);
    // A fixed-length string ends at its first NUL; anything but padding after it would be
    // silently dropped ("aggpack-packing\0x" read as "aggpack-packing"), so it is refused.
    if (std::any_of(buffer.begin() + static_cast<std::ptrdiff_t>(length), buffer.end(),
                    [](char c) { return c != '\0'; })) {
      fail(field, {Sentence::kNativeNulByte, {std::to_string(length)}});
    }
    return {buffer.data(), length};
  }

  // Opens a single-number attribute and returns it with its stored type.
  std::pair<Handle, Handle> open_number(hid_t object, const std::string& field,
                                        const char* name) const {
    Handle attribute = open_attribute(object, field, name);
    Handle space(H5Aget_space(attribute.get()), H5Sclose);
    if (!space.is_valid() || H5Sget_simple_extent_npoints(space.get()) != 1) {
      fail(field, {Sentence::kNativeNotSingleNumber, {}});
    }
    Handle type(H5Aget_type(attribute.get()), H5Tclose);
    if (!type.is_valid()) fail_hdf5(field, Sentence::kHdf5AttributeType);
    return {std::move(attribute), std::move(type)};
  }

  // A float attribute (float32 or float64), finite.
  double read_attribute_float(hid_t object, const std::string& object_path,
                              const char* name) const {
    const std::string field = object_path + "/" + name;
    const auto [attribute, type] = open_number(object, field, name);
    if (H5Tget_class(type.get()) != H5T_FLOAT || H5Tget_size(type.get()) > 8) {
      const Wording stored = describe_type(type.get());
      fail_stored(field,
                  stored_as(Sentence::kNativeStoredAs, stored, english(stored), {"float64"}));
    }
    double value = 0.0;
    if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
      fail_hdf5(field, Sentence::kHdf5ReadAttribute);
    }
    if (!std::isfinite(value)) {
      fail(field + " = " + format_value(value), {Sentence::kNativeNotFinite, {}});
    }
    return value;
  }

  // An integer attribute of at most 64 bits; a signed one must not be negative (HDF5's own
  // conversion would silently clamp it).
  std::uint64_t read_attribute_unsigned(hid_t object, const std::string& object_path,
                                        const char* name) const {
    const std::string field = object_path + "/" + name;
    const auto [attribute, type] = open_number(object, field, name);
    if (H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_size(type.get()) > 8) {
      const Wording type_words = describe_type(type.get());
      std::string stored = english(type_words);
      if (H5Tget_class(type.get()) == H5T_FLOAT) {
        double value = 0.0;
        if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) >= 0) {
          stored += " (" + format_value(value) + ")";
        }
      }
      fail_stored(field, stored_as(Sentence::kNativeStoredAsNotInteger, type_words, stored));
    }
    if (H5Tget_sign(type.get()) == H5T_SGN_NONE) {
      std::uint64_t value = 0;
      if (H5Aread(attribute.get(), H5T_NATIVE_UINT64, &value) < 0) {
        fail_hdf5(field, Sentence::kHdf5ReadAttribute);
      }
      return value;
    }
    std::int64_t value = 0;
    if (H5Aread(attribute.get(), H5T_NATIVE_INT64, &value) < 0) {
      fail_hdf5(field, Sentence::kHdf5ReadAttribute);
    }
    if (value < 0) {
      fail(field + " = " + std::to_string(value), {Sentence::kNativeNegative, {}});
    }
    return static_cast<std::uint64_t>(value);
  }

  // Reads a dataset of `columns` columns (0 = 1-D) and element type exactly `element` into `out`.
  // Before allocating, the declared size is checked against the bytes the file really stores
  // for it (every aggpack dataset is written in full), so a forged dimension cannot make us
  // allocate more than the file could hold.
  template <typename T>
  void read_dataset(hid_t parent, const char* group_name, const char* name, hid_t memory_type,
                    const ElementType& element, std::size_t columns, std::vector<T>& out,
                    std::size_t& rows) const {
    static_assert(sizeof(T) <= 8);
    const std::string field = std::string("/") + group_name + "/" + name;
    if (!exists(H5Lexists(parent, name, H5P_DEFAULT), field)) {
      fail(field, {Sentence::kNativeMissingDataset, {}});
    }
    Handle dataset(H5Dopen2(parent, name, H5P_DEFAULT), H5Dclose);
    if (!dataset.is_valid()) fail_hdf5(field, Sentence::kHdf5OpenDataset);
    Handle type(H5Dget_type(dataset.get()), H5Tclose);
    if (!type.is_valid()) fail_hdf5(field, Sentence::kHdf5DatasetType);
    if (H5Tget_class(type.get()) != element.type_class || H5Tget_size(type.get()) != element.size ||
        (element.type_class == H5T_INTEGER && H5Tget_sign(type.get()) != element.sign)) {
      const Wording stored = describe_type(type.get());
      fail_stored(field,
                  stored_as(Sentence::kNativeStoredAs, stored, english(stored), {element.name}));
    }
    Handle space(H5Dget_space(dataset.get()), H5Sclose);
    const int rank = space.is_valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    const int expected_rank = columns == 0 ? 1 : 2;
    if (rank != expected_rank) {
      fail(field, {Sentence::kNativeRank, {std::to_string(rank), std::to_string(expected_rank)}});
    }
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0) {
      fail_hdf5(field, Sentence::kHdf5DatasetSize);
    }
    if (columns != 0 && dims[1] != columns) {
      fail(field, {Sentence::kNativeColumns, {std::to_string(dims[1]), std::to_string(columns)}});
    }
    const std::string shape_text =
        std::to_string(dims[0]) + (columns == 0 ? "" : " x " + std::to_string(columns));
    // dims[0] <= file size (a row has at least one byte) keeps the products below from
    // overflowing; compression cannot beat kMaxCompressionRatio either.
    const auto ratio = static_cast<std::uint64_t>(NativeLimits::kMaxCompressionRatio);
    if (dims[0] > ratio * file_size_) {
      fail(field, {Sentence::kNativeDeclaresValues,
                   {shape_text, element.name, std::to_string(file_size_)}});
    }
    const hsize_t elements = dims[0] * std::max<hsize_t>(columns, 1);
    const hsize_t declared_bytes = elements * element.size;
    if (elements > 0) {
      const hsize_t stored_bytes = H5Dget_storage_size(dataset.get());
      const bool is_compressed = has_compression(dataset.get(), field);
      const hsize_t allowed =
          is_compressed ? ratio * stored_bytes : stored_bytes;  // stored <= file size, below
      if (stored_bytes > file_size_ || declared_bytes > allowed) {
        fail(field, {is_compressed ? Sentence::kNativeDeclaresStoredCompressed
                                   : Sentence::kNativeDeclaresStored,
                     {shape_text, element.name, std::to_string(declared_bytes),
                      std::to_string(stored_bytes), std::to_string(file_size_)}});
      }
    }
    rows = dims[0];
    try {
      out.assign(elements, T{});
    } catch (const std::bad_alloc&) {
      fail(field, {Sentence::kNativeTooLarge, {shape_text}});
    }
    if (elements > 0 &&
        H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
      fail_hdf5(field, Sentence::kHdf5ReadDataset);
    }
  }

 private:
  // Rejects data stored in other files; true if a filter other than the Fletcher-32 checksum and
  // the byte shuffle (which do not change the amount of data) is applied, i.e. the stored bytes may
  // be compressed.
  bool has_compression(hid_t dataset, const std::string& field) const {
    Handle properties(H5Dget_create_plist(dataset), H5Pclose);
    if (!properties.is_valid()) fail_hdf5(field, Sentence::kHdf5DatasetProperties);
    // Data in other files (external raw files, virtual datasets) is not part of a packing file.
    if (H5Pget_layout(properties.get()) == H5D_VIRTUAL ||
        H5Pget_external_count(properties.get()) != 0) {
      fail(field, {Sentence::kNativeStoredOutside, {}});
    }
    const int filters = H5Pget_nfilters(properties.get());
    for (int k = 0; k < filters; ++k) {
      unsigned flags = 0;
      std::size_t value_count = 0;
      unsigned filter_config = 0;
      const H5Z_filter_t filter = H5Pget_filter2(properties.get(), static_cast<unsigned>(k), &flags,
                                                 &value_count, nullptr, 0, nullptr, &filter_config);
      if (filter != H5Z_FILTER_FLETCHER32 && filter != H5Z_FILTER_SHUFFLE) return true;
    }
    return false;
  }

  std::string path_;
  std::uint64_t file_size_;
};

// The HDF5 signature sits at offset 0 or, after a user block, at 512, 1024, 2048, ... We check it
// ourselves because H5Fis_hdf5 can leave a half-opened file behind in the library on bad input.
bool has_hdf5_signature(const std::string& path) {
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  for (std::uint64_t offset = 0; offset + 8 <= size; offset = offset == 0 ? 512 : 2 * offset) {
    char bytes[8] = {};
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(bytes, 8)) return false;
    if (std::memcmp(bytes, kSignature, 8) == 0) return true;
  }
  return false;
}

Packing read_hdf5(const std::string& path) {
  if (!has_hdf5_signature(path)) {
    throw FormatError(Wording{Sentence::kNotHdf5, {path, kNativeFormatName}});
  }
  std::error_code size_error;
  const std::uint64_t file_size = std::filesystem::file_size(path, size_error);
  if (size_error) throw IoError(Wording{Sentence::kReadSystemError, {path, size_error.message()}});
  const Reader reader(path, file_size);
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // Strong close: closing the file closes every object still open in it, so a read that failed
  // half-way cannot leave the file open inside the library (HDF5 would then hand the stale, cached
  // file to the next open of the same path).
  H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose);
  if (!file.is_valid()) {
    reader.fail(Sentence::kHdf5Unreadable, {hdf5_reason()});
  }
  const hid_t root = file.get();

  if (!reader.exists(H5Aexists(root, "format_name"), "/format_name")) {
    reader.fail(Sentence::kNoFormatName, {kNativeFormatName});
  }
  const std::string format_name = reader.read_attribute_string(root, "", "format_name");
  if (format_name != kNativeFormatName) {
    reader.fail(Sentence::kWrongFormatName, {echo(format_name), kNativeFormatName});
  }
  const std::uint64_t version = reader.read_attribute_unsigned(root, "", "format_version");
  if (version != kNativeFormatVersion) {
    reader.fail(Sentence::kWrongFormatVersion,
                {std::to_string(version), std::to_string(version), AGGPACK_VERSION,
                 std::to_string(kNativeFormatVersion)});
  }

  Packing packing;
  std::vector<double> container_values;  // in file order, for the range check
  const ContainerKindInfo* container_kind = nullptr;
  {
    Handle group = reader.open_group(root, "container");
    Container& c = packing.container;
    const std::string kind = reader.read_attribute_string(group.get(), "/container", "kind");
    const ContainerKindInfo* info = find_container_kind(kind);
    if (info == nullptr) {
      reader.fail("/container/kind = " + echo(kind),
                  {Sentence::kNativeUnknownKind, {container_kind_names()}});
    }
    c = info->defaults;
    // Every kind's parameters are stored; only this kind's are kept (checked before the rest of
    // the file's content, as validate_packing would).
    for (const ContainerKindInfo& each : container_kinds()) {
      for (const ContainerParam& param : each.params) {
        const double value = reader.read_attribute_float(group.get(), "/container", param.name);
        container_values.push_back(value);
        param.set(c, value);
      }
    }
    c.wall_gap = reader.read_attribute_float(group.get(), "/container", "wall_gap");
    container_values.push_back(c.wall_gap);
    container_kind = info;
    if (reader.exists(H5Aexists(group.get(), "periodic"), "/container/periodic")) {
      const std::string word = reader.read_attribute_string(group.get(), "/container", "periodic");
      auto* box = c.get_if<BoxContainer>();
      if (box == nullptr || !parse_periodic_word(word, box->periodic)) {
        reader.fail("/container/periodic = " + echo(word),
                    {Sentence::kNativePeriodicWord, {"x, y, z, xy, xz, yz or xyz"}});
      }
    }
  }

  {
    Handle group = reader.open_group(root, "shapes");
    std::vector<double> vertices;
    std::vector<std::uint32_t> triangles;
    std::vector<std::uint64_t> vertex_offsets;
    std::vector<std::uint64_t> triangle_offsets;
    std::size_t vertex_rows = 0;
    std::size_t triangle_rows = 0;
    std::size_t shape_rows = 0;
    std::size_t triangle_shape_rows = 0;
    reader.read_dataset(group.get(), "shapes", "vertex_offsets", H5T_NATIVE_UINT64, kUint64, 0,
                        vertex_offsets, shape_rows);
    reader.read_dataset(group.get(), "shapes", "triangle_offsets", H5T_NATIVE_UINT64, kUint64, 0,
                        triangle_offsets, triangle_shape_rows);
    if (shape_rows == 0) {
      reader.fail("/shapes/vertex_offsets", {Sentence::kNativeOffsetsEmpty, {}});
    }
    if (triangle_shape_rows != shape_rows) {
      reader.fail("/shapes/triangle_offsets",
                  {Sentence::kNativeValuesButHas,
                   {std::to_string(triangle_shape_rows), "/shapes/vertex_offsets",
                    std::to_string(shape_rows)}});
    }
    reader.read_dataset(group.get(), "shapes", "vertices", H5T_NATIVE_DOUBLE, kFloat64, 3, vertices,
                        vertex_rows);
    reader.read_dataset(group.get(), "shapes", "triangles", H5T_NATIVE_UINT32, kUint32, 3,
                        triangles, triangle_rows);
    if (vertex_offsets.front() != 0 || vertex_offsets.back() != vertex_rows) {
      reader.fail("/shapes/vertex_offsets",
                  {Sentence::kNativeOffsetsRun,
                   {std::to_string(vertex_offsets.front()), std::to_string(vertex_offsets.back()),
                    std::to_string(vertex_rows), "/shapes/vertices"}});
    }
    if (triangle_offsets.front() != 0 || triangle_offsets.back() != triangle_rows) {
      reader.fail(
          "/shapes/triangle_offsets",
          {Sentence::kNativeOffsetsRun,
           {std::to_string(triangle_offsets.front()), std::to_string(triangle_offsets.back()),
            std::to_string(triangle_rows), "/shapes/triangles"}});
    }
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      if (!std::isfinite(vertices[k])) {
        reader.fail("/shapes/vertices[" + std::to_string(k / 3) + "]",
                    {Sentence::kNativeNotFinite, {}});
      }
    }
    const std::size_t shape_count = shape_rows - 1;
    packing.shapes.reserve(shape_count);
    for (std::size_t s = 0; s < shape_count; ++s) {
      const std::uint64_t v0 = vertex_offsets[s];
      const std::uint64_t v1 = vertex_offsets[s + 1];
      const std::uint64_t t0 = triangle_offsets[s];
      const std::uint64_t t1 = triangle_offsets[s + 1];
      if (v1 < v0 || v1 > vertex_rows) {
        reader.fail("/shapes/vertex_offsets[" + std::to_string(s + 1) + "] = " + std::to_string(v1),
                    {Sentence::kNativeOffsetsDecrease, {}});
      }
      if (t1 < t0 || t1 > triangle_rows) {
        reader.fail(
            "/shapes/triangle_offsets[" + std::to_string(s + 1) + "] = " + std::to_string(t1),
            {Sentence::kNativeOffsetsDecrease, {}});
      }
      std::vector<Vec3> shape_vertices;
      shape_vertices.reserve(v1 - v0);
      for (std::uint64_t v = v0; v < v1; ++v) {
        shape_vertices.emplace_back(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
      }
      std::vector<Triangle> shape_triangles;
      shape_triangles.reserve(t1 - t0);
      for (std::uint64_t t = t0; t < t1; ++t) {
        shape_triangles.push_back({triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]});
      }
      try {
        packing.shapes.emplace_back(std::move(shape_vertices), std::move(shape_triangles));
      } catch (const InvalidInput& error) {
        native_detail::fail_field(path,
                                  {Sentence::kNativeShapeRows,
                                   {"/shapes/triangles", std::to_string(s), std::to_string(t0),
                                    std::to_string(t1 == t0 ? t0 : t1 - 1)}},
                                  {Sentence::kNativeNotPolyhedron, {error.what()}},
                                  worded_as_value(error));
      }
    }
  }

  {
    Handle group = reader.open_group(root, "particles");
    std::vector<std::uint32_t> shape;
    std::vector<std::uint32_t> size_class;
    std::vector<double> position;
    std::vector<double> rotation;
    std::vector<double> control_radius;
    std::vector<double> scale;
    std::size_t rows[6] = {};
    reader.read_dataset(group.get(), "particles", "shape", H5T_NATIVE_UINT32, kUint32, 0, shape,
                        rows[0]);
    reader.read_dataset(group.get(), "particles", "position", H5T_NATIVE_DOUBLE, kFloat64, 3,
                        position, rows[1]);
    reader.read_dataset(group.get(), "particles", "rotation", H5T_NATIVE_DOUBLE, kFloat64, 4,
                        rotation, rows[2]);
    reader.read_dataset(group.get(), "particles", "control_radius", H5T_NATIVE_DOUBLE, kFloat64, 0,
                        control_radius, rows[3]);
    reader.read_dataset(group.get(), "particles", "size_class", H5T_NATIVE_UINT32, kUint32, 0,
                        size_class, rows[4]);
    reader.read_dataset(group.get(), "particles", "scale", H5T_NATIVE_DOUBLE, kFloat64, 0, scale,
                        rows[5]);
    const char* names[6] = {"shape",          "position",   "rotation",
                            "control_radius", "size_class", "scale"};
    const std::size_t n = rows[0];
    for (int k = 1; k < 6; ++k) {
      if (rows[k] != n) {
        reader.fail(std::string("/particles/") + names[k],
                    {Sentence::kNativeRowsButHas,
                     {std::to_string(rows[k]), "/particles/shape", std::to_string(n)}});
      }
    }
    packing.particles.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Particle& p = packing.particles[i];
      p.shape = shape[i];
      p.size_class = size_class[i];
      p.control_radius = control_radius[i];
      p.scale = scale[i];
      p.pose.position = Vec3(position[3 * i], position[3 * i + 1], position[3 * i + 2]);
      p.pose.rotation =
          Quat(rotation[4 * i], rotation[4 * i + 1], rotation[4 * i + 2], rotation[4 * i + 3]);
    }
  }

  {
    Handle group = reader.open_group(root, "provenance");
    Provenance& p = packing.provenance;
    p.aggpack_version = reader.read_attribute_string(group.get(), "/provenance", "aggpack_version");
    p.config_toml = reader.read_attribute_string(group.get(), "/provenance", "config_toml");
    p.packer = reader.read_attribute_string(group.get(), "/provenance", "packer");
    p.seed = reader.read_attribute_unsigned(group.get(), "/provenance", "seed");
    if (reader.exists(H5Aexists(group.get(), "shape_library"), "/provenance/shape_library")) {
      p.shape_library = reader.read_attribute_string(group.get(), "/provenance", "shape_library");
    }
  }
  native_detail::check_container_values(*container_kind, container_values, path);
  validate_packing(packing, path);
  return packing;
}

}  // namespace

Packing read_packing(const std::string& path) {
  // stat fails with EACCES in an unreadable folder: only ENOENT is "no such file".
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error) throw IoError(io_detail::read_failure_wording(path, error.value()));
  if (std::filesystem::is_directory(status)) {
    throw IoError(Wording{Sentence::kReadFolder, {path}});
  }
  errno = 0;
  if (!std::ifstream(path, std::ios::binary)) {
    throw IoError(io_detail::read_failure_wording(path, errno));
  }
  const SilenceHdf5Errors silence;
  return read_hdf5(path);
}

}  // namespace aggpack
