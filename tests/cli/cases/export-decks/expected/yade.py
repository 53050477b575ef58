# aggpack 0.1.0 YADE deck: the paper's trough test (angle of repose) with 2
#     particles.
# Run: yade -n -x <this file> (or yade <this file> for the GUI)
# ASSUMPTIONS (change them here or with the export options named in brackets):
# - Units: SI (m, kg, s, N, Pa); lengths, gravity and speeds times the export
#     scale 1 [--scale]. Density and modulus are written as given: convert
#   them yourself when the scale is not 1 (mm: t/mm^3 and MPa).
# - Particles: elastic, material AGGREGATE, density 2700, Young's modulus 5e+10,
#     Poisson's ratio 0.2 [--density --youngs-modulus --poisson-ratio].
# - Contact: Coulomb friction mu_s = 0.5 between particles and between particles
#     and walls, penalty normal contact [--friction].
# - Gravity 9.81 along -z [--gravity].
# - Trough: x 0 .. 0.4, y 0 .. 0.1, floor z = 0, walls up to z = 0.1; floor and
#     walls rigid and fixed [--trough-length].
# - Baffle: the plane x = 0.2 across the trough, rigid, particles behind it
#     [--baffle-position].
# - Step SETTLE, 0.285569 s: the particles fall and settle, the baffle stands
#     still [--settle-time].
# - Step BAFFLE, 0.4 s: the baffle moves toward +x at 0.5 to the trough end
#     (0.2) [--baffle-speed].
# - Step REST, 1 s: the pile comes to rest [--rest-time]. End time 1.68557 s.
# YOU MAY WANT TO CHANGE: the friction (the paper sweeps mu_s 0.05 .. 1.0); the
#     settle time (the pile must be at rest before the baffle moves); a softer
#     modulus or mass scaling (rock stiffness makes explicit time increments
#     tiny); the output intervals. Then measure the angle of repose from the
#     final pile's side view (aggpack repose does it for its own simulation).
# YADE: PolyhedraMat.young is the stiffness of YADE's volumetric polyhedra
#     contact law (force per overlap volume, N/m^3), not the rock's modulus:
#     YADE's examples use 1e7 .. 1e8; a large value needs a tiny time step. The
#     time step is 0.2 sqrt(m / (young pi r^2)) of the lightest particle (mass
#     m, equivalent radius r) [--time-step]; NewtonIntegrator damping 0.3
#     (YADE's usual numerical damping) dissipates energy besides friction.
# YADE: floor and walls are utils.wall planes; the baffle is a wall plane moved
#     at the baffle speed by a PyRunner during step BAFFLE.
# aggpack 0.1.0 packing, 2 particles, rebuilt as YADE polyhedra.
# Run with: yade this_file.py
# Coordinates in metres times 1.
from yade import polyhedra_utils

material = PolyhedraMat(label='AGGREGATE', density=2700, young=5e+10, poisson=0.2)
O.materials.append(material)

# One entry per particle (particle i+1 of the packing): its vertices in world coordinates.
particles = [
    [(0.09397180223966836, 0.05, 0.05), (0.009741850568423992, 0.05, 0.05), (0.05, 0.09264141851182406, 0.05), (0.05, 0.014713919520544731, 0.05), (0.05, 0.05, 0.0817325825278918), (0.05, 0.05, 0.008981324424755799)],
    [(0.1893833629358485, 0.05, 0.05), (0.10237137738858955, 0.05, 0.05), (0.15000000000000002, 0.09212035409042968, 0.05), (0.15000000000000002, 0.009774600432955166, 0.05), (0.15000000000000002, 0.05, 0.08456607274137265), (0.15000000000000002, 0.05, 0.0044399299873950845)],
]

for vertices in particles:
    O.bodies.append(polyhedra_utils.polyhedra(material, v=vertices))

# ---- The trough test (aggpack deck) ----
import math
from yade import utils

FRICTION = 0.5
GRAVITY = 9.81
SETTLE_TIME = 0.2855686245854129
BAFFLE_TIME = 0.4
REST_TIME = 1
BAFFLE_SPEED = 0.5
TROUGH_END = 0.4
TIME_STEP = 0  # 0: stiffness_time_step()

material.frictionAngle = math.atan(FRICTION)
particle_ids = [b.id for b in O.bodies]
walls = [
    utils.wall(0, axis=2, material=material),  # floor
    utils.wall(0, axis=1, material=material),  # side wall y0
    utils.wall(0.1, axis=1, material=material),  # side wall y1
    utils.wall(0, axis=0, material=material),  # end wall x0
    utils.wall(0.4, axis=0, material=material),  # end wall x1
]
baffle = utils.wall(0.2, axis=0, material=material)
O.bodies.append(walls + [baffle])

def move_baffle():
    # Still in SETTLE, toward +x in BAFFLE (until the trough end), still again in REST.
    moving = SETTLE_TIME <= O.time < SETTLE_TIME + BAFFLE_TIME and baffle.state.pos[0] < TROUGH_END
    baffle.state.vel = Vector3(BAFFLE_SPEED if moving else 0.0, 0.0, 0.0)

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Polyhedra_Polyhedra_PolyhedraGeom(), Ig2_Wall_Polyhedra_PolyhedraGeom()],
        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],
        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()],
    ),
    PyRunner(iterPeriod=1, command='move_baffle()'),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -GRAVITY)),
]
def stiffness_time_step():
    # YADE's PWaveTimeStep only knows spheres. The volumetric law pushes back with about
    # young x overlap volume, i.e. a stiffness young x pi r^2 against a particle of mass m
    # and equivalent radius r: a fifth of sqrt(m / stiffness), the smallest over particles.
    step = float('inf')
    for i in particle_ids:
        b = O.bodies[i]
        r = (3.0 * b.state.mass / (4.0 * math.pi * material.density)) ** (1.0 / 3.0)
        step = min(step, 0.2 * math.sqrt(b.state.mass / (material.young * math.pi * r * r)))
    return step

O.dt = TIME_STEP if TIME_STEP > 0 else stiffness_time_step()

def mean_height():
    return sum(O.bodies[i].state.pos[2] for i in particle_ids) / max(1, len(particle_ids))

start_height = mean_height()
steps = int(math.ceil((SETTLE_TIME + BAFFLE_TIME + REST_TIME) / O.dt))
print('aggpack-yade: running %d steps of %g s' % (steps, O.dt))
O.run(steps, True)
speed = max(O.bodies[i].state.vel.norm() for i in particle_ids) if particle_ids else 0.0
print('aggpack-yade: particles %d bodies %d iterations %d time %.9g mean_z_start %.9g mean_z_end %.9g max_speed %.9g baffle_x %.9g' % (len(particle_ids), len(O.bodies), O.iter, O.time, start_height, mean_height(), speed, baffle.state.pos[0]))
