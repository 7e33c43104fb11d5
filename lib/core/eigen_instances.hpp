#pragma once
// Eigen's symmetric eigen-solvers, compiled once for the whole project (eigen_instances.cpp) instead
// of in every translation unit that uses them.
//
// Why: instantiating Eigen::SelfAdjointEigenSolver / GeneralizedSelfAdjointEigenSolver (the
// tridiagonalization, the Householder sequences, the implicit QR) is the heaviest template work of
// the build. Measured 2026-12-04 (GCC 12, -O3, one unit): studies/cfl_tables/cfl_tables.cpp took
// 22.7 s of CPU with them instantiated in the unit, 5.5 s with the declarations below. Fourteen
// files use them (lib/element, lib/explicit, lib/modal, lib/multibody, one study, five test programs).
//
// Include this header in every file that uses these solvers (a file that does not still compiles and
// gives the same results, but instantiates them again). It is not in core/types.hpp on purpose: the
// declarations cost ~0.13 s of CPU in every unit that includes them (measured), and a change to a
// header every unit includes recompiles the whole build (and empties the compiler cache for CI).
//
// The declarations cover the matrix types the project uses (MatrixXd and, for the lumped bird's 2 x 2
// problem, Matrix2d) and the solver's constructor and compute() taking that same matrix type. A call
// with an expression (say `SelfAdjointEigenSolver<MatrixXd> es(0.5 * (A + A.transpose()))`)
// instantiates compute() for the expression's type in its own unit again: name the matrix first.
// Results are the same bits either way: the same IEEE operations, compiled with the same flags.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

extern template class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
extern template class Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>;
extern template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
extern template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>;
// The member templates (an explicit instantiation of the class leaves them out).
extern template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::SelfAdjointEigenSolver(
    const Eigen::EigenBase<Eigen::MatrixXd>&, int);
extern template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, int);
extern template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::SelfAdjointEigenSolver(
    const Eigen::EigenBase<Eigen::Matrix2d>&, int);
extern template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>&
Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::compute<Eigen::Matrix2d>(const Eigen::EigenBase<Eigen::Matrix2d>&, int);
