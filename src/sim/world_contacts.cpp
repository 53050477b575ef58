// World: the broad-phase filter that skips pairs which cannot touch, and the contact and overlap
// statistics of the current state.
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <algorithm>
#include <cmath>

#include "world_impl.h"

namespace aggpack {

namespace {

// Extent of a particle's collision body (hull + margin) along the world direction `axis`,
// measured from its centre of mass.
double support_extent(const btCollisionObject& body, const btVector3& axis) {
  const auto* hull = static_cast<const btConvexHullShape*>(body.getCollisionShape());
  const btVector3 local = axis * body.getWorldTransform().getBasis();  // R^T axis
  return hull->localGetSupportVertexWithoutMarginNonVirtual(local).dot(local) + hull->getMargin();
}

}  // namespace

// Bullet's broad phase pairs bodies whose (rotation-inflated) AABBs overlap: about 24 pairs per
// particle in a pile, each costing two GJK runs per step (Bullet 3.24 runs a libccd intersection
// test and then its own GJK, both from a fixed start axis: ~14,000 instructions a pair), although
// only ~3 per particle touch. Two cheap tests skip the pairs that cannot make a contact point:
//  1. bounding spheres (sphere against sphere, or against the wall box);
//  2. a separating axis: the line between the two centres for two particles, the wall's face
//     normal for a particle and a wall. If the two bodies' extents along it (support mapping of
//     the hull + margin, ~300 instructions each) leave a gap wider than Bullet's contact breaking
//     threshold, Bullet's narrow phase would add no point and drop every point it keeps.
// A skipped pair's manifold is cleared so that no stale contact point survives.
void World::Impl::near_callback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher,
                                const btDispatcherInfo& info) {
  const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
  const auto* impl = static_cast<const Impl*>(a->getUserPointer());
  const int index_a = a->getUserIndex();
  const int index_b = b->getUserIndex();
  bool is_far = false;
  if (impl != nullptr && (index_a >= 0 || index_b >= 0)) {
    if (index_a >= 0 && index_b >= 0) {
      const double reach = kPairReach * (impl->bounding_radius[static_cast<std::size_t>(index_a)] +
                                         impl->bounding_radius[static_cast<std::size_t>(index_b)]);
      const btVector3 between =
          b->getWorldTransform().getOrigin() - a->getWorldTransform().getOrigin();
      const double distance2 = between.length2();
      is_far = distance2 > reach * reach;
      if (!is_far && distance2 > 0.0) {
        const btVector3 axis = between / std::sqrt(distance2);
        const double gap = axis.dot(between) - support_extent(*a, axis) - support_extent(*b, -axis);
        is_far = gap > impl->breaking_threshold;
      }
    } else {
      const auto* particle = index_a >= 0 ? a : b;
      const auto* wall = index_a >= 0 ? b : a;
      const auto* box = static_cast<const btBoxShape*>(wall->getCollisionShape());
      const btVector3 local =
          wall->getWorldTransform().invXform(particle->getWorldTransform().getOrigin());
      const btVector3 half = box->getHalfExtentsWithMargin();
      btVector3 outside(0, 0, 0);
      for (int axis = 0; axis < 3; ++axis) {
        outside[axis] = std::max(btScalar(0), btFabs(local[axis]) - half[axis]);
      }
      const double reach =
          kPairReach * impl->bounding_radius[static_cast<std::size_t>(particle->getUserIndex())];
      is_far = outside.length2() > reach * reach;
      // Separating axis: the normal of the box face the centre lies beyond.
      for (int axis = 0; axis < 3 && !is_far; ++axis) {
        if (!(outside[axis] > 0.0)) continue;
        btVector3 normal = wall->getWorldTransform().getBasis().getColumn(axis);
        if (local[axis] < 0.0) normal = -normal;
        is_far = outside[axis] - support_extent(*particle, -normal) > impl->breaking_threshold;
      }
    }
  }
  if (!is_far) {
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
    return;
  }
  if (pair.m_algorithm != nullptr) {
    btManifoldArray manifolds;
    pair.m_algorithm->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) manifolds[m]->clearManifold();
  }
}

ContactStatistics World::contact_statistics() const {
  ContactStatistics stats;
  auto* dispatcher = impl_->dispatcher.get();
  double deepest = 0.0;
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    for (int c = 0; c < manifold->getNumContacts(); ++c) {
      const double distance = manifold->getContactPoint(c).getDistance();
      if (distance <= 0.0) {
        ++stats.contact_count;
        deepest = std::max(deepest, -distance);
      }
    }
  }
  stats.max_contact_penetration = deepest / impl_->scale;
  return stats;
}

OverlapStatistics World::overlap_statistics() const {
  const auto& impl = *impl_;
  OverlapStatistics stats;
  auto& pairs = impl.world->getPairCache()->getOverlappingPairArray();
  double deepest = 0.0;
  for (int p = 0; p < pairs.size(); ++p) {
    const auto* a = static_cast<const btCollisionObject*>(pairs[p].m_pProxy0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(pairs[p].m_pProxy1->m_clientObject);
    const int index_a = a->getUserIndex();
    const int index_b = b->getUserIndex();
    if (index_a < 0 && index_b < 0) continue;  // wall-wall
    if (index_a >= 0 && index_b >= 0) {
      // Whether the exact polyhedra intersect is decided by aggpack's own GJK; Bullet's EPA (on
      // the unshrunk hulls, margin 0) only measures how deep.
      const auto& shape_a = impl.shapes[impl.body_shape[static_cast<std::size_t>(index_a)]];
      const auto& shape_b = impl.shapes[impl.body_shape[static_cast<std::size_t>(index_b)]];
      if (!gjk_distance(shape_a.exact, pose(static_cast<std::size_t>(index_a)), shape_b.exact,
                        pose(static_cast<std::size_t>(index_b)))
               .is_intersecting) {
        continue;
      }
      ++stats.overlapping_pairs;
    }
    auto exact_hull = [&impl](int index) -> const btConvexShape* {
      if (index >= 0) {
        return impl.shapes[impl.body_shape[static_cast<std::size_t>(index)]].exact_hull.get();
      }
      return impl.walls[static_cast<std::size_t>(-1 - index)].exact_shape.get();
    };
    btGjkEpaSolver2::sResults result;
    const btVector3 guess = b->getWorldTransform().getOrigin() - a->getWorldTransform().getOrigin();
    if (btGjkEpaSolver2::Penetration(exact_hull(index_a), a->getWorldTransform(),
                                     exact_hull(index_b), b->getWorldTransform(), guess, result,
                                     false)) {
      deepest = std::max(deepest, static_cast<double>(-result.distance));
    }
  }
  stats.max_depth = deepest / impl.scale;
  stats.max_depth_fraction = stats.max_depth / impl.smallest_size;
  return stats;
}

}  // namespace aggpack
