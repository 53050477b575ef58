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
#include <cmath>

#include "world_impl.h"

namespace aggpack::detail {

// Bullet's Gauss-Seidel sweeps on compact rows (OrderedSolver::compact_sweeps).
//
// Bullet 3.24 (double precision, scalar code) sweeps btSolverConstraint rows of 288 bytes that
// point into btSolverBody records of 488 bytes, through a function pointer per row, and computes
// a residual with a division per row. The sweeps below do the same arithmetic in the same order
// (so the results are bit-identical: tests/sim/world_solver_test.cpp runs both) on copies holding
// only what a row update touches. Two facts make the copies smaller than Bullet's and exact:
//  - Bullet's contactNormal2 is -contactNormal1 (negation is exact), except in a row against the
//    fixed body (static walls), where the fixed side's normal, relpos x normal and angular
//    component are all zero. There the stored normal is the other side's (negated), and the fixed
//    side's term is still +0: its velocities are +0, so n.v is +-0, and adding
//    relpos x normal . w = +0 gives +0, as Bullet's zero normal does.
//  - A body's linear and angular factors are 1 (checked), so Bullet's multiplications by them are
//    exact no-ops; the fixed body (no original body, whose impulses Bullet skips) has zero inverse
//    mass and zero angular components (checked), so applying its impulses adds +-0 to +0: no-op.
namespace {

inline btScalar dot(const btScalar* a, const btScalar* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline btScalar dot_negated(const btScalar* a, const btScalar* b) {
  return -a[0] * b[0] + -a[1] * b[1] + -a[2] * b[2];
}

inline void copy3(const btVector3& v, btScalar* out) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

inline bool is_one(const btVector3& v) { return v.x() == 1.0 && v.y() == 1.0 && v.z() == 1.0; }
inline bool is_zero(const btVector3& v) { return v.x() == 0.0 && v.y() == 0.0 && v.z() == 0.0; }

// Applies `delta` along the row to both bodies (btSolverBody::internalApplyImpulse).
inline void apply(const SweepRow& row, SweepBody& a, SweepBody& b, btScalar delta) {
  for (int k = 0; k < 3; ++k) {
    a.linear[k] += row.normal[k] * a.inv_mass[k] * delta;
    a.angular[k] += row.angular_a[k] * delta;
    b.linear[k] += -row.normal[k] * b.inv_mass[k] * delta;
    b.angular[k] += row.angular_b[k] * delta;
  }
}

// Bullet's gResolveSingleConstraintRowLowerLimit / Generic_scalar_reference (HasUpper), and
// gResolveSplitPenetrationImpulse_scalar_reference with `applied` the push impulse and `rhs` the
// penetration's.
template <bool HasUpper>
inline btScalar solve_row(const SweepRow& row, btScalar rhs, btScalar& applied, SweepBody& a,
                          SweepBody& b, btScalar lower, btScalar upper) {
  btScalar delta = rhs - applied * row.cfm;
  const btScalar velocity_a = dot(row.normal, a.linear) + dot(row.relpos1_cross_normal, a.angular);
  const btScalar velocity_b =
      dot_negated(row.normal, b.linear) + dot(row.relpos2_cross_normal, b.angular);
  delta -= velocity_a * row.jac_diag_inv;
  delta -= velocity_b * row.jac_diag_inv;
  const btScalar sum = applied + delta;
  if (sum < lower) {
    delta = lower - applied;
    applied = lower;
  } else if (HasUpper && sum > upper) {
    delta = upper - applied;
    applied = upper;
  } else {
    applied = sum;
  }
  apply(row, a, b, delta);
  return delta * (1. / row.jac_diag_inv);
}

// Bullet's residual bookkeeping: leastSquaresResidual = btMax(leastSquaresResidual, r * r).
inline btScalar max_residual(btScalar largest, btScalar residual) {
  const btScalar square = residual * residual;
  return largest > square ? largest : square;
}

}  // namespace

bool OrderedSolver::load_compact() {
  const int body_count = m_tmpSolverBodyPool.size();
  sweep_bodies_.resize(static_cast<std::size_t>(body_count));
  for (int i = 0; i < body_count; ++i) {
    const btSolverBody& body = m_tmpSolverBodyPool[i];
    if (body.m_originalBody != nullptr) {
      if (!is_one(body.m_linearFactor) || !is_one(body.m_angularFactor)) return false;
    } else if (!is_zero(body.m_invMass)) {
      return false;
    }
    copy3(body.m_invMass, sweep_bodies_[static_cast<std::size_t>(i)].inv_mass);
  }
  auto load_row = [this](const btSolverConstraint& from, bool is_friction, SweepRow& row) {
    const bool is_fixed_a = m_tmpSolverBodyPool[from.m_solverBodyIdA].m_originalBody == nullptr;
    const bool is_fixed_b = m_tmpSolverBodyPool[from.m_solverBodyIdB].m_originalBody == nullptr;
    // A fixed side has a zero normal, relpos x normal and angular component (see above); else
    // normal 2 is normal 1 negated.
    if (is_fixed_a && is_fixed_b) return false;
    if (is_fixed_a) {
      if (!is_zero(from.m_contactNormal1) || !is_zero(from.m_relpos1CrossNormal) ||
          !is_zero(from.m_angularComponentA)) {
        return false;
      }
      copy3(-from.m_contactNormal2, row.normal);
    } else {
      if (is_fixed_b ? !is_zero(from.m_contactNormal2) || !is_zero(from.m_relpos2CrossNormal) ||
                           !is_zero(from.m_angularComponentB)
                     : !(from.m_contactNormal2 == -from.m_contactNormal1)) {
        return false;
      }
      copy3(from.m_contactNormal1, row.normal);
    }
    copy3(from.m_relpos1CrossNormal, row.relpos1_cross_normal);
    copy3(from.m_relpos2CrossNormal, row.relpos2_cross_normal);
    copy3(from.m_angularComponentA, row.angular_a);
    copy3(from.m_angularComponentB, row.angular_b);
    row.rhs = from.m_rhs;
    row.cfm = from.m_cfm;
    row.jac_diag_inv = from.m_jacDiagABInv;
    row.applied = from.m_appliedImpulse;
    row.limit = is_friction ? from.m_friction : from.m_lowerLimit;
    row.body_a = from.m_solverBodyIdA;
    row.body_b = from.m_solverBodyIdB;
    row.normal_row = -1;
    return true;
  };
  const int contacts = m_tmpSolverContactConstraintPool.size();
  contact_rows_.resize(static_cast<std::size_t>(contacts));
  rhs_penetration_.resize(static_cast<std::size_t>(contacts));
  push_applied_.resize(static_cast<std::size_t>(contacts));
  std::vector<int>& position = contact_position_;
  position.assign(static_cast<std::size_t>(contacts), -1);
  for (int j = 0; j < contacts; ++j) {
    const int index = m_orderTmpConstraintPool[j];
    const btSolverConstraint& from = m_tmpSolverContactConstraintPool[index];
    const auto slot = static_cast<std::size_t>(j);
    if (!load_row(from, false, contact_rows_[slot])) return false;
    rhs_penetration_[slot] = from.m_rhsPenetration;
    push_applied_[slot] = from.m_appliedPushImpulse;
    position[static_cast<std::size_t>(index)] = j;
  }
  const int frictions = m_tmpSolverContactFrictionConstraintPool.size();
  friction_rows_.resize(static_cast<std::size_t>(frictions));
  for (int j = 0; j < frictions; ++j) {
    const btSolverConstraint& from =
        m_tmpSolverContactFrictionConstraintPool[m_orderFrictionConstraintPool[j]];
    SweepRow& row = friction_rows_[static_cast<std::size_t>(j)];
    if (!load_row(from, true, row)) return false;
    if (from.m_frictionIndex < 0 || from.m_frictionIndex >= contacts) return false;
    row.normal_row = position[static_cast<std::size_t>(from.m_frictionIndex)];
  }
  return true;
}

void OrderedSolver::store_compact() {
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    btSolverConstraint& to = m_tmpSolverContactConstraintPool[m_orderTmpConstraintPool[j]];
    to.m_appliedImpulse = contact_rows_[static_cast<std::size_t>(j)].applied;
    to.m_appliedPushImpulse = push_applied_[static_cast<std::size_t>(j)];
  }
  for (int j = 0; j < m_tmpSolverContactFrictionConstraintPool.size(); ++j) {
    m_tmpSolverContactFrictionConstraintPool[m_orderFrictionConstraintPool[j]].m_appliedImpulse =
        friction_rows_[static_cast<std::size_t>(j)].applied;
  }
}

bool OrderedSolver::compact_sweeps(const btContactSolverInfo& info) {
  if (m_tmpSolverContactRollingFrictionConstraintPool.size() != 0 ||
      m_maxOverrideNumSolverIterations > info.m_numIterations || !load_compact()) {
    return false;
  }
  const int contacts = static_cast<int>(contact_rows_.size());
  const int body_count = static_cast<int>(sweep_bodies_.size());
  const btScalar threshold = info.m_leastSquaresResidualThreshold;
  // Split-impulse sweeps on the push and turn velocities
  // (solveGroupCacheFriendlySplitImpulseIterations).
  if (info.m_splitImpulse != 0) {
    for (int i = 0; i < body_count; ++i) {
      const btSolverBody& from = m_tmpSolverBodyPool[i];
      copy3(from.m_pushVelocity, sweep_bodies_[static_cast<std::size_t>(i)].linear);
      copy3(from.m_turnVelocity, sweep_bodies_[static_cast<std::size_t>(i)].angular);
    }
    // A row without penetration changes nothing and its residual is 0 * (1 / jacDiagABInv) = +-0,
    // which leaves Bullet's running maximum (>= +0) as it is: only the other rows are swept. (A
    // row whose 1 / jacDiagABInv is not finite would make it NaN: then every row is swept.)
    split_rows_.clear();
    bool is_finite = true;
    for (int j = 0; j < contacts; ++j) {
      const auto slot = static_cast<std::size_t>(j);
      if (rhs_penetration_[slot] != 0.0) {
        split_rows_.push_back(j);
      } else {
        is_finite = is_finite && std::isfinite(1. / contact_rows_[slot].jac_diag_inv);
      }
    }
    if (!is_finite) {
      split_rows_.resize(static_cast<std::size_t>(contacts));
      for (int j = 0; j < contacts; ++j) split_rows_[static_cast<std::size_t>(j)] = j;
    }
    for (int iteration = 0; iteration < info.m_numIterations; ++iteration) {
      btScalar largest = 0.0;
      for (const int j : split_rows_) {
        const auto slot = static_cast<std::size_t>(j);
        const SweepRow& row = contact_rows_[slot];
        btScalar residual = 0.0;
        if (rhs_penetration_[slot] != 0.0) {
          residual =
              solve_row<false>(row, rhs_penetration_[slot], push_applied_[slot],
                               sweep_bodies_[static_cast<std::size_t>(row.body_a)],
                               sweep_bodies_[static_cast<std::size_t>(row.body_b)], row.limit, 0.0);
        } else {
          residual = btScalar(0.0) * (1. / row.jac_diag_inv);
        }
        largest = max_residual(largest, residual);
      }
      if (largest <= threshold || iteration >= info.m_numIterations - 1) break;
    }
    for (int i = 0; i < body_count; ++i) {
      btSolverBody& to = m_tmpSolverBodyPool[i];
      const SweepBody& from = sweep_bodies_[static_cast<std::size_t>(i)];
      to.m_pushVelocity.setValue(from.linear[0], from.linear[1], from.linear[2]);
      to.m_turnVelocity.setValue(from.angular[0], from.angular[1], from.angular[2]);
    }
  }
  // Velocity sweeps (solveSingleIteration): every contact row, then every friction row with
  // limits from its contact row's impulse.
  for (int i = 0; i < body_count; ++i) {
    const btSolverBody& from = m_tmpSolverBodyPool[i];
    copy3(from.m_deltaLinearVelocity, sweep_bodies_[static_cast<std::size_t>(i)].linear);
    copy3(from.m_deltaAngularVelocity, sweep_bodies_[static_cast<std::size_t>(i)].angular);
  }
  const int iterations = std::max(m_maxOverrideNumSolverIterations, info.m_numIterations);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    btScalar largest = 0.0;
    for (SweepRow& row : contact_rows_) {
      const btScalar residual = solve_row<false>(
          row, row.rhs, row.applied, sweep_bodies_[static_cast<std::size_t>(row.body_a)],
          sweep_bodies_[static_cast<std::size_t>(row.body_b)], row.limit, 0.0);
      largest = max_residual(largest, residual);
    }
    for (SweepRow& row : friction_rows_) {
      const btScalar total = contact_rows_[static_cast<std::size_t>(row.normal_row)].applied;
      if (total > btScalar(0)) {
        const btScalar residual = solve_row<true>(
            row, row.rhs, row.applied, sweep_bodies_[static_cast<std::size_t>(row.body_a)],
            sweep_bodies_[static_cast<std::size_t>(row.body_b)], -(row.limit * total),
            row.limit * total);
        largest = max_residual(largest, residual);
      }
    }
    m_leastSquaresResidual = largest;
    if (largest <= threshold || iteration >= iterations - 1) break;
  }
  for (int i = 0; i < body_count; ++i) {
    btSolverBody& to = m_tmpSolverBodyPool[i];
    const SweepBody& from = sweep_bodies_[static_cast<std::size_t>(i)];
    to.m_deltaLinearVelocity.setValue(from.linear[0], from.linear[1], from.linear[2]);
    to.m_deltaAngularVelocity.setValue(from.angular[0], from.angular[1], from.angular[2]);
  }
  store_compact();
  return true;
}

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
  if (block_contacts_ <= 0 && is_plain && contacts > 0 && compact_sweeps(info)) return 0.0;
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
