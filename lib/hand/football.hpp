#pragma once
// The football sweep of thesis Sec 4.2-4.3 as a hand::Scene: Table 4-3's boundary conditions, the
// five conveyor cases of Table 4-4, and the inputs the text leaves out (THESIS_CH4_5.md Sec 9,
// reconstructed; studies/football_sweep/README.md lists each and its effect). The study and
// fem-explicit take the model from studies/football_sweep/football_sweep.toml; scene() states the
// same model in C++, the reference that test ExplicitCase.FootballCaseFileBuildsTheStudysModel holds
// the case file to (bit for bit), and Table 4-4's cases are the study's changes to the file.
#include <string>
#include <utility>
#include <vector>

#include "core/units.hpp"
#include "hand/scene.hpp"

namespace fem::hand::football {

inline constexpr double fast = 18.0 * units::inch;   // conveyor speed 0.4572 m/s (Table 4-3)
inline constexpr double slow = 10.0 * units::inch;   // 0.254 m/s after the switch
inline constexpr double half_mass = 0.425 / 2;       // raw weight / 2 (half model, Sec 4.2)
inline constexpr double mu_static = 0.4, mu_dynamic = 0.3;  // Table 4-3
inline constexpr double pallet_offset = 8.0 * units::mm;    // Fig 4-4: football 8 mm behind the pallet centre
/// Football centre at t = 0 (Table 4-3) and semi-axes (244/132/132 mm).
inline const Vec3 centre{685.5 * units::mm, 50.8 * units::mm, 184.0 * units::mm};
inline const Vec3 semi_axes{122 * units::mm, 66 * units::mm, 66 * units::mm};

/// One row of Table 4-4: 18 in/s, then 10 in/s from t_switch (< 0: constant, Case 1).
struct Case {
    int id = 0;
    double t_switch = -1.0;
    /// The pallet's speed over time (Curve::steps: the step is exact).
    Curve schedule() const;
};
std::vector<Case> table_4_4();

/// The fingers whose sweeps overlap: neighbours on a level, and upper over lower within 22.5 deg.
std::vector<std::pair<std::string, std::string>> neighbour_pairs();

/// The scene of case c from t = 0 (hand::seen_from gives it from a later start).
Scene scene(const Case& c);

}  // namespace fem::hand::football
