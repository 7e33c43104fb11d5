// The one home of Eigen's symmetric eigen-solvers for the project (eigen_instances.hpp says why).
#include "core/eigen_instances.hpp"

template class Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
template class Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>;
template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>;
template class Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>;
template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::SelfAdjointEigenSolver(const Eigen::EigenBase<Eigen::MatrixXd>&,
                                                                               int);
template Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>&
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>::compute<Eigen::MatrixXd>(const Eigen::EigenBase<Eigen::MatrixXd>&, int);
template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::SelfAdjointEigenSolver(const Eigen::EigenBase<Eigen::Matrix2d>&,
                                                                               int);
template Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>&
Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>::compute<Eigen::Matrix2d>(const Eigen::EigenBase<Eigen::Matrix2d>&, int);
