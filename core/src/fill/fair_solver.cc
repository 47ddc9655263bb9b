// SPDX-License-Identifier: AGPL-3.0-or-later
#include "fill/fair_solver.h"

#include <CGAL/version.h>

#include <new>

namespace dot {

// fair() in CGAL 5.5 (internal/fair_impl.h) calls factor(A), then
// linear_solver() for x, y and z, and reads the three solutions only after
// the third call returned: so the out-of-process path defers the first two
// and solves all three with one factorization on the third. Check that
// order again before moving to another CGAL.
static_assert(CGAL_VERSION_NR >= 1050500000 && CGAL_VERSION_NR < 1050600000,
              "check the call order of CGAL's fair() (see above)");
constexpr size_t kCoordinates = 3;

Status SolveSparseLu(const SparseSystem& system, std::vector<double>* x) {
  const Eigen::Index n = system.n;
  if (n <= 0 || system.rhs <= 0 ||
      system.b.size() != static_cast<size_t>(n * system.rhs) ||
      system.rows.size() != system.values.size() ||
      system.cols.size() != system.values.size()) {
    return InvalidArgument("malformed sparse system");
  }
  std::vector<Eigen::Triplet<double>> nonzeros;
  nonzeros.reserve(system.values.size());
  for (size_t k = 0; k < system.values.size(); ++k) {
    if (system.rows[k] < 0 || system.rows[k] >= n || system.cols[k] < 0 ||
        system.cols[k] >= n) {
      return InvalidArgument("sparse system entry outside the matrix");
    }
    nonzeros.emplace_back(system.rows[k], system.cols[k], system.values[k]);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(nonzeros.begin(), nonzeros.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(a);
  if (lu.info() != Eigen::Success) {
    return InvalidArgument("the sparse system is singular");
  }
  const Eigen::Map<const Eigen::MatrixXd> b(system.b.data(), n, system.rhs);
  x->resize(system.b.size());
  Eigen::Map<Eigen::MatrixXd>(x->data(), n, system.rhs) = lu.solve(b);
  if (lu.info() != Eigen::Success) {
    return InvalidArgument("the sparse solve failed");
  }
  return OkStatus();
}

FairSolver::FairSolver(const Control& control, RunTicker* ticker)
    : control_(control), ticker_(ticker), state_(std::make_shared<State>()) {}

bool FairSolver::Stop(const Status& why) {
  state_->stop = why;
  return false;
}

bool FairSolver::factor(const Matrix& a, NT& d) {
  d = 1;  // Eigen has no homogeneous coordinate
  State& s = *state_;
  if (!ticker_->Poll()) return Stop(ticker_->status());
  s.a = &a.eigen_object();
  s.in_process =
      !control_.solve_sparse || s.a->rows() <= kSolveSparseMinUnknowns;
  if (!s.in_process) return true;  // factorized with the solve, elsewhere
  s.lu.compute(*s.a);
  return s.lu.info() == Eigen::Success;
}

bool FairSolver::linear_solver(const Vector& b, Vector& x) {
  State& s = *state_;
  if (!ticker_->Poll()) return Stop(ticker_->status());
  if (s.in_process) {
    x = s.lu.solve(b);
    return s.lu.info() == Eigen::Success;
  }
  s.b.push_back(&b);
  s.x.push_back(&x);
  return s.b.size() < kCoordinates || SolveDeferred();
}

bool FairSolver::SolveDeferred() {
  State& s = *state_;
  SparseSystem system;
  system.n = s.a->rows();
  system.rhs = static_cast<int32_t>(s.b.size());
  system.rows.reserve(static_cast<size_t>(s.a->nonZeros()));
  system.cols.reserve(static_cast<size_t>(s.a->nonZeros()));
  system.values.reserve(static_cast<size_t>(s.a->nonZeros()));
  for (Eigen::Index c = 0; c < s.a->outerSize(); ++c) {
    for (EigenMatrix::InnerIterator it(*s.a, c); it; ++it) {
      system.rows.push_back(static_cast<int32_t>(it.row()));
      system.cols.push_back(static_cast<int32_t>(it.col()));
      system.values.push_back(it.value());
    }
  }
  for (const Vector* b : s.b) {
    system.b.insert(system.b.end(), b->data(), b->data() + b->size());
  }
  std::vector<double> x;
  const Status status = control_.solve_sparse(system, &x);
  // The hook's own stop is the fill's status and names the solve. (Before,
  // `||` skipped the ticker's Poll after such a stop, and the fill went on
  // with the ticker's status still OK.)
  if (status.code == StatusCode::kCancelled ||
      status.code == StatusCode::kDeadlineExceeded) {
    return Stop(status);
  }
  if (!ticker_->Poll()) return Stop(ticker_->status());
  if (!status.ok()) {
    s.error = status.message;
    return false;
  }
  for (size_t k = 0; k < s.x.size(); ++k) {
    *s.x[k] =
        Eigen::Map<const Eigen::VectorXd>(x.data() + k * system.n, system.n);
  }
  return true;
}

}  // namespace dot
