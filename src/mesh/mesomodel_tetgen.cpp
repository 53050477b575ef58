// TetGen on a mesomodel's piecewise linear complex (mesomodel_plc.h), always in a worker process
// (core/isolated.h): Debian's TetGen 1.5 can abort or loop on some inputs, and a failure must
// cost the command, never the process that asked (the GUI, the Python module).

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/isolated.h"
#include "mesomodel_plc.h"
#include "tetgen_worker.h"

#ifdef AGGPACK_HAS_TETGEN
#define TETLIBRARY
#include <tetgen.h>
#undef REAL
#endif

namespace aggpack::detail {

#ifdef AGGPACK_HAS_TETGEN

namespace {

using Failure = TetGenFailure;

void fill_input(const Plc& plc, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(plc.points.size());
  in.pointlist = new double[3 * plc.points.size()];
  for (std::size_t i = 0; i < plc.points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) in.pointlist[3 * i + axis] = plc.points[i][axis];
  }
  in.numberoffacets = static_cast<int>(plc.facets.size());
  in.facetlist = new tetgenio::facet[plc.facets.size()];
  in.facetmarkerlist = new int[plc.facets.size()];
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const PlcFacet& source = plc.facets[f];
    tetgenio::facet& facet = in.facetlist[f];
    in.facetmarkerlist[f] = source.marker;
    facet.numberofpolygons = static_cast<int>(source.polygons.size());
    facet.polygonlist = new tetgenio::polygon[source.polygons.size()];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    for (std::size_t p = 0; p < source.polygons.size(); ++p) {
      const auto& loop = source.polygons[p];
      facet.polygonlist[p].numberofvertices = static_cast<int>(loop.size());
      facet.polygonlist[p].vertexlist = new int[loop.size()];
      for (std::size_t k = 0; k < loop.size(); ++k) {
        facet.polygonlist[p].vertexlist[k] = static_cast<int>(loop[k]);
      }
    }
  }
  in.numberofholes = static_cast<int>(plc.holes.size());
  in.holelist = new double[3 * plc.holes.size() + 1];
  for (std::size_t h = 0; h < plc.holes.size(); ++h) {
    for (int axis = 0; axis < 3; ++axis) in.holelist[3 * h + axis] = plc.holes[h][axis];
  }
  in.numberofregions = static_cast<int>(plc.regions.size());
  in.regionlist = new double[5 * plc.regions.size()];
  for (std::size_t r = 0; r < plc.regions.size(); ++r) {
    const PlcRegion& region = plc.regions[r];
    for (int axis = 0; axis < 3; ++axis) in.regionlist[5 * r + axis] = region.seed[axis];
    in.regionlist[5 * r + 3] = region.attribute;
    in.regionlist[5 * r + 4] = region.max_volume > 0.0 ? region.max_volume : -1.0;
  }
}

// The mesh as the worker sends it: counts, then the arrays as they are in memory.
std::string mesh_here(const Plc& plc, const std::string& switches) {
  tetgenio in;
  tetgenio out;
  fill_input(plc, in);
  // For bug reports: AGGPACK_TETGEN_DUMP=BASE writes BASE.node and BASE.poly (TetGen's files).
  if (const char* dump = std::getenv("AGGPACK_TETGEN_DUMP"); dump != nullptr && *dump != 0) {
    std::string base = dump;
    in.save_nodes(base.data());
    in.save_poly(base.data());
  }
  std::string letters = switches;
  try {
    tetrahedralize(letters.data(), &in, &out);
  } catch (int code) {
    throw tetgen_failure({code == 3   ? Sentence::kTetGenFacetsIntersect
                          : code == 1 ? Sentence::kTetGenOutOfMemory
                                      : Sentence::kTetGenErrorCode,
                          {std::to_string(code)}});
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra <= 0 ||
      out.numberofpoints < in.numberofpoints || out.numberoftetrahedronattributes < 1) {
    throw tetgen_failure({Sentence::kTetGenNoTetrahedra, {}});
  }
  const std::uint64_t counts[2] = {static_cast<std::uint64_t>(out.numberofpoints),
                                   static_cast<std::uint64_t>(out.numberoftetrahedra)};
  std::string bytes(reinterpret_cast<const char*>(counts), sizeof counts);
  bytes.append(reinterpret_cast<const char*>(out.pointlist), counts[0] * 3 * sizeof(double));
  std::vector<std::uint32_t> corners(4 * counts[1]);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    corners[i] = static_cast<std::uint32_t>(out.tetrahedronlist[i]);
  }
  append_array(bytes, corners);
  std::vector<int> attributes(counts[1]);
  const int stride = out.numberoftetrahedronattributes;
  for (std::size_t e = 0; e < counts[1]; ++e) {
    attributes[e] = static_cast<int>(out.tetrahedronattributelist[e * stride]);
  }
  append_array(bytes, attributes);
  return bytes;
}

