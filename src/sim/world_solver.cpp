// The cache-blocked velocity sweeps of OrderedSolver (world_impl.h; PhysicsOptions::solver).
//
// Bullet's sequential-impulse solver sweeps every velocity row (a normal row and two friction rows
// per contact point) solver_iterations times per step, each sweep over all rows. At 10,000
// particles the rows and solver bodies (~30 MB in double precision) exceed the last-level cache, so
// every sweep streams them from memory (bench/RESULTS.md, "Physics speed"). Here the sweeps are
// regrouped: the contacts, in the solver's canonical order (manifolds sorted by the particles they
// join, so a block holds contacts of neighbouring particles), are cut into blocks; a pass sweeps
// each block block_sweeps times before the next block, and passes repeat until every row has been
// swept solver_iterations times. Within a sweep of a block the order is Bullet's: normal rows,
// then the friction rows (limits from the normal impulse), then rolling-friction rows.
//
// Every row still gets the same number of projected Gauss-Seidel updates, but impulses travel
// between blocks only once per pass: a block converges its local forces against the current
// state of its neighbours, and the global passes (warm started from the previous step's impulses)
// carry the forces through the pile. With one block it is Bullet's Gauss-Seidel, bit for bit.
// The split-impulse (position) sweeps over the normal rows are blocked the same way. Bullet stops
// sweeping when a sweep changes nothing (its residual threshold is 0); here a pass over all blocks
// that changes nothing stops the sweeps, which changes nothing either.

#include <algorithm>

#include "world_impl.h"

namespace aggpack::detail {

bool OrderedSolver::split_block(int begin, int end) {
  bool is_changed = false;
  for (int c = begin; c < end; ++c) {
    const btSolverConstraint& row = m_tmpSolverContactConstraintPool[m_orderTmpConstraintPool[c]];
    const btScalar residual = resolveSplitPenetrationImpulse(
        m_tmpSolverBodyPool[row.m_solverBodyIdA], m_tmpSolverBodyPool[row.m_solverBodyIdB], row);
    is_changed = is_changed || residual != btScalar(0);
  }
  return is_changed;
}

void OrderedSolver::sweep_block(int begin, int end) {
  btConstraintArray& normal = m_tmpSolverContactConstraintPool;
  btConstraintArray& friction = m_tmpSolverContactFrictionConstraintPool;
  btConstraintArray& rolling = m_tmpSolverContactRollingFrictionConstraintPool;
  for (int c = begin; c < end; ++c) {
    const btSolverConstraint& row = normal[m_orderTmpConstraintPool[c]];
    resolveSingleConstraintRowLowerLimit(m_tmpSolverBodyPool[row.m_solverBodyIdA],
                                         m_tmpSolverBodyPool[row.m_solverBodyIdB], row);
  }
  // The friction rows of contacts [begin, end) are contiguous: contact c owns the rows from its
  // m_frictionIndex to the next contact's.
  const int friction_begin = normal[begin].m_frictionIndex;
  const int friction_end = end < normal.size() ? normal[end].m_frictionIndex : friction.size();
  for (int j = friction_begin; j < friction_end; ++j) {
    btSolverConstraint& row = friction[m_orderFrictionConstraintPool[j]];
    const btScalar total = normal[row.m_frictionIndex].m_appliedImpulse;
    if (total > btScalar(0)) {
      row.m_lowerLimit = -(row.m_friction * total);
      row.m_upperLimit = row.m_friction * total;
      resolveSingleConstraintRowGeneric(m_tmpSolverBodyPool[row.m_solverBodyIdA],
                                        m_tmpSolverBodyPool[row.m_solverBodyIdB], row);
    }
  }
  for (int j = rolling_begin_[begin]; j < rolling_begin_[end]; ++j) {
    btSolverConstraint& row = rolling[j];
    const btScalar total = normal[row.m_frictionIndex].m_appliedImpulse;
    if (total > btScalar(0)) {
      btScalar magnitude = row.m_friction * total;
      if (magnitude > row.m_friction) magnitude = row.m_friction;
      row.m_lowerLimit = -magnitude;
      row.m_upperLimit = magnitude;
      resolveSingleConstraintRowGeneric(m_tmpSolverBodyPool[row.m_solverBodyIdA],
                                        m_tmpSolverBodyPool[row.m_solverBodyIdB], row);
    }
  }
}

btScalar OrderedSolver::solveGroupCacheFriendlyIterations(
    btCollisionObject** bodies, int body_count, btPersistentManifold** manifolds,
    int manifold_count, btTypedConstraint** constraints, int constraint_count,
    const btContactSolverInfo& info, btIDebugDraw* debug) {
  const int contacts = m_tmpSolverContactConstraintPool.size();
  // Joints, randomised or interleaved orders are never used by World: leave them to Bullet.
  const bool is_plain =
      constraint_count == 0 && m_tmpSolverNonContactConstraintPool.size() == 0 &&
      (info.m_solverMode &
       (SOLVER_RANDMIZE_ORDER | SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS)) == 0;
  if (block_contacts_ <= 0 || !is_plain || contacts == 0) {
    return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
        bodies, body_count, manifolds, manifold_count, constraints, constraint_count, info, debug);
  }
  const int iterations = info.m_numIterations;
  if (info.m_splitImpulse != 0) {
    bool is_changed = true;
    for (int done = 0; done < iterations && is_changed;) {
      const int sweeps = std::min(block_sweeps_, iterations - done);
      is_changed = false;
      for (int begin = 0; begin < contacts; begin += block_contacts_) {
        const int end = std::min(contacts, begin + block_contacts_);
        for (int s = 0; s < sweeps; ++s) is_changed = split_block(begin, end) || is_changed;
      }
      done += sweeps;
    }
  }

  // Rolling-friction rows are appended contact by contact: rolling_begin_[c] is the first row of
  // contact c (and of every later contact), rolling_begin_[contacts] the pool's end.
  const btConstraintArray& rolling = m_tmpSolverContactRollingFrictionConstraintPool;
  rolling_begin_.assign(static_cast<std::size_t>(contacts) + 1, rolling.size());
  for (int j = rolling.size() - 1; j >= 0; --j) rolling_begin_[rolling[j].m_frictionIndex] = j;
  for (int c = contacts - 1; c >= 0; --c) {
    rolling_begin_[c] = std::min(rolling_begin_[c], rolling_begin_[c + 1]);
  }

  for (int done = 0; done < iterations;) {
    const int sweeps = std::min(block_sweeps_, iterations - done);
    for (int begin = 0; begin < contacts; begin += block_contacts_) {
      const int end = std::min(contacts, begin + block_contacts_);
      for (int s = 0; s < sweeps; ++s) sweep_block(begin, end);
    }
    done += sweeps;
  }
  return 0.0;
}

}  // namespace aggpack::detail
