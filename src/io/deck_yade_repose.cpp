// The YADE script of `aggpack repose --engine yade` (aggpack/io/yade_repose.h): the export's
// polyhedra bodies (export_yade.cpp), the deck's trough, engines and time step
// (deck_yade_common.h), and the repose test's stages and rest criteria as a PyRunner.

#include "aggpack/io/yade_repose.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "deck_yade_common.h"
#include "export_detail.h"

namespace aggpack {

namespace {

std::string py(double value) {
  std::string text;
  detail::append_number(text, value);
  return text;
}

// The control of the run: stage 1 (settle behind the baffle), stage 2 (the baffle moves until
// it is untouched for BAFFLE_CLEAR_TIME and one largest particle size beyond the pile's toe, then
// it is removed; at the far wall it stops), then the wait for rest and its confirmation. The same
// rules as src/sim/repose.cpp, in YADE's time.
constexpr const char* kControl = R"(
def kinetic_energy():
    energy = 0.0
    for i in particle_ids:
        s = O.bodies[i].state
        w = s.ori.conjugate() * s.angVel  # body frame, where the inertia is diagonal
        energy += 0.5 * s.mass * s.vel.squaredNorm() + 0.5 * (
            s.inertia[0] * w[0] ** 2 + s.inertia[1] * w[1] ** 2 + s.inertia[2] * w[2] ** 2)
    return energy

def pile_speed():
    # The speed 99 % of the pile's particles stay below: centres above FIT_LOWER x the crest.
    crest = max(O.bodies[i].bound.max[2] for i in particle_ids)
    speeds = sorted(O.bodies[i].state.vel.norm() for i in particle_ids
                    if O.bodies[i].state.pos[2] > FIT_LOWER * crest)
    if not speeds:
        return 0.0
    return speeds[int(math.ceil(0.99 * len(speeds))) - 1]

def write_poses(out, tag):
    for i in particle_ids:
        s = O.bodies[i].state
        q = s.ori
        out.write('%s %d %r %r %r %r %r %r %r\n' % (tag, i, s.pos[0], s.pos[1], s.pos[2],
                                                    q[3], q[0], q[1], q[2]))

THRESHOLD = KINETIC_ENERGY_RATIO * TOTAL_MASS * GRAVITY * MEDIAN_SIZE
WINDOW = CONFIRM_WINDOW * math.sqrt(MEDIAN_SIZE / GRAVITY)
SPEED_LIMIT = CONFIRM_SPEED * math.sqrt(GRAVITY * MEDIAN_SIZE)
FAR_STOP = TROUGH_LENGTH - BAFFLE_THICKNESS
run = {'stage': 1, 'begin': 0.0, 'quiet': -1.0, 'confirm': -1.0, 'untouched': 0.0,
       'stage1_rest': 0, 'stage1_time': 0.0, 'removed': 0, 'travel': 0.0, 'waiting': -1.0,
       'stage2_rest': 0, 'restarts': 0, 'max_speed': 0.0, 'window_speed': 0.0, 'done': False}
result = open(RESULT_FILE, 'w')
write_poses(result, 'initial')

def report():
    print('aggpack-yade-progress stage %d time %.9g total %.9g energy %.9g threshold %.9g '
          'iterations %d' % (run['stage'], O.time - run['begin'], O.time, kinetic_energy(),
                             THRESHOLD if run['stage'] != 2 or run['waiting'] >= 0 else 0.0,
                             O.iter), flush=True)

def finish(at_rest):
    run['stage2_rest'] = 1 if at_rest else 0
    run['done'] = True
    O.pause()

def control():
    if run['done']:
        return
    now = O.time
    if run['stage'] == 1:
        energy = kinetic_energy()
        at_rest = False
        if now >= STAGE1_MIN_TIME:
            if energy < THRESHOLD:
                if run['quiet'] < 0:
                    run['quiet'] = now
                at_rest = now - run['quiet'] >= QUIET_TIME
            else:
                run['quiet'] = -1.0
        if at_rest or now >= MAX_TIME:
            run['stage1_rest'] = 1 if at_rest else 0
            run['stage1_time'] = now
            write_poses(result, 'settled')
            run['stage'] = 2
            run['begin'] = now
            run['untouched'] = now
            baffle.state.vel = Vector3(BAFFLE_SPEED, 0, 0)
        return
    if run['waiting'] < 0:
        # The baffle moves toward +x; it stops at the far wall, or goes once clear of the pile.
        x = baffle.state.pos[0]
        if x >= FAR_STOP - 0.5 * BAFFLE_SPEED * O.dt:
            baffle.state.vel = Vector3(0, 0, 0)
            baffle.state.pos = Vector3(FAR_STOP, baffle.state.pos[1], baffle.state.pos[2])
            run['travel'] = FAR_STOP - BAFFLE_POSITION
            run['waiting'] = now
            return
        if any(i.isReal for i in O.interactions.withBody(baffle.id)):
            run['untouched'] = now
            return
        if now - run['untouched'] < BAFFLE_CLEAR_TIME:
            return
        toe = max(O.bodies[i].state.pos[0] for i in particle_ids)
        if x - toe > CLEAR_GAP:
            run['travel'] = x - BAFFLE_POSITION
            O.bodies.erase(baffle.id)
            run['removed'] = 1
            run['waiting'] = now
        return
    # Waiting: the energy criterion, then the confirmation window (the pile's particles slower
    # than SPEED_LIMIT throughout; a violation restarts both).
    if now - run['waiting'] >= MAX_TIME:
        finish(False)
        return
    if now - run['waiting'] < MIN_TIME:
        return
    energy = kinetic_energy()
    if run['confirm'] < 0:
        if energy < THRESHOLD:
            if run['quiet'] < 0:
                run['quiet'] = now
            if now - run['quiet'] >= QUIET_TIME:
                if WINDOW <= 0:
                    finish(True)
                    return
                run['confirm'] = now
                run['window_speed'] = 0.0
        else:
            run['quiet'] = -1.0
        return
    speed = pile_speed()
    run['window_speed'] = max(run['window_speed'], speed)
    if speed > SPEED_LIMIT:
        run['restarts'] += 1
        run['confirm'] = -1.0
        run['quiet'] = -1.0
        return
    if now - run['confirm'] >= WINDOW:
        run['max_speed'] = run['window_speed']
        finish(True)

run['quiet'] = -1.0
print('aggpack-yade-start particles %d dt %r check_steps %d threshold %r' % (
    len(particle_ids), O.dt, CHECK_STEPS, THRESHOLD), flush=True)
O.run()
O.wait()
write_poses(result, 'final')
result.write('stage1 %d %r\n' % (run['stage1_rest'], run['stage1_time']))
result.write('stage2 %d %r %r %d\n' % (run['stage2_rest'], O.time - run['begin'], run['travel'],
                                       run['removed']))
result.write('confirm %r %d %r %r\n' % (WINDOW, run['restarts'], run['max_speed'], SPEED_LIMIT))
result.write('run %r %d\n' % (O.dt, O.iter))
result.write('end\n')
result.close()
print('aggpack-yade-done iterations %d time %.9g' % (O.iter, O.time), flush=True)
)";

}  // namespace

