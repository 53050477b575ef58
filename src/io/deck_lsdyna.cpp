// LS-DYNA deck (.k): the .k mesh of export_k.cpp (part i = particle i, ELFORM 10 tetrahedra),
// planar rigid walls (*RIGIDWALL_PLANAR) for the floor and the four walls, the baffle as a rigid
// shell part moved by *BOUNDARY_PRESCRIBED_MOTION_RIGID, gravity by *LOAD_BODY_Z and its curve,
// *CONTACT_AUTOMATIC_SINGLE_SURFACE over every part with friction, termination and output.
// Every card is in the fixed 10-column format (curve points: 20 columns).

#include <initializer_list>

#include "deck_common.h"

namespace aggpack::detail {

namespace {

// One card: integer fields (as text) and numbers, each right-aligned in `width` columns.
struct Field {
  Field(std::uint64_t value) : text(std::to_string(value)) {}  // NOLINT: implicit on purpose
  Field(int value) : text(std::to_string(value)) {}            // NOLINT
  Field(double value, bool) : text(deck_number(value, 9)) {}
  std::string text;
};

Field real(double value) { return {value, true}; }

void card(std::string& out, std::initializer_list<Field> fields, int width = 10) {
  for (const Field& field : fields) {
    out.append(static_cast<std::size_t>(width) - std::min<std::size_t>(width, field.text.size()),
               ' ');
    out += field.text;
  }
  out += '\n';
}

// A curve of (time, value) points in 20-column fields.
void curve(std::string& out, int id, const char* title,
           std::initializer_list<std::pair<double, double>> points) {
  out += "*DEFINE_CURVE_TITLE\n";
  out += title;
  out += "\n$#    lcid      sidr       sfa       sfo\n";
  card(out, {id, 0, real(1.0), real(1.0)});
  for (const auto& [a, o] : points) out += deck_field(a, 20) + deck_field(o, 20) + '\n';
}

// A planar rigid wall through `tail` whose normal (toward the particles) is `normal`.
void rigid_wall(std::string& out, const char* name, const Vec3& tail, const Vec3& normal,
                double friction) {
  const Vec3 head = tail + normal;
  out += std::string("$ ") + name +
         "\n*RIGIDWALL_PLANAR\n$#    nsid    nsidex     boxid    offset     birth     death\n";
  card(out, {0, 1, 0, real(0.0), real(0.0), real(1e20)});
  out += "$#      xt        yt        zt        xh        yh        zh      fric\n";
  card(out, {real(tail.x()), real(tail.y()), real(tail.z()), real(head.x()), real(head.y()),
             real(head.z()), real(friction)});
}

}  // namespace

void write_deck_lsdyna(const ExportModel& model, std::ostream& out) {
  const std::vector<ParticleBounds> bounds = particle_bounds(model);
  const Trough t = make_trough(model, bounds);
  const MaterialOptions& material = model.options().material;
  const std::uint64_t baffle_part = model.size() + 1;
  write_lsdyna_mesh(
      model, out,
      deck_header(model, t, "LS-DYNA", "lsdyna i=<this file>", "$ ",
                  {"LS-DYNA: floor and walls are *RIGIDWALL_PLANAR (all nodes but the "
                   "baffle's, friction above); the baffle is rigid shell part " +
                   std::to_string(baffle_part) +
                   " moved along x by *BOUNDARY_PRESCRIBED_MOTION_RIGID (curve 2); gravity "
                   "*LOAD_BODY_Z (curve 1); *CONTACT_AUTOMATIC_SINGLE_SURFACE over every part; "
                   "set DT2MS in *CONTROL_TIMESTEP for mass scaling."}));

  std::string text = "$ Trough test: termination, time step, gravity, contact, walls, baffle.\n";
  text += "*CONTROL_TERMINATION\n$#  endtim\n";
  card(text, {real(t.end_time())});
  text += "*CONTROL_TIMESTEP\n$#  dtinit    tssfac      isdo    tslimt     dt2ms\n";
  card(text, {real(0.0), real(0.9), 0, real(0.0), real(0.0)});
  curve(text, 1, "gravity", {{0.0, 1.0}, {10.0 * t.end_time() + 1.0, 1.0}});
  text += "*LOAD_BODY_Z\n$#    lcid        sf\n";
  card(text, {1, real(t.gravity)});
  const double ramp = 0.01 * t.baffle_time;
  const double start = t.settle_time;
  const double stop = t.settle_time + t.baffle_time;
  curve(text, 2, "baffle velocity",
        {{0.0, 0.0},
         {start, 0.0},
         {start + ramp, t.baffle_speed},
         {stop, t.baffle_speed},
         {stop + ramp, 0.0},
         {10.0 * t.end_time() + 1.0, 0.0}});

  text += "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n$#    ssid      msid     sstyp     mstyp\n";
  card(text, {0, 0, 5, 0});
  text += "$#      fs        fd        dc        vc       vdc    penchk        bt        dt\n";
  card(text, {real(t.friction), real(t.friction), real(0.0), real(0.0), real(20.0), 0, real(0.0),
              real(1e20)});
  text += "$#     sfs       sfm       sst       mst      sfst      sfmt       fsf       vsf\n";
  card(text,
       {real(1.0), real(1.0), real(0.0), real(0.0), real(1.0), real(1.0), real(1.0), real(1.0)});

  const Vec3& l = t.lower;
  const Vec3& u = t.upper;
  rigid_wall(text, "floor", l, Vec3(0, 0, 1), t.friction);
  rigid_wall(text, "side wall y0", l, Vec3(0, 1, 0), t.friction);
  rigid_wall(text, "side wall y1", Vec3(l.x(), u.y(), l.z()), Vec3(0, -1, 0), t.friction);
  rigid_wall(text, "end wall x0", l, Vec3(1, 0, 0), t.friction);
  rigid_wall(text, "end wall x1", Vec3(u.x(), l.y(), l.z()), Vec3(-1, 0, 0), t.friction);

  // The baffle: one rigid shell (4 nodes), excluded from the rigid walls (node set 1).
  const std::uint64_t node = model.node_count() + 1;
  text += "$ Baffle: rigid shell part " + std::to_string(baffle_part) + "\n*PART\nbaffle\n";
  card(text, {baffle_part, 2, 2});
  text += "*SECTION_SHELL\n$#   secid    elform      shrf       nip\n";
  card(text, {2, 2, real(1.0), 2});
  text += "$#      t1        t2        t3        t4\n";
  const double thickness = 0.1 * t.largest_radius;
  card(text, {real(thickness), real(thickness), real(thickness), real(thickness)});
  text += "*MAT_RIGID\n$#     mid        ro         e        pr\n";
  card(text,
       {2, real(material.density), real(material.youngs_modulus), real(material.poisson_ratio)});
  text += "$#     cmo      con1      con2\n";
  card(text, {real(1.0), real(5.0), real(7.0)});
  text += "$#lco or a1      a2        a3        v1        v2        v3\n";
  card(text, {real(0.0), real(0.0), real(0.0), real(0.0), real(0.0), real(0.0)});
  text += "*NODE\n";
  // Shell contact reaches half the thickness off the mid-surface: the plate stands that far ahead.
  const double x = t.baffle + 0.5 * thickness;
  const Vec3 corners[4] = {Vec3(x, l.y(), l.z()), Vec3(x, u.y(), l.z()), Vec3(x, u.y(), u.z()),
                           Vec3(x, l.y(), u.z())};
  for (std::uint64_t c = 0; c < 4; ++c) {
    append_field(text, node + c, 8);
    for (int axis = 0; axis < 3; ++axis) text += deck_field(corners[c][axis], 16);
    text += "       0       0\n";
  }
  text += "*ELEMENT_SHELL\n";
  card(text, {model.element_count() + 1, baffle_part, node, node + 1, node + 2, node + 3}, 8);
  text += "*SET_NODE_LIST\n$#     sid\n";
  card(text, {1});
  card(text, {node, node + 1, node + 2, node + 3});
  text += "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n$#     pid       dof       vad      lcid        sf\n";
  card(text, {baffle_part, 1, 0, 2, real(1.0)});

  const double interval = t.end_time() / 100.0;
  for (const char* database :
       {"*DATABASE_GLSTAT", "*DATABASE_MATSUM", "*DATABASE_RWFORC", "*DATABASE_RCFORC"}) {
    text += std::string(database) + "\n$#      dt\n";
    card(text, {real(interval)});
  }
  text += "*DATABASE_BINARY_D3PLOT\n$#      dt\n";
  card(text, {real(t.end_time() / 50.0)});
  text += "*END\n";
  out << text;
}

}  // namespace aggpack::detail
