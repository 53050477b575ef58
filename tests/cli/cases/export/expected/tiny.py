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
