#pragma once
// The ellipsoid grasp and flip of thesis Sec 4.4 as a hand::Scene: Tables 4-5 (grasp) and 4-6
// (flip), with the inputs the text leaves out reconstructed (THESIS_CH4_5.md Sec 9 items 7-8;
// studies/ellipsoid_flip/README.md lists each and its effect). The study and fem-explicit take the
// model from studies/ellipsoid_flip/ellipsoid_flip.toml (its two [[phase]]s); scene() states the
// same model in C++, the reference that test ExplicitCase.EllipsoidCaseFileBuildsTheStudysModel
// holds the case file to (bit for bit), as football.hpp does for Tables 4-3/4-4.
//
// Two phases, one scene each, the same mesh: the grasp (the object carried in -x at conveyor speed
// to the drum centre while the hand turns to 180 deg at 1.5 s; no gravity) and the flip (restarted
// from the grasp's state at 2 s: the drum spin held at 180 deg, the whole hand turned 135 deg about
// the global z axis at 4.71 rad/s in 0.5 s, the object free, gravity on). hand::seen_from gives a
// phase from a later start.
#include "core/units.hpp"
#include "hand/scene.hpp"

namespace fem::hand::ellipsoid {

inline constexpr double conveyor = 18.0 * units::inch;        // 0.4572 m/s (Table 4-5: 0.457)
inline constexpr double drum_speed = 20.0 * units::rpm;       // 2.0944 rad/s (Table 4-5)
inline constexpr double flip_speed = 4.71;                    // rad/s, 45 rpm (Table 4-6)
inline constexpr double flip_duration = 0.5;                  // s: 4.71 x 0.5 = 2.355 rad = 134.9 deg
inline constexpr double grasp_end = 2.0;                      // s, Table 4-5's simulation time
inline constexpr double flip_end = grasp_end + 1.0;           // Table 4-6's 1 s
inline constexpr double mu_static = 0.4, mu_dynamic = 0.3;    // Tables 4-5/4-6
inline constexpr double density = 1000.0;                     // kg/m^3 (Sec 4.4: 1.53 kg whole)
/// Where the drum stops: half a turn, pi / omega = 1.49999 s ("180 deg at 1.5 s").
double spin_stop();
/// Semi-axes 97 (x), 57 (y), 66 (z) mm (Sec 4.4 gives 97/66/57; Sec 9 item 7: 66 across, Table 5-3's
/// width 130 mm ~ 2 x 66).
inline const Vec3 semi_axes{97 * units::mm, 57 * units::mm, 66 * units::mm};
/// Centre at t = 0: x such that the object reaches the drum centre x = 0 when the drum stops
/// (conveyor x 1.5 s = 685.8 mm; Table 4-5 prints 0.69 m), y 50.8 mm (the football's height, Sec 9
/// item 7), z on the symmetry plane 184 mm (Table 4-5).
Vec3 centre();

enum class Phase { grasp, flip };

struct Options {
    Phase phase = Phase::grasp;
};

/// The scene of a phase. Grasp: object carried (v_x = -conveyor until spin_stop(), then held at 0:
/// Table 4-5 "conveyor speed = object speed", the object "stops at the drum centre"), no gravity
/// (Table 4-5 lists none), the drum turning until spin_stop(); the flip's turn is in the scene too
/// (zero until grasp_end), so both phases describe the same motions up to grasp_end and the flip
/// restarts from the grasp's dump with only the object's carriage removed and gravity switched on
/// (a Curve step at grasp_end).
Scene scene(const Options& o = {});

}  // namespace fem::hand::ellipsoid
