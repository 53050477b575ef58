// The YADE trough shared by the deck and the repose engine's script (deck_yade_common.h).

#include "deck_yade_common.h"

namespace aggpack::detail {

std::string yade_walls(const YadeTroughPlanes& p, const std::string& material,
                       std::string (*number)(double)) {
  const auto wall = [&](double at, int axis) {
    return "utils.wall(" + number(at) + ", axis=" + std::to_string(axis) +
           ", material=" + material + ")";
  };
  return "walls = [\n    " + wall(p.floor, 2) + ",  # floor\n    " + wall(p.y0, 1) +
         ",  # side wall y0\n    " + wall(p.y1, 1) + ",  # side wall y1\n    " + wall(p.x0, 0) +
         ",  # end wall x0\n    " + wall(p.x1, 0) +
         ",  # end wall x1\n]\nbaffle = " + wall(p.baffle, 0) +
         "\nO.bodies.append(walls + [baffle])\n\n";
}

std::string yade_engines(const std::string& runners, const std::string& damping) {
  return "O.engines = [\n"
         "    ForceResetter(),\n"
         "    InsertionSortCollider([Bo1_Polyhedra_Aabb(), Bo1_Wall_Aabb()]),\n"
         "    InteractionLoop(\n"
         "        [Ig2_Polyhedra_Polyhedra_PolyhedraGeom(), Ig2_Wall_Polyhedra_PolyhedraGeom()],\n"
         "        [Ip2_PolyhedraMat_PolyhedraMat_PolyhedraPhys()],\n"
         "        [Law2_PolyhedraGeom_PolyhedraPhys_Volumetric()],\n"
         "    ),\n" +
         runners + "    NewtonIntegrator(damping=" + damping +
         ", gravity=(0, 0, -GRAVITY)),\n"
         "]\n";
}

std::string yade_time_step_function() {
  return "def stiffness_time_step():\n"
         "    # YADE's PWaveTimeStep only knows spheres. The volumetric law pushes back with "
         "about\n"
         "    # young x overlap volume, i.e. a stiffness young x pi r^2 against a particle of mass "
         "m\n"
         "    # and equivalent radius r: a fifth of sqrt(m / stiffness), the smallest over "
         "particles.\n"
         "    step = float('inf')\n"
         "    for i in particle_ids:\n"
         "        b = O.bodies[i]\n"
         "        r = (3.0 * b.state.mass / (4.0 * math.pi * material.density)) ** (1.0 / 3.0)\n"
         "        step = min(step, 0.2 * math.sqrt(b.state.mass / (material.young * math.pi * r * "
         "r)))\n"
         "    return step\n\n";
}

}  // namespace aggpack::detail
