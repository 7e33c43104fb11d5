#pragma once
// Modal analysis (thesis Sec 2.4, Eq 2-36..2-38): the lowest natural frequencies and mode shapes of
// (K - omega^2 M) phi = 0, by shift-and-invert Lanczos (Spectra's SymGEigsShiftSolver) with a sparse
// factorization of K - sigma M (CHOLMOD's supernodal Cholesky through Eigen when available, else
// Eigen's SimplicialLDLT with AMD ordering). ANSYS, which the thesis
// uses, extracts the same pairs by Block Lanczos.
//
// Rigid-body modes: a free (or partly free) structure has a singular K, so K itself cannot be
// factorized. Give a negative shift (ModalOptions::shift_hz < 0): K - sigma M is then positive
// definite and the zero eigenvalues come out as the first modes. Without a shift a singular model is
// refused with "model has rigid-body modes: add supports or use shift", unless
// ModalOptions::admit_rigid_body_modes picks the shift itself (as ccx runs a free model).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace fem {
struct AssembledSystem;
struct Mesh;
}  // namespace fem

namespace fem::modal {

struct ModalOptions {
    int modes = 10;
    /// Shift as a frequency [Hz], sign kept: sigma = sign(f) (2 pi f)^2. 0 = no shift (the model must
    /// be supported). A negative shift admits rigid-body modes.
    double shift_hz = 0.0;
    /// With shift_hz == 0: solve a model with rigid-body modes (free or partly supported) as
    /// CalculiX does, without asking for a shift: a small negative shift sigma = -1e-8 max(K_ii / M_ii)
    /// (about 1e-8 of the highest eigenvalue) makes K - sigma M positive definite; rigid-body modes
    /// come out as eigenvalues near 0 and the others unchanged. Used for decks (deck/deck.hpp).
    bool admit_rigid_body_modes = false;
    /// Lanczos basis size; 0 = max(2 modes + 1, modes + 16), capped by the problem size.
    int basis = 0;
    int max_iterations = 1000;
    double tolerance = 1e-10;  // Spectra's relative Ritz-value tolerance
    /// Factorize with CHOLMOD (supernodal) when the library was built with it and sigma <= 0;
    /// otherwise, or when false, Eigen's SimplicialLDLT.
    bool use_cholmod = true;
};

struct ModalResult {
    Eigen::VectorXd eigenvalues;     // omega^2 [rad^2/s^2], ascending
    Eigen::VectorXd frequencies_hz;  // sign(lambda) sqrt(|lambda|) / (2 pi): a rigid mode shows as ~0
    Eigen::MatrixXd shapes;          // reduced DOFs x modes, mass normalized (phi^T M phi = 1)
    /// ||K phi - lambda M phi|| / ||K phi|| per mode; for a rigid-body mode (|lambda| < |sigma|, where
    /// K phi is round-off) the backward error ||K phi - lambda M phi|| / (||K||_1 ||phi||).
    Eigen::VectorXd residuals;
    double shift = 0.0;           // sigma used [rad^2/s^2]
    int iterations = 0;           // Lanczos restarts
    long long operations = 0;     // solves with the factor
    long long factor_nonzeros = 0;
    std::string factorization;    // which sparse factorization was used
    double factor_seconds = 0.0, solve_seconds = 0.0;
};

/// The spread of the diagonals of K and M (lower triangles, reduced DOFs): what makes
/// K phi = lambda M phi hard or impossible in double precision (parts many orders of magnitude
/// apart in stiffness or mass, a value that overflows). Error messages of solve_modes quote it;
/// callers that know the model name the parts at the extreme DOFs.
struct Conditioning {
    Conditioning(const Eigen::SparseMatrix<double>& stiffness, const Eigen::SparseMatrix<double>& mass);
    double k_min = 0, k_max = 0, m_min = 0, m_max = 0;  // over the positive diagonal entries
    int dof_k_min = -1, dof_k_max = -1, dof_m_min = -1, dof_m_max = -1;  // where (dof_k_max: a non-finite one first)
    double lambda_max = 0;  // max K_ii / M_ii: about the highest eigenvalue [rad^2/s^2]
    bool k_finite = true, m_finite = true;
    /// Every entry finite and the eigenvalue scale below 1e300.
    bool representable() const;
    std::string describe() const;
};

/// Lowest `options.modes` pairs of the generalized problem with K, M given as LOWER triangles (as
/// AssembledSystem holds them). Throws InputError for a singular model without a shift, a shift at
/// an eigenvalue, a shift or matrices that overflow (with the Conditioning), SolverError with the
/// Conditioning when the eigensolver fails or Lanczos does not converge. A model of at most 2000
/// equations whose Lanczos run breaks down (a singular mass bounds its Krylov space: CalculiX's C3D8I
/// on a few elements) is solved with dense matrices instead when K - sigma M is positive definite
/// (ModalResult::factorization then says so).
ModalResult solve_modes(const Eigen::SparseMatrix<double>& stiffness, const Eigen::SparseMatrix<double>& mass,
                        const ModalOptions& options);
ModalResult solve_modes(const AssembledSystem& system, const ModalOptions& options);

/// Modal assurance criterion MAC(i, j) = (a_i . b_j)^2 / ((a_i . a_i)(b_j . b_j)) between the columns
/// of two mode sets of the same DOFs.
Eigen::MatrixXd mac(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);
/// Mass-weighted MAC, a_i . b_j replaced by a_i^T M b_j (M as a lower triangle): the identity for a
/// mass-orthogonal set against itself.
Eigen::MatrixXd mac(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::SparseMatrix<double>& mass);

/// Pairs modes of set a with modes of set b by MAC: repeatedly takes the largest remaining entry
/// (greedy assignment). Each mode is used at most once; pairs below min_mac are left out.
struct ModePair {
    int a = 0, b = 0;
    double mac = 0.0;
};
std::vector<ModePair> pair_modes(const Eigen::MatrixXd& mac_matrix, double min_mac = 0.0);

/// Writes frequencies.csv (mode, frequency_hz, eigenvalue, residual) and modes.h5 (datasets
/// frequencies_hz, eigenvalues, residuals, nodes (n x 3)) into `dir`, and for the first `shapes`
/// modes (all when < 0; none when 0: frequencies only) mode_<k>/translation (n x 3, k from 1) in
/// modes.h5 and a PVD series modes.pvd with one VTU per mode (point field "mode_shape").
void write_results(const std::filesystem::path& dir, const Mesh& mesh, const AssembledSystem& system,
                   const ModalResult& result, int shapes = -1);

/// A one-paragraph run summary (size, factor fill, iterations, times, frequencies, worst residual).
std::string summary(const AssembledSystem& system, const ModalResult& result);

}  // namespace fem::modal
