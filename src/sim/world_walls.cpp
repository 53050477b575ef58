// World: the container's static walls (from the container kind) and the user's wall boxes.
#include <string>
#include <utility>

#include "aggpack/core/error.h"
#include "world_impl.h"

namespace aggpack {

using detail::from_bt;
using detail::to_bt;

std::size_t World::Impl::add_wall(const WallBox& box) {
  if (box.box.is_empty() || !((box.box.upper - box.box.lower).array() > 0.0).all()) {
    throw InvalidInput("wall box", "empty", "lower < upper on every axis");
  }
  return add_wall(ContainerWall::from_box(box.box), box.is_kinematic);
}

std::size_t World::Impl::add_wall(const ContainerWall& box, bool is_kinematic) {
  detail::Wall wall;
  wall.is_kinematic = is_kinematic;
  wall.half_extent = box.half_extent;
  wall.shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
  wall.shape->setMargin(margin);  // a box's margin lies inside its faces
  wall.shape->initializePolyhedralFeatures();
  wall.exact_shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
  wall.exact_shape->setMargin(0.0);
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(to_bt(scale * box.centre));
  if (box.angle != 0.0) transform.setRotation(btQuaternion(btVector3(0, 0, 1), box.angle));
  wall.motion = std::make_unique<btDefaultMotionState>(transform);
  btRigidBody::btRigidBodyConstructionInfo construction(0.0, wall.motion.get(), wall.shape.get());
  construction.m_friction = wall_friction();
  construction.m_restitution = options.restitution;
  wall.body = std::make_unique<btRigidBody>(construction);
  if (wall.is_kinematic) {
    wall.body->setCollisionFlags(wall.body->getCollisionFlags() |
                                 btCollisionObject::CF_KINEMATIC_OBJECT);
    wall.body->setActivationState(DISABLE_DEACTIVATION);
  }
  wall.body->setUserIndex(-1 - static_cast<int>(walls.size()));
  wall.body->setUserPointer(this);
  world->addRigidBody(wall.body.get());
  walls.push_back(std::move(wall));
  return walls.size() - 1;
}

void World::Impl::add_container_walls(double wall_height) {
  for (const ContainerWall& wall :
       container_walls(packing.container, wall_thickness, wall_height)) {
    add_wall(wall, false);
  }
}

std::size_t World::add_wall(const WallBox& wall) { return impl_->add_wall(wall); }

void World::set_wall_velocity(std::size_t wall, const Vec3& velocity) {
  if (wall >= impl_->walls.size() || !impl_->walls[wall].is_kinematic) {
    throw InvalidInput("wall", std::to_string(wall), "a kinematic wall id");
  }
  impl_->walls[wall].velocity = velocity;
}

void World::remove_wall(std::size_t wall) {
  if (wall >= impl_->walls.size() || impl_->walls[wall].is_removed) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  impl_->world->removeRigidBody(impl_->walls[wall].body.get());
  impl_->walls[wall].is_removed = true;
}

Aabb World::wall_box(std::size_t wall) const {
  if (wall >= impl_->walls.size()) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  const auto& w = impl_->walls[wall];
  const Vec3 centre = from_bt(w.body->getWorldTransform().getOrigin()) / impl_->scale;
  return {centre - w.half_extent, centre + w.half_extent};
}

bool World::is_wall_touched(std::size_t wall, double gap) const {
  if (wall >= impl_->walls.size()) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  const auto* body = impl_->walls[wall].body.get();
  auto* dispatcher = impl_->dispatcher.get();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    if (manifold->getBody0() != body && manifold->getBody1() != body) continue;
    for (int c = 0; c < manifold->getNumContacts(); ++c) {
      if (manifold->getContactPoint(c).getDistance() <= gap * impl_->scale) return true;
    }
  }
  return false;
}

}  // namespace aggpack