// Markers of the facets TetGen's -d finds intersecting, as text ("7 12 ..."), capped.
std::string intersecting_markers_here(const Plc& plc) {
  tetgenio in;
  tetgenio out;
  fill_input(plc, in);
  std::string letters = "pdzQ";
  try {
    tetrahedralize(letters.data(), &in, &out);
  } catch (int) {
    return {};
  }
  std::set<int> markers;
  if (out.trifacemarkerlist != nullptr) {
    for (int f = 0; f < out.numberoftrifaces && markers.size() < 64; ++f) {
      markers.insert(out.trifacemarkerlist[f]);
    }
  }
  std::string text;
  for (const int marker : markers) text += std::to_string(marker) + ' ';
  return text;
}

PlcMesh deserialize(const std::string& bytes) {
  std::uint64_t counts[2] = {0, 0};
  const Wording malformed{Sentence::kWorkerMalformed, {}};
  if (bytes.size() < sizeof counts) throw tetgen_failure(malformed);
  std::memcpy(counts, bytes.data(), sizeof counts);
  const std::uint64_t expected =
      sizeof counts + counts[0] * 3 * sizeof(double) + counts[1] * (4 * 4 + sizeof(int));
  if (bytes.size() != expected) throw tetgen_failure(malformed);
  const char* at = bytes.data() + sizeof counts;
  PlcMesh mesh;
  mesh.nodes.resize(counts[0]);
  for (auto& node : mesh.nodes) {
    std::memcpy(node.data(), at, 3 * sizeof(double));
    at += 3 * sizeof(double);
  }
  mesh.tetrahedra.resize(counts[1]);
  std::memcpy(mesh.tetrahedra.data(), at, counts[1] * sizeof(Tetrahedron));
  at += counts[1] * sizeof(Tetrahedron);
  mesh.attributes.resize(counts[1]);
  std::memcpy(mesh.attributes.data(), at, counts[1] * sizeof(int));
  for (Tetrahedron& tet : mesh.tetrahedra) {
    for (const std::uint32_t node : tet) {
      if (node >= mesh.nodes.size()) throw tetgen_failure(malformed);
    }
    // TetGen's orientation convention is the opposite of ours; fix by sign, not by belief.
    if (tetra_volume(mesh.nodes[tet[0]], mesh.nodes[tet[1]], mesh.nodes[tet[2]],
                     mesh.nodes[tet[3]]) < 0.0) {
      std::swap(tet[0], tet[1]);
    }
  }
  return mesh;
}

}  // namespace

PlcMesh tetrahedralize_plc(const Plc& plc, const std::string& switches, double time_limit) {
  const auto work = [&](std::size_t) {
    return worker_answer([&] { return mesh_here(plc, switches); });
  };
  const IsolatedOutcome outcome =
      run_isolated(1, work, {.workers = 1, .time_limit = time_limit}).front();
  std::string bytes;
  Wording failure;
  std::vector<WordedValue> words;  // values of the failure that are sentences of their own
  if (worker_result(outcome, bytes, failure, words)) {
    try {
      return deserialize(bytes);
    } catch (const Failure& malformed) {
      failure = malformed.wording;
    }
  }
  // Ask TetGen which facets meet, so the message can name the particles.
  const IsolatedOutcome detected =
      run_isolated(1, [&](std::size_t) { return intersecting_markers_here(plc); },
                   {.workers = 1, .time_limit = time_limit})
          .front();
  std::vector<Wording> surfaces;
  if (detected.is_done && !detected.bytes.empty()) {
    std::istringstream markers(detected.bytes);
    int marker = 0;
    while (markers >> marker) {
      surfaces.push_back(marker < 0 ? Wording{Sentence::kSurfaceWall, {std::to_string(-marker)}}
                         : marker % 2 == 0
                             ? Wording{Sentence::kSurfaceAggregate, {std::to_string(marker / 2)}}
                             : Wording{Sentence::kSurfaceItzLayer, {std::to_string(marker / 2)}});
    }
  }
  if (!surfaces.empty()) {
    // "wall 1, aggregate 2, ...": each surface and each tail of the list a sentence of its own.
    Wording list = surfaces.back();
    for (auto surface = surfaces.rbegin() + 1; surface != surfaces.rend(); ++surface) {
      words.push_back({english(list), list});
      words.push_back({english(*surface), *surface});
      list = {Sentence::kSurfaceList, {english(*surface), english(list)}};
    }
    words.push_back({english(list), list});
    if (failure.sentence != Sentence::kText) words.push_back({english(failure), failure});
    failure = {Sentence::kTetGenIntersecting, {english(failure), english(list)}};
  }
  LimitExceeded error(Wording{Sentence::kMesomodelMesh, {}}, failure,
                      Wording{Sentence::kTetGenCanMesh, {"packer.gap", "container.wall_gap"}});
  for (WordedValue& each : words) error.word_value(std::move(each.text), std::move(each.wording));
  throw error;
}

#else

PlcMesh tetrahedralize_plc(const Plc& /*plc*/, const std::string& /*switches*/,
                           double /*time_limit*/) {
  throw InvalidInput("mesomodel", "tetrahedral mesh",
                     "--voxels (this build has no TetGen: install libtet1.5-dev)");
}

#endif

}  // namespace aggpack::detail