void write_yade_repose_script(const Packing& initial, const YadeReposeScript& s,
                              std::ostream& out) {
  if (initial.particles.empty()) {
    throw InvalidInput("repose fill", "no particles", "at least one particle");
  }
  // Sizes as the Bullet world takes them (src/sim/world_shapes.cpp): equivalent diameters, the
  // median for the rest criteria; the largest bounding-box diagonal for the baffle's clearance.
  std::vector<double> volumes(initial.shapes.size());
  for (std::size_t k = 0; k < initial.shapes.size(); ++k) {
    volumes[k] = mass_properties(initial.shapes[k]).volume;
  }
  std::vector<double> sizes;
  double mass = 0.0;
  double clear_gap = 0.0;
  for (const Particle& particle : initial.particles) {
    const double volume = volumes[particle.shape] * std::pow(particle.scale, 3);
    mass += s.density * volume;
    sizes.push_back(std::cbrt(6.0 * volume / std::numbers::pi));
    clear_gap = std::max(clear_gap,
                         particle.scale * initial.shapes[particle.shape].bounds().extent().norm());
  }
  std::sort(sizes.begin(), sizes.end());
  const double median = sizes[sizes.size() / 2];

  ExportOptions options;
  options.material = {
      .name = "AGGREGATE", .density = s.density, .youngs_modulus = s.young, .poisson_ratio = 0.2};
  const detail::ExportModel model(initial, options, detail::ElementMode::kSurface, 0,
                                  initial.particles.size());
  out << "# aggpack " AGGPACK_VERSION
         " repose test in YADE (aggpack repose --engine yade). Run by aggpack; by hand:\n"
         "#   yade -n -x this_file.py\n";
  detail::write_yade(model, out);
  std::string text =
      "\n# ---- The repose test (aggpack repose --engine yade) ----\n"
      "import math\nfrom yade import utils\n\n";
  const std::pair<const char*, double> constants[] = {
      {"TROUGH_LENGTH", s.trough_length},
      {"TROUGH_WIDTH", s.trough_width},
      {"BAFFLE_POSITION", s.baffle_position},
      {"BAFFLE_THICKNESS", s.baffle_thickness},
      {"BAFFLE_SPEED", s.baffle_speed},
      {"BAFFLE_CLEAR_TIME", s.baffle_clear_time},
      {"CLEAR_GAP", clear_gap},
      {"FRICTION", s.friction},
      {"WALL_FRICTION", s.wall_friction},
      {"GRAVITY", s.gravity},
      {"DAMPING", s.damping},
      {"TIME_STEP", s.time_step},
      {"KINETIC_ENERGY_RATIO", s.kinetic_energy_ratio},
      {"QUIET_TIME", s.quiet_time},
      {"CHECK_INTERVAL", s.check_interval},
      {"STAGE1_MIN_TIME", s.stage1_min_time},
      {"MIN_TIME", s.min_time},
      {"MAX_TIME", s.max_time},
      {"CONFIRM_WINDOW", s.confirm_window},
      {"CONFIRM_SPEED", s.confirm_speed},
      {"FIT_LOWER", s.fit_lower},
      {"PROGRESS_SECONDS", s.progress_seconds},
      {"TOTAL_MASS", mass},
      {"MEDIAN_SIZE", median},
  };
  for (const auto& [name, value] : constants) text += std::string(name) + " = " + py(value) + "\n";
  text += "RESULT_FILE = '" + s.result_file + "'\n\n";
  // Particles and walls: YADE takes the smaller friction angle of a contact's two materials, so
  // the walls get their own material.
  text +=
      "material.frictionAngle = math.atan(FRICTION)\n"
      "wall_material = PolyhedraMat(label='WALL', density=material.density, "
      "young=material.young, poisson=material.poisson, frictionAngle=math.atan(WALL_FRICTION))\n"
      "O.materials.append(wall_material)\n"
      "particle_ids = [b.id for b in O.bodies]\n";
  text += detail::yade_walls({.floor = 0.0,
                              .y0 = 0.0,
                              .y1 = s.trough_width,
                              .x0 = 0.0,
                              .x1 = s.trough_length,
                              .baffle = s.baffle_position},
                             "wall_material", py);
  text += detail::yade_time_step_function();
  text +=
      "O.dt = TIME_STEP if TIME_STEP > 0 else stiffness_time_step()\n"
      "CHECK_STEPS = max(1, int(round(CHECK_INTERVAL / O.dt)))\n";
  text += detail::yade_engines(
      "    PyRunner(iterPeriod=CHECK_STEPS, command='control()'),\n"
      "    PyRunner(realPeriod=PROGRESS_SECONDS, command='report()'),\n",
      "DAMPING");
  out << text << kControl;
}

}  // namespace aggpack
