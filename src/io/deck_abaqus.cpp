// Abaqus/Explicit deck (.inp): the particles as deformable C3D4 bodies (the flat layout of
// export_inp.cpp), the floor and four walls as one fixed rigid body of R3D4 elements, the baffle
// as a rigid R3D4 plate whose reference node gets a velocity boundary condition, gravity, general
// contact (all exterior surfaces) with Coulomb friction, three explicit steps, output requests.

#include <array>

#include "deck_common.h"

namespace aggpack::detail {

namespace {

struct Plate {
  const char* name;
  std::array<Vec3, 4> corners;
};

void append_node(std::string& out, std::uint64_t id, const Vec3& p) {
  append_number(out, id);
  for (int axis = 0; axis < 3; ++axis) out += ", " + deck_number(p[axis]);
  out += '\n';
}

// Rigid R3D4 plates; walls reach one largest particle radius beyond the trough's corners.
std::vector<Plate> wall_plates(const Trough& t) {
  const double m = t.largest_radius;
  const double x0 = t.lower.x() - m;
  const double x1 = t.upper.x() + m;
  const double y0 = t.lower.y() - m;
  const double y1 = t.upper.y() + m;
  const double z0 = t.lower.z();
  const double z1 = t.upper.z();
  const double xa = t.lower.x();
  const double xb = t.upper.x();
  const double ya = t.lower.y();
  const double yb = t.upper.y();
  return {
      {"FLOOR", {Vec3(x0, y0, z0), Vec3(x1, y0, z0), Vec3(x1, y1, z0), Vec3(x0, y1, z0)}},
      {"WALL_Y0", {Vec3(x0, ya, z0), Vec3(x0, ya, z1), Vec3(x1, ya, z1), Vec3(x1, ya, z0)}},
      {"WALL_Y1", {Vec3(x0, yb, z0), Vec3(x1, yb, z0), Vec3(x1, yb, z1), Vec3(x0, yb, z1)}},
      {"WALL_X0", {Vec3(xa, y0, z0), Vec3(xa, y1, z0), Vec3(xa, y1, z1), Vec3(xa, y0, z1)}},
      {"WALL_X1", {Vec3(xb, y0, z0), Vec3(xb, y0, z1), Vec3(xb, y1, z1), Vec3(xb, y1, z0)}},
  };
}

void append_output(std::string& out, double time) {
  out += "*OUTPUT, FIELD, TIME INTERVAL=" + deck_number(time / 20) +
         "\n*NODE OUTPUT\nU, V\n*ELEMENT OUTPUT, ELSET=AGGREGATES\nS\n"
         "*OUTPUT, HISTORY, TIME INTERVAL=" +
         deck_number(time / 100) +
         "\n*ENERGY OUTPUT\nALLKE, ALLIE, ALLFD, ALLWK, ETOTAL\n"
         "*NODE OUTPUT, NSET=BAFFLE_REF\nU1, V1, RF1\n";
}

}  // namespace

void write_deck_abaqus(const ExportModel& model, std::ostream& out) {
  const std::vector<ParticleBounds> bounds = particle_bounds(model);
  const Trough t = make_trough(model, bounds);
  out << deck_header(
      model, t, "Abaqus/Explicit", "abaqus job=<this file without .inp>", "** ",
      {"Abaqus: particles are deformable C3D4 bodies; floor and walls are one rigid body "
       "(R3D4, reference node WALLS_REF encastred); the baffle is a rigid R3D4 plate whose "
       "reference node BAFFLE_REF has a velocity boundary condition; general contact over all "
       "exterior surfaces (Abaqus/Explicit enforces it by penalty) and the friction above.",
       "Abaqus: real rock stiffness gives a stable increment of ~1e-6 s per 0.1 m particle; "
       "uncomment the *FIXED MASS SCALING line of step SETTLE to run faster (check the kinetic "
       "energy stays small against the internal energy)."});
  write_abaqus(model, out);

  std::string text = "** Rigid floor and walls (one rigid body), rigid baffle.\n";
  std::uint64_t node = model.node_count() + 1;
  std::uint64_t element = model.element_count() + 1;
  std::string walls_set;
  std::vector<Plate> plates = wall_plates(t);
  plates.push_back(
      {"BAFFLE",
       {Vec3(t.baffle, t.lower.y(), t.lower.z()), Vec3(t.baffle, t.lower.y(), t.upper.z()),
        Vec3(t.baffle, t.upper.y(), t.upper.z()), Vec3(t.baffle, t.upper.y(), t.lower.z())}});
  for (const Plate& plate : plates) {
    const std::string name = plate.name;
    text += "*NODE, NSET=" + name + "_NODES\n";
    const std::uint64_t first = node;
    for (const Vec3& c : plate.corners) append_node(text, node++, c);
    text += "*ELEMENT, TYPE=R3D4, ELSET=" + name + '\n';
    append_number(text, element++);
    for (std::uint64_t n = first; n < node; ++n) {
      text += ", ";
      append_number(text, n);
    }
    text += '\n';
    if (name != "BAFFLE") walls_set += walls_set.empty() ? name : ", " + name;
  }
  text += "*ELSET, ELSET=WALLS\n" + walls_set + '\n';
  const Vec3 centre = 0.5 * (t.lower + t.upper);
  text += "*NODE, NSET=WALLS_REF\n";
  append_node(text, node++, Vec3(centre.x(), centre.y(), t.lower.z()));
  text += "*NODE, NSET=BAFFLE_REF\n";
  append_node(text, node++, Vec3(t.baffle, centre.y(), centre.z()));
  text +=
      "*RIGID BODY, ELSET=WALLS, REF NODE=WALLS_REF\n"
      "*RIGID BODY, ELSET=BAFFLE, REF NODE=BAFFLE_REF\n"
      "*BOUNDARY\nWALLS_REF, ENCASTRE\n"
      "*AMPLITUDE, NAME=CONSTANT\n0, 1, " +
      deck_number(10 * t.end_time() + 1) + ", 1\n*SURFACE INTERACTION, NAME=ROUGH\n*FRICTION\n" +
      deck_number(t.friction) + ",\n";

  text +=
      "** Step SETTLE: the particles fall and settle behind the still baffle.\n"
      "*STEP, NAME=SETTLE, NLGEOM=YES\n*DYNAMIC, EXPLICIT\n, " +
      deck_number(t.settle_time) +
      "\n** *FIXED MASS SCALING, ELSET=AGGREGATES, DT=1e-05, TYPE=BELOW MIN\n"
      "*BOUNDARY, TYPE=VELOCITY\nBAFFLE_REF, 1, 6, 0\n*DLOAD\nAGGREGATES, GRAV, " +
      deck_number(t.gravity) +
      ", 0, 0, -1\n*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
      "*CONTACT PROPERTY ASSIGNMENT\n, , ROUGH\n";
  append_output(text, t.settle_time);
  text +=
      "*END STEP\n** Step BAFFLE: the baffle moves toward +x to the trough end.\n"
      "*STEP, NAME=BAFFLE, NLGEOM=YES\n*DYNAMIC, EXPLICIT\n, " +
      deck_number(t.baffle_time) +
      "\n*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=CONSTANT\nBAFFLE_REF, 1, 1, " +
      deck_number(t.baffle_speed) + '\n';
  append_output(text, t.baffle_time);
  text += "*END STEP\n";
  if (t.rest_time > 0.0) {
    text +=
        "** Step REST: the baffle stands at the trough end, the pile comes to rest.\n"
        "*STEP, NAME=REST, NLGEOM=YES\n*DYNAMIC, EXPLICIT\n, " +
        deck_number(t.rest_time) + "\n*BOUNDARY, TYPE=VELOCITY\nBAFFLE_REF, 1, 1, 0\n";
    append_output(text, t.rest_time);
    text += "*END STEP\n";
  }
  out << text;
}

}  // namespace aggpack::detail
