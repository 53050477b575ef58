// CalculiX deck (.inp): the trough test reduced to what ccx supports. The floor, the walls and the
// baffle are single C3D8 slabs with every node prescribed (fixed, the baffle's moved along x);
// ccx has no general contact, so contact pairs are listed: between particles whose bounding
// spheres are within contact_distance, between every particle and the floor, and between a
// particle and a wall or the baffle within that distance (surface-to-surface penalty contact:
// ccx 2.20's explicit node-to-surface contact corrupts its heap with more than 16 pairs).
// Three explicit *DYNAMIC steps: ccx's implicit dynamics rejects frictional impacts (its energy
// rules cut the increment to nothing), explicit integration runs them.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "deck_common.h"

namespace aggpack::detail {

namespace {

// A slab: its box and the C3D8 face (S1..S6) that faces the particles.
struct Slab {
  const char* name;
  Aabb box;
  int face;
};

// C3D8 corner order: bottom 1-2-3-4 counter-clockwise seen from above, then top 5-8.
std::array<Vec3, 8> corners(const Aabb& b) {
  const Vec3& l = b.lower;
  const Vec3& u = b.upper;
  return {Vec3(l.x(), l.y(), l.z()), Vec3(u.x(), l.y(), l.z()), Vec3(u.x(), u.y(), l.z()),
          Vec3(l.x(), u.y(), l.z()), Vec3(l.x(), l.y(), u.z()), Vec3(u.x(), l.y(), u.z()),
          Vec3(u.x(), u.y(), u.z()), Vec3(l.x(), u.y(), u.z())};
}

std::vector<Slab> slabs(const Trough& t) {
  const double th = std::max(t.largest_radius, 1e-3 * t.extent().norm());
  const Vec3& l = t.lower;
  const Vec3& u = t.upper;
  return {
      // C3D8 faces: S1 z-, S2 z+, S3 y-, S4 x+, S5 y+, S6 x-.
      {"FLOOR", {Vec3(l.x() - th, l.y() - th, l.z() - th), Vec3(u.x() + th, u.y() + th, l.z())}, 2},
      {"WALL_Y0", {Vec3(l.x() - th, l.y() - th, l.z()), Vec3(u.x() + th, l.y(), u.z())}, 5},
      {"WALL_Y1", {Vec3(l.x() - th, u.y(), l.z()), Vec3(u.x() + th, u.y() + th, u.z())}, 3},
      {"WALL_X0", {Vec3(l.x() - th, l.y(), l.z()), Vec3(l.x(), u.y(), u.z())}, 4},
      {"WALL_X1", {Vec3(u.x(), l.y(), l.z()), Vec3(u.x() + th, u.y(), u.z())}, 6},
      {"BAFFLE", {Vec3(t.baffle, l.y(), l.z()), Vec3(t.baffle + th, u.y(), u.z())}, 6},
  };
}

// Distance from a particle's box to a slab's particle-side face (negative: beyond it).
double gap_to(const Slab& slab, const ParticleBounds& b) {
  switch (slab.face) {
    case 2:
      return b.box.lower.z() - slab.box.upper.z();
    case 3:
      return slab.box.lower.y() - b.box.upper.y();
    case 4:
      return b.box.lower.x() - slab.box.upper.x();
    case 5:
      return b.box.lower.y() - slab.box.upper.y();
    default:
      return slab.box.lower.x() - b.box.upper.x();
  }
}

void append_pair(std::string& out, const std::string& slave, const std::string& master) {
  out +=
      "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=SURFACE TO SURFACE\n" + slave + ", " + master + '\n';
}

// Pairs (i < j) of particles whose bounding spheres are within `distance`: a sweep along x.
std::vector<std::pair<std::size_t, std::size_t>> neighbour_pairs(
    const std::vector<ParticleBounds>& bounds, double distance) {
  std::vector<std::size_t> order(bounds.size());
  std::iota(order.begin(), order.end(), 0);
  const auto start = [&](std::size_t i) { return bounds[i].centre.x() - bounds[i].radius; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return start(a) < start(b) || (start(a) == start(b) && a < b);
  });
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < order.size(); ++a) {
    const ParticleBounds& p = bounds[order[a]];
    const double reach = p.centre.x() + p.radius + distance;
    for (std::size_t b = a + 1; b < order.size() && start(order[b]) <= reach; ++b) {
      const ParticleBounds& q = bounds[order[b]];
      if ((p.centre - q.centre).norm() <= p.radius + q.radius + distance) {
        pairs.emplace_back(std::min(order[a], order[b]), std::max(order[a], order[b]));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// ccx's stable explicit increment, estimated: the smallest tetrahedron height over the
// dilatational wave speed. Sets the output frequency only (ccx computes its own increment).
double stable_increment(const ExportModel& model) {
  const MaterialOptions& m = model.options().material;
  const double nu = m.poisson_ratio;
  const double wave =
      std::sqrt(m.youngs_modulus * (1 - nu) / (m.density * (1 + nu) * (1 - 2 * nu)));
  double height = std::numeric_limits<double>::infinity();
  std::vector<Vec3> nodes;
  std::vector<Tetrahedron> scratch;
  for (std::size_t k = 0; k < model.size(); ++k) {
    model.linear_nodes(k, nodes);
    for (const Tetrahedron& e : model.tetrahedra(k, scratch)) {
      const Vec3 p[4] = {nodes[e[0]], nodes[e[1]], nodes[e[2]], nodes[e[3]]};
      const double volume = std::abs((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0])) / 6;
      double area = 0;
      for (int f = 0; f < 4; ++f) {
        const Vec3& a = p[(f + 1) % 4];
        area = std::max(area, 0.5 * (p[(f + 2) % 4] - a).cross(p[(f + 3) % 4] - a).norm());
      }
      if (area > 0) height = std::min(height, 3 * volume / area);
    }
  }
  return height / wave;
}

void append_step(std::string& out, const char* name, double time, double increment,
                 const std::string& boundary) {
  // About 20 output frames per step.
  const auto frequency =
      static_cast<std::uint64_t>(std::max(1.0, std::floor(time / increment / 20)));
  const std::string every = ", FREQUENCY=" + std::to_string(frequency);
  out += "** Step " + std::string(name) + "\n*STEP, NLGEOM, INC=1000000000\n*DYNAMIC, EXPLICIT\n" +
         deck_number(std::min(increment, time)) + ", " + deck_number(time) + '\n' + boundary +
         "*NODE FILE, NSET=ALLNODES" + every + "\nU, V\n*EL FILE" + every +
         "\nS\n"
         "*NODE PRINT, NSET=FLOOR_N, TOTALS=ONLY" +
         every +
         "\nRF\n"
         "*NODE PRINT, NSET=BAFFLE_N, TOTALS=ONLY" +
         every + "\nRF\n*END STEP\n";
}

}  // namespace

void write_deck_calculix(const ExportModel& model, std::ostream& out) {
  const std::vector<ParticleBounds> bounds = particle_bounds(model);
  const Trough t = make_trough(model, bounds);
  const DeckOptions& deck = model.options().deck;
  const double distance = deck.contact_distance > 0.0
                              ? model.options().scale * deck.contact_distance
                              : 0.5 * t.largest_radius;
  const double stiffness = 0.02 * model.options().material.youngs_modulus / t.largest_radius;
  const double increment = stable_increment(model);
  const std::vector<Slab> walls = slabs(t);
  const auto pairs = neighbour_pairs(bounds, distance);

  out << deck_header(
      model, t, "CalculiX", "ccx -i <this file without .inp>", "** ",
      {"CalculiX: the floor, walls and baffle are C3D8 slabs with every node prescribed (the "
       "baffle's moved along x by *BOUNDARY with an amplitude); ccx has no general contact, so "
       "contact pairs are listed, fixed at export: particle pairs whose bounding spheres are "
       "within " +
           deck_number(distance) +
           " [--contact-distance], every particle with the floor, and "
           "particles that close to a wall or the baffle: particles that meet new neighbours "
           "while flowing (stage 2) pass through them. " +
           std::to_string(pairs.size()) + " particle pairs.",
       "CalculiX: penalty contact, linear pressure-overclosure slope " + deck_number(stiffness) +
           " (0.02 E / largest particle radius), stick slope a tenth of it. Explicit *DYNAMIC "
           "steps: ccx picks the stable increment (estimated " +
           deck_number(increment, 12) +
           " s from the smallest tetrahedron; it scales with sqrt(density / E)), output about 20 "
           "times per step. ccx's implicit dynamics fails on frictional impacts."});
  write_abaqus(model, out);

  std::string text = "** Floor, walls and baffle: C3D8 slabs, every node prescribed.\n";
  std::uint64_t node = model.node_count() + 1;
  std::uint64_t element = model.element_count() + 1;
  std::string fixed_sets;
  for (const Slab& slab : walls) {
    const std::string name = slab.name;
    text += "*NODE, NSET=" + name + "_N\n";
    const std::uint64_t first = node;
    for (const Vec3& c : corners(slab.box)) {
      append_number(text, node++);
      for (int axis = 0; axis < 3; ++axis) text += ", " + deck_number(c[axis]);
      text += '\n';
    }
    text += "*ELEMENT, TYPE=C3D8, ELSET=" + name + '\n';
    append_number(text, element++);
    for (std::uint64_t n = first; n < node; ++n) {
      text += ", ";
      append_number(text, n);
    }
    text += "\n*SURFACE, TYPE=ELEMENT, NAME=" + name + "_SURFACE\n" + name + ", S" +
            std::to_string(slab.face) + '\n';
    if (name != "BAFFLE") fixed_sets += name + "_N, 1, 3\n";
  }
  text +=
      "*ELSET, ELSET=SLABS\nFLOOR, WALL_Y0, WALL_Y1, WALL_X0, WALL_X1, BAFFLE\n"
      "*SOLID SECTION, ELSET=SLABS, MATERIAL=" +
      model.options().material.name + '\n';
  text += "*BOUNDARY\n" + fixed_sets + "BAFFLE_N, 1, 3\n";
  text += "*AMPLITUDE, NAME=BAFFLE_MOVE\n0, 0, " + deck_number(t.baffle_time) + ", 1\n";
  text += "*SURFACE INTERACTION, NAME=ROUGH\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n" +
          deck_number(stiffness) + "\n*FRICTION\n" + deck_number(t.friction) + ", " +
          deck_number(0.1 * stiffness) + '\n';
  for (const auto& [i, j] : pairs) {
    append_pair(text, model.particle_name(i) + "_SURFACE", model.particle_name(j) + "_SURFACE");
  }
  for (std::size_t k = 0; k < model.size(); ++k) {
    for (const Slab& slab : walls) {
      if (slab.face == 2 || gap_to(slab, bounds[k]) <= distance) {
        append_pair(text, model.particle_name(k) + "_SURFACE", std::string(slab.name) + "_SURFACE");
      }
    }
  }
  const std::string gravity =
      "*DLOAD\nAGGREGATES, GRAV, " + deck_number(t.gravity) + ", 0, 0, -1\n";
  append_step(text, "SETTLE", t.settle_time, increment, gravity);
  append_step(
      text, "BAFFLE", t.baffle_time, increment,
      "*BOUNDARY, AMPLITUDE=BAFFLE_MOVE\nBAFFLE_N, 1, 1, " + deck_number(t.travel()) + '\n');
  if (t.rest_time > 0.0) {
    append_step(text, "REST", t.rest_time, increment,
                "*BOUNDARY\nBAFFLE_N, 1, 1, " + deck_number(t.travel()) + '\n');
  }
  out << text;
}

}  // namespace aggpack::detail
