// Convex hull through Qhull's reentrant C library (libqhull_r; Debian's libqhull-dev).

#include "aggpack/geom/convex_hull_3d.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace aggpack {

namespace {

// Qhull's messages go to a memory stream, so a failure can quote them in one line.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&buffer_, &size_)) {}
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;
  ~MessageStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);  // NOLINT(cppcoreguidelines-no-malloc): open_memstream's buffer
  }
  [[nodiscard]] FILE* file() const { return file_; }
  // The first line of what Qhull wrote (its error code and reason).
  std::string first_line() {
    if (file_ == nullptr) return "";
    std::fflush(file_);
    std::string text(buffer_ != nullptr ? buffer_ : "", size_);
    const auto start = text.find_first_not_of(" \n");
    if (start == std::string::npos) return "";
    text = text.substr(start, text.find('\n', start) - start);
    return clipped(text, 200);
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

// One Qhull run, freed on every path.
class Qhull {
 public:
  Qhull() { qh_zero(&qh_, messages_.file()); }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;
  ~Qhull() {
    qh_freeqhull(&qh_, !qh_ALL);
    int current = 0;
    int total = 0;
    qh_memfreeshort(&qh_, &current, &total);
  }
  qhT* get() { return &qh_; }
  MessageStream& messages() { return messages_; }

 private:
  MessageStream messages_;
  qhT qh_{};
};

}  // namespace

ConvexPolyhedron convex_hull(std::span<const Vec3> points) {
  if (points.size() < 4) {
    throw InvalidInput("hull", std::to_string(points.size()) + " points", "at least 4 points");
  }
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw InvalidInput("hull", "a non-finite point", "finite coordinates");
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  }
  Qhull run;
  qhT* qh = run.get();
  char command[] = "qhull";  // default options: merged facets, no output
  const int code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                command, nullptr, run.messages().file());
  if (code != 0) {
    const std::string reason = run.messages().first_line();
    throw InvalidInput(
        Wording{Sentence::kText, {"hull"}}, Wording{Sentence::kQhullError, {std::to_string(code)}},
        Wording{Sentence::kPointsSpanVolume, {reason.empty() ? "degenerate" : reason}});
  }
  // Hull vertices in input order (deterministic), renumbered from 0.
  std::vector<std::int64_t> index(points.size(), -1);
  vertexT* vertex = nullptr;
  FORALLvertices { index[static_cast<std::size_t>(qh_pointid(qh, vertex->point))] = 0; }
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (index[i] < 0) continue;
    index[i] = static_cast<std::int64_t>(vertices.size());
    vertices.push_back(points[i]);
  }
  std::vector<Triangle> triangles;
  facetT* facet = nullptr;
  FORALLfacets {
    // qh_facet3vertex: the facet's vertices in cyclic order around it.
    setT* ring = qh_facet3vertex(qh, facet);
    std::vector<std::uint32_t> cycle;
    vertexT** vertexp = nullptr;  // FOREACHvertex_'s cursor
    FOREACHvertex_(ring) {
      cycle.push_back(static_cast<std::uint32_t>(
          index[static_cast<std::size_t>(qh_pointid(qh, vertex->point))]));
    }
    qh_settempfree(qh, &ring);
    const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
    // Fan from the ring's first vertex; each triangle turned outward by the facet's normal.
    for (std::size_t k = 1; k + 1 < cycle.size(); ++k) {
      Triangle t{cycle[0], cycle[k], cycle[k + 1]};
      const Vec3 n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
      if (n.dot(normal) < 0.0) std::swap(t[1], t[2]);
      triangles.push_back(t);
    }
  }
  return {std::move(vertices), std::move(triangles)};
}

ConvexPolyhedron simplify_hull(const ConvexPolyhedron& body, std::size_t max_vertices) {
  if (max_vertices < 4) {
    throw InvalidInput("hull vertex budget", std::to_string(max_vertices), ">= 4");
  }
  if (body.vertex_count() <= max_vertices) return body;
  // Support vertex of each direction by hill climbing over the hull's vertex graph: on a convex
  // polytope a linear function has no local maximum but the global one (ties aside), and
  // consecutive Fibonacci directions are close, so each climb starts near its answer.
  const auto neighbours = body.vertex_neighbours();
  const auto& vertices = body.vertices();
  std::vector<char> is_chosen(vertices.size(), 0);
  std::size_t current = 0;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const std::size_t directions = max_vertices;
  for (std::size_t k = 0; k < directions; ++k) {
    const double z = 1.0 - 2.0 * (static_cast<double>(k) + 0.5) / static_cast<double>(directions);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * static_cast<double>(k);
    const Vec3 direction(r * std::cos(phi), r * std::sin(phi), z);
    for (bool is_moved = true; is_moved;) {
      is_moved = false;
      double best = vertices[current].dot(direction);
      for (const std::uint32_t next : neighbours[current]) {
        const double value = vertices[next].dot(direction);
        if (value > best) {
          best = value;
          current = next;
          is_moved = true;
        }
      }
    }
    is_chosen[current] = 1;
  }
  std::vector<Vec3> chosen;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (is_chosen[i] != 0) chosen.push_back(vertices[i]);
  }
  return convex_hull(chosen);
}

}  // namespace aggpack
