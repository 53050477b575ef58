// CalculiX deck (.inp): the trough test reduced to what ccx supports. The floor, the walls and the
// baffle are single C3D8 slabs with every node prescribed (fixed, the baffle's moved along x);
// ccx has no general contact, so contact pairs are listed: between particles whose bounding
// spheres are within contact_distance, between every particle and the floor, and between a
// particle and a wall or the baffle within that distance. Three implicit *DYNAMIC steps.

#include <algorithm>
#include <array>
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

void append_step(std::string& out, const char* name, double time, double increment,
                 const std::string& boundary) {
  const double first = std::min(increment, time);
  out += "** Step " + std::string(name) + "\n*STEP, NLGEOM, INC=10000000\n*DYNAMIC\n" +
         deck_number(first) + ", " + deck_number(time) + ", " + deck_number(first * 1e-6) + ", " +
         deck_number(first) + '\n' + boundary +
         "*NODE FILE, NSET=ALLNODES\nU, V\n*EL FILE\nS\n"
         "*NODE PRINT, NSET=FLOOR_N, TOTALS=ONLY\nRF\n"
         "*NODE PRINT, NSET=BAFFLE_N, TOTALS=ONLY\nRF\n*END STEP\n";
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
  const double increment_of = deck.max_increment;
  const auto increment = [&](double time) {
    return increment_of > 0.0 ? increment_of : time / 100;
  };
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
           " (0.02 E / largest particle radius), stick slope a tenth of it; implicit *DYNAMIC "
           "steps with increments of at most " +
           (increment_of > 0.0 ? deck_number(increment_of) : std::string("step time / 100")) +
           " [--max-increment]."});
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
  append_step(text, "SETTLE", t.settle_time, increment(t.settle_time), gravity);
  append_step(
      text, "BAFFLE", t.baffle_time, increment(t.baffle_time),
      "*BOUNDARY, AMPLITUDE=BAFFLE_MOVE\nBAFFLE_N, 1, 1, " + deck_number(t.travel()) + '\n');
  if (t.rest_time > 0.0) {
    append_step(text, "REST", t.rest_time, increment(t.rest_time),
                "*BOUNDARY\nBAFFLE_N, 1, 1, " + deck_number(t.travel()) + '\n');
  }
  out << text;
}

}  // namespace aggpack::detail
