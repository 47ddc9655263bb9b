// SPDX-License-Identifier: AGPL-3.0-or-later
// The sparse solver behind CGAL's fair() (its SparseLinearAlgebraWith-
// FactorTraits_d concept), made stoppable. Eigen's SparseLU, CGAL's default
// and still the solver here, cannot be interrupted inside a factorization
// (0.6 s for 12,000 unknowns), and no iterative solver converges on these
// bi-Laplacians in comparable time. So small systems are solved in process,
// and larger ones by Control::solve_sparse when the caller gives one (the
// server's helper processes, which a cancel kills at once). The ticker is
// polled before each step; once it says stop, factor() and linear_solver()
// return false (CGAL then gives up fairing) and stopped() is true.
#ifndef DOT_CORE_FILL_FAIR_SOLVER_H_
#define DOT_CORE_FILL_FAIR_SOLVER_H_

#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Eigen_vector.h>

#include <Eigen/SparseLU>
#include <memory>
#include <string>
#include <vector>

#include "dot/control.h"
#include "dot/problem.h"
#include "util/run_control.h"

namespace dot {

class FairSolver {
 public:
  using Matrix = CGAL::Eigen_sparse_matrix<double>;
  using Vector = CGAL::Eigen_vector<double>;
  using NT = double;

  FairSolver(const Control& control, RunTicker* ticker);

  bool factor(const Matrix& a, NT& d);
  bool linear_solver(const Vector& b, Vector& x);

  // Whether a step was stopped (cancel or deadline, seen by the ticker or
  // by solve_sparse; once stopped, it stays so), and that stop's status,
  // which names where.
  bool stopped() const { return !state_->stop.ok(); }
  const Status& stop_status() const { return state_->stop; }
  // Why solve_sparse failed, when it did (empty otherwise).
  const std::string& error() const { return state_->error; }

 private:
  using EigenMatrix = Matrix::EigenType;
  // CGAL copies the traits object: the state lives behind a shared pointer.
  struct State {
    const EigenMatrix* a = nullptr;
    Eigen::SparseLU<EigenMatrix, Eigen::COLAMDOrdering<int>> lu;
    bool in_process = true;
    // Deferred right-hand sides and where their solutions go (see .cc).
    std::vector<const Vector*> b;
    std::vector<Vector*> x;
    Status stop;  // not OK once stopped
    std::string error;
  };
  bool SolveDeferred();
  bool Stop(const Status& why);  // records why; returns false for CGAL

  const Control& control_;
  RunTicker* ticker_;
  std::shared_ptr<State> state_;
};

}  // namespace dot

#endif  // DOT_CORE_FILL_FAIR_SOLVER_H_
