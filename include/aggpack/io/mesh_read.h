#pragma once
// Readers of particle meshes made elsewhere (scans, CAD): STL (binary and ASCII), Wavefront OBJ
// and PLY (ASCII, binary little- and big-endian), into one indexed TriangleMesh. Strict and
// bounded: counts are checked against the file's size before anything is allocated, and every
// fault is a one-line FormatError naming the file and what is wrong.

#include <cstdint>
#include <string>
#include <string_view>

#include "aggpack/geom/triangle_mesh.h"

namespace aggpack {

/// The mesh file formats read_mesh_file understands.
enum class MeshFileFormat { kStl, kObj, kPly };

/// The format of a file name by its extension (.stl, .obj, .ply; any case); false if none.
bool mesh_file_format(std::string_view path, MeshFileFormat& format);

/// A file's bytes, refused above `max_bytes`. \throw IoError (missing, a folder, unreadable),
/// LimitExceeded naming the file when it is larger than max_bytes.
std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes);

/// Parses a mesh file's content. STL facets are joined at bitwise-equal vertices (STL stores
/// each facet's own copies); OBJ and PLY polygons are fanned into triangles from their first
/// vertex. `path` names the file in messages. \throw FormatError.
TriangleMesh parse_mesh(const std::string& content, MeshFileFormat format, const std::string& path);

/// FNV-1a 64-bit hash of a file's content, as "fnv1a64:" and 16 hex digits (provenance: which
/// bytes a shape came from; not a security hash).
std::string content_hash(std::string_view content);

namespace io_detail {
/// PLY (src/io/mesh_read_ply.cpp). \throw FormatError.
TriangleMesh parse_ply(const std::string& content, const std::string& path);
}  // namespace io_detail

}  // namespace aggpack
