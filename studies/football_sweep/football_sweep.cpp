// Study football_sweep: a rubber football riding a conveyor pallet through a turning compliant hand
// (thesis Sec 4.2-4.3, Tables 4-1..4-4, Figs 4-1, 4-3..4-11; experiment of Yin 2003, whose curves
// the text does not print).
//
// Model (the half model of Table 4-2, loaded from studies/football_sweep/football_sweep.toml, the
// case file fem-explicit runs, and built by lib/hand; reconstructions in README.md):
//   - the hand: the stepped drum turning at 20 rpm about -y, five Table 4-1 fingers (hexahedral
//     mapped 5 x 5 sections, 725 / 500 elements as Table 4-2), roots tied to the drum, absolute
//     mass damping alpha 180 / 600 (LS-DYNA *DAMPING_PART_MASS);
//   - the half football: ellipsoid 122/66/66 mm, 512 hexahedra, 0.2125 kg (half of 0.425 kg),
//     rubber E 6.1 MPa, nu 0.49, centre (685.5, 50.8, 184) mm, u_z = 0 on the plane z = 184 mm;
//   - the pallet: a rigid 200 x 50 mm plate under the football moving in -x at 18 in/s, then
//     10 in/s from the case's switch time (Table 4-4);
//   - contact: every finger with the football (two-way), the football with the pallet and with the
//     drum; mu = mu_s = 0.4 (Eq 2-35 with c_d = 0). Finger against finger is not in the judged runs:
//     neighbouring fingers stay 12 mm apart or more (measured, min_clearance). Each finger against
//     its mirror image (the other drum's) is: a frictionless wall on the symmetry plane (the case
//     file's [hand] mirror_contact; README reconstruction 9);
//   - gravity 9.81 m/s^2 in -y.
//
// What the study adds to the case file: Table 4-4's cases (each replaces the pallet's speed schedule;
// the file's is Case 4), the damping-frame and mirror variants, the run plan, checks and figures.
//
// Run plan (README "Cost"): the five cases of Table 4-4 are the same run until the earliest speed
// switch (Case 5, 1.06 s). One process runs Case 1 and writes a restart dump 0.1 ms before each
// other case's switch; from it a child restarts with its own pallet schedule and runs on, so every
// case is bit-identical to a run from t = 0. A case whose switch comes when the football is out of
// reach of both pallets (Case 2: thrown off the pallet before 1.38 s) goes on sharing the parent's
// run, bit for bit, and is forked from its dump only if the football comes within reach of either
// pallet. CTest stops each case at the end of the judged window; --full runs to 3 s.
#include <csignal>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "check/study.hpp"
#include "contact/explicit_contact.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "damping/signal.hpp"
#include "explicit/parallel.hpp"
#include "explicit/solver.hpp"
#include "explicit_case/case_file.hpp"
#include "hand/football.hpp"
#include "hand/plane_excursion.hpp"
#include "hand/scene.hpp"
#include "io/atomic_file.hpp"
#include "io/table.hpp"
#include "io/vtu.hpp"

using namespace fem;
using namespace fem::hand;
using units::inch;
using units::mm;
using nlohmann::json;

namespace {

// SIGUSR1 ends every process's run at its next sample, as if its end time had come: the records
// written so far are kept (`kill -USR1 <pids>` on a run that will not finish in time).
volatile std::sig_atomic_t g_stop = 0;
extern "C" void request_stop_signal(int) { g_stop = 1; }

const std::vector<std::string> kFingers = {"A", "B", "C", "D", "E"};
using football::Case;
const std::vector<Case> kCases = football::table_4_4();
const auto kFingerPairs = football::neighbour_pairs();

// A variant of the case file's model.
struct Variant {
    DampingFrame frame = DampingFrame::absolute;
    double roll_sign = 1.0;        // R_x sense (HandSpec::roll_sign): the mirror case is -1
    bool football = true;          // false: the hand alone
};

// The case file's scene (football_sweep.toml: Case 4 from t = 0), read once in main().
Scene g_case_scene;

// The study's scene of Table 4-4 case c from physical time t0 on: the case file's model with the
// case's pallet schedule (Table 4-4: 18 in/s, 10 in/s from its switch time) and the variant.
Scene football_scene(const Case& c, const Variant& v, double t0 = 0.0) {
    Scene s = g_case_scene;
    s.damping_frame = v.frame;
    s.hand.roll_sign = v.roll_sign;
    if (v.football) {
        s.plates.at(0).speed = c.schedule();
    } else {
        s.objects.clear(), s.plates.clear(), s.contacts.clear();
        s.mirror_contact = false;  // no half object, no symmetry plane (the fingers-only run ends at 0.1 s, long before any finger reaches it)
    }
    return seen_from(std::move(s), t0);
}

// Contact statistics per pair and per finger, accumulated every cycle by the observer.
struct PerPair {
    double impulse = 0, time = 0, first = -1, last = -1, max_penetration = 0, max_penetration_fraction = 0, at = 0;
};

// --- one run --------------------------------------------------------------------------------------

constexpr double kSample = 1e-4;   // history / observer interval: 0.1 ms bins (the CFC 60 input)
constexpr double kRow = 1e-3;      // rows of the written records
constexpr double kStart = 0.95;    // start of the judged runs (s): 0.11 s before the first contact (README "Cost")
constexpr double kLagTime = 0.1;   // steady finger lag: measured this long after the start (time constants 15-25 ms), before contact
// End of the judged window (s; README "Cost"): the latest time a check can judge, the end of the
// tolerance band of fig-4-3/case-4/time-of-max-y (1.825 + 0.1 s), so no check loses a value it could
// pass with (2.0 s until this session: ~9 % of the CTest cost).
constexpr double kWindow = 1.93;
const std::vector<double> kSnapshots = {0.95, 1.1, 1.3, 1.5, 1.6, 1.7, 1.8, 1.92};  // Figs 4-1, 4-5, 4-9 (8 panels)

// What one case records (JSON between the processes).
struct Record {
    int id = 0;
    std::vector<double> t, x, y, z, rel_x, s_ball, s_ball_cfc, s_fingers;   // rows every kRow
    std::map<std::string, std::vector<double>> tip_y, impulse;
    std::map<std::string, double> lag, min_clearance;                       // per finger / finger pair
    // Per finger: its surface nodes' farthest excursion beyond the half football's symmetry plane
    // (where the mirrored half of the model is) every 0.1 ms: [distance (m), time (s), node, first
    // time beyond the plane (s; -1: never)] (README "Penetration").
    std::map<std::string, hand::PlaneExcursion> beyond_plane;
    std::map<std::string, PerPair> pairs, fingers;
    std::vector<double> snap_t;
    std::vector<std::vector<double>> snap_x;                                // node coordinates (flat)
    double y0 = 0, window = 0, s_cfc_max = 0, s_raw_max = 0;
    // At the end of the judged window: largest penetration so far (the energy health is the run
    // summary's, judged over the same window: ExplicitOptions::health_until).
    double pen_window = 0;
    json summary;
};

json pair_json(const PerPair& p) {
    return {p.impulse, p.time, p.first, p.last, p.max_penetration, p.max_penetration_fraction, p.at};
}
PerPair pair_from(const json& a) { return {a[0], a[1], a[2], a[3], a[4], a[5], a[6]}; }

json to_json(const Record& r) {
    json j = {{"id", r.id}, {"t", r.t}, {"x", r.x}, {"y", r.y}, {"z", r.z}, {"rel_x", r.rel_x}, {"s_ball", r.s_ball},
              {"s_ball_cfc", r.s_ball_cfc}, {"s_fingers", r.s_fingers}, {"tip_y", r.tip_y}, {"impulse", r.impulse},
              {"lag", r.lag}, {"min_clearance", r.min_clearance}, {"snap_t", r.snap_t}, {"snap_x", r.snap_x},
              {"y0", r.y0}, {"window", r.window}, {"s_cfc_max", r.s_cfc_max}, {"s_raw_max", r.s_raw_max},
              {"pen_window", r.pen_window}, {"beyond_plane", r.beyond_plane},
              {"summary", r.summary}};
    for (const auto& [n, p] : r.pairs) j["pairs"][n] = pair_json(p);
    for (const auto& [n, p] : r.fingers) j["fingers"][n] = pair_json(p);
    return j;
}

Record from_json(const json& j) {
    Record r;
    r.id = j.at("id");
    for (auto [key, v] : {std::pair{"t", &r.t}, {"x", &r.x}, {"y", &r.y}, {"z", &r.z}, {"rel_x", &r.rel_x},
                          {"s_ball", &r.s_ball}, {"s_ball_cfc", &r.s_ball_cfc}, {"s_fingers", &r.s_fingers}})
        j.at(key).get_to(*v);
    j.at("tip_y").get_to(r.tip_y), j.at("impulse").get_to(r.impulse), j.at("lag").get_to(r.lag);
    j.at("min_clearance").get_to(r.min_clearance), j.at("snap_t").get_to(r.snap_t), j.at("snap_x").get_to(r.snap_x);
    r.y0 = j.at("y0"), r.window = j.at("window"), r.s_cfc_max = j.at("s_cfc_max"), r.s_raw_max = j.at("s_raw_max");
    r.pen_window = j.at("pen_window");
    if (j.contains("beyond_plane")) j.at("beyond_plane").get_to(r.beyond_plane);
    r.summary = j.at("summary");
    if (j.contains("pairs")) for (const auto& [n, a] : j["pairs"].items()) r.pairs[n] = pair_from(a);
    if (j.contains("fingers")) for (const auto& [n, a] : j["fingers"].items()) r.fingers[n] = pair_from(a);
    return r;
}

damping::SampledSignal cfc60(std::vector<double> bins) {
    return damping::cfc_filter(damping::SampledSignal{0.5 * kSample, kSample, std::move(bins)}, 60.0);
}

struct RunOptions {
    double end = 3.0;            // simulated end
    double window = 3.0;         // checks use t <= window only (the same with and without --full)
    double start = 0.0;          // physical time of the model's t = 0 (football_scene's t0)
    std::vector<Case> cases;     // cases[0] runs in this process, the others restart at their switch
    std::filesystem::path out;
    std::filesystem::path dumps;  // restart dumps at the speed switches (removed after the run)
    std::string name = "football";
};

// Tip lag of each finger: how far the tip-centre node trails its rigid-rotation position, along the
// direction of motion (positive: behind).
std::map<std::string, double> tip_lags(const HandModel& hm, const NodalState& s, double t) {
    std::map<std::string, double> lag;
    for (const auto& f : kFingers) {
        const int n = hm.tip_node(f);
        const Vec3 rigid = hm.drum_position(s.X[n], t);
        const Vec3 et = hm.drum_motion().velocity_at(rigid, t).normalized();
        lag[f] = -(s.x[n] - rigid).dot(et);
    }
    return lag;
}

// What the observer keeps between cycles for one case (a forked child carries it on).
struct Recorder {
    const Variant& v;
    const RunOptions& o;
    Record r;
    std::map<std::string, std::vector<int>> surf;  // surface nodes of each finger (finger-finger clearance)
    std::vector<double> bins;                      // football stress maxima per 0.1 ms (the CFC 60 input)
    double bin_s = 0, row_s = 0, row_sf = 0, next_bin = 0, next_row = 0, next_clearance = 0, next_log = 0;
    double t_last = -1;
    std::size_t snap = 0;
    // Cases that share this run (run(): the football out of reach of their pallet and of this run's):
    // what differs in their record, their football - pallet x per row and their pallet's nodes at
    // each snapshot, from the rows and snapshots where the sharing began.
    struct Sharer {
        int id = 0;
        Plate pallet;
        std::size_t row0 = 0, snap0 = 0;
        std::vector<double> rel_x;
        std::vector<std::vector<std::pair<int, Vec3>>> snap_pallet;
    };
    std::vector<Sharer> sharers;
    std::vector<int> pallet_nodes;  // the pallet's mesh nodes (rigid)
    double plane_z = 0;             // the half football's symmetry plane

    Recorder(const Variant& v_, const RunOptions& o_, const HandModel& hm, int id) : v(v_), o(o_) {
        r.id = id;
        r.window = o.window;
        if (v.football) r.y0 = hm.centre_of_mass("football", hm.mesh().nodes).y();
        for (const auto& f : kFingers)
            surf[f] = hand::finger_surface_nodes(hm, f);
        for (const auto& [a, b] : kFingerPairs) r.min_clearance[a + b] = 1e9;
        if (v.football) {
            std::set<int> nodes;
            for (int b : hm.mesh().blocks_of_part("pallet"))
                for (int n : hm.mesh().blocks[b].connectivity) nodes.insert(n);
            pallet_nodes.assign(nodes.begin(), nodes.end());
            plane_z = hm.scene().objects.at(0).centre.z();
            for (const auto& f : kFingers) r.beyond_plane[f] = hand::kNoExcursion;
        }
        next_bin = next_row = next_clearance = next_log = o.start;
    }

    double max_penetration() const {
        double pen = 0;
        for (const auto& [n, p] : r.pairs) pen = std::max(pen, p.max_penetration_fraction);
        return pen;
    }

    // Every cycle (ExplicitOptions::observer_interval = 0).
    void cycle(const ExplicitSolver& s, const HandModel& hm) {
        const double tau = s.time(), t = tau + o.start;  // model and physical time
        if (g_stop) s.request_stop();
        // A restarted child sees the cycles up to its fork again: they are counted already.
        if (tau <= t_last) return;
        const double dt = t_last < 0 ? 0.0 : tau - t_last;
        t_last = tau;
        contacts(hm, t, dt);
        const double sb = v.football ? s.max_von_mises("football") : 0.0;
        bin_s = std::max(bin_s, sb);
        row_s = std::max(row_s, sb);
        for (const auto& f : kFingers) row_sf = std::max(row_sf, s.max_von_mises("finger-" + f));
        if (t + 1e-12 < next_bin) return;
        // --- every 0.1 ms ---
        next_bin += kSample;
        bins.push_back(bin_s);
        bin_s = 0;
        if (r.lag.empty() && tau >= kLagTime) r.lag = tip_lags(hm, s.state(), tau);
        if (t >= next_clearance) clearances(s, t);
        if (v.football) plane_crossing(s, t);
        if (t >= next_log) log(s, hm, t, sb);
        if (snap < kSnapshots.size() && t >= kSnapshots[snap]) {
            ++snap;
            r.snap_t.push_back(t);
            std::vector<double> flat;
            for (const auto& p : s.state().x) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
            r.snap_x.push_back(std::move(flat));
            for (auto& sh : sharers) {  // (the solver moves rigid nodes onto their motion, to rounding)
                std::vector<std::pair<int, Vec3>> at;
                for (int n : pallet_nodes) at.emplace_back(n, sh.pallet.motion().position(s.state().X[n], tau));
                sh.snap_pallet.push_back(std::move(at));
            }
        }
        if (t < next_row - 1e-12) return;
        // --- every 1 ms ---
        next_row += kRow;
        r.t.push_back(t);
        if (v.football) {
            const Vec3 c = hm.centre_of_mass("football", s.state().x);
            r.x.push_back(c.x()), r.y.push_back(c.y()), r.z.push_back(c.z());
            r.rel_x.push_back(c.x() - hm.plate_centre("pallet", tau).x());
            for (auto& sh : sharers) sh.rel_x.push_back(c.x() - sh.pallet.motion().position(sh.pallet.centre, tau).x());
        }
        r.s_ball.push_back(row_s), r.s_fingers.push_back(row_sf);
        row_s = row_sf = 0;
        for (const auto& f : kFingers) {
            const int node = hm.tip_node(f);
            r.tip_y[f].push_back(s.state().x[node].y() - s.state().X[node].y());
            r.impulse[f].push_back(r.fingers[f].impulse);
        }
        if (t <= o.window + 1e-12) r.pen_window = max_penetration();
    }

    // Contact this cycle: impulse, contact time and the first/last contact per pair and per finger;
    // the deepest penetration (lib/contact: a fraction of the slave node's element size) and when
    // it was reached.
    void contacts(const HandModel& hm, double t, double dt) {
        for (const auto& [name, c] : hm.contact_reports()) {  // the pairs and the mirror wall
            auto& q = r.pairs[name];
            q.impulse += c.force_on_master.norm() * dt;
            if (c.active > 0) {
                q.time += dt;
                if (q.first < 0) q.first = t;
                q.last = t;
            }
            if (c.max_penetration_fraction > q.max_penetration_fraction) {
                if (c.max_penetration_fraction > std::max(0.3, q.max_penetration_fraction + 0.1)) report_deep(hm, name, c, t);
                q.max_penetration_fraction = c.max_penetration_fraction, q.at = t;
            }
            q.max_penetration = c.max_penetration;
        }
        if (!v.football) return;
        // Force on each finger from the football (fingers on football: pass 0 = finger nodes on
        // football faces, force on the finger; pass 1 = football nodes on finger faces, reaction).
        const auto& fc = hm.contact("fingers on football");
        std::map<std::string, Vec3> on;
        for (const auto& c : fc.contacts()) {
            const Vec3 f = c.normal_force * c.normal + c.tangential_force;
            // (try_emplace with zero: a default-constructed Eigen vector is uninitialised)
            if (c.pass == 0) on.try_emplace(hm.finger_of_node(c.node), Vec3::Zero()).first->second += f;
            else on.try_emplace(hm.finger_of_block(fc.slave_surface().segments[c.segment].block), Vec3::Zero()).first->second -= f;
        }
        for (const auto& [finger, f] : on) {
            auto& q = r.fingers[finger];
            q.impulse += f.norm() * dt;
            q.time += dt;
            if (q.first < 0) q.first = t;
            q.last = t;
        }
    }

    // A new deepest penetration of a pair (beyond 0.3 of the element size): which node, on which
    // side, how deep, so that a jump can be traced (README "Open problems").
    void report_deep(const HandModel& hm, const std::string& name, const ContactReport& c, double t) const {
        std::string where;  // the deepest contact point, where the contact keeps them (a pair, not the wall)
        for (const auto& p : hm.pairs()) {
            if (p.name != name) continue;
            const contact::ContactPoint* deep = nullptr;
            for (const auto& cp : p.contact->contacts())
                if (!deep || cp.gap < deep->gap) deep = &cp;
            if (!deep) break;
            const std::string part = hm.finger_of_node(deep->node).empty() ? "object/plate" : "finger-" + hm.finger_of_node(deep->node);
            where = fmt::format(" at node {} ({}, pass {}, x = {:.1f} {:.1f} {:.1f} mm, normal {:.2f} {:.2f} {:.2f})",
                                deep->node, part, deep->pass, 1e3 * deep->position.x(), 1e3 * deep->position.y(),
                                1e3 * deep->position.z(), deep->normal.x(), deep->normal.y(), deep->normal.z());
        }
        fmt::print("  {} case {} t {:.4f}: {} penetration {:.3f} of the element ({:.2f} mm){} ({} contacts)\n", o.name, r.id,
                   t, name, c.max_penetration_fraction, 1e3 * c.max_penetration, where, c.active);
    }

    // Every 5 ms: the closest surface nodes of neighbouring fingers.
    void clearances(const ExplicitSolver& s, double) {
        next_clearance += 5e-3;
        const auto& x = s.state().x;
        auto box = [&](const std::vector<int>& nodes) {
            Eigen::AlignedBox<double, 3> b;
            for (int i : nodes) b.extend(x[i]);
            return b;
        };
        for (const auto& [a, b] : kFingerPairs) {
            double& best = r.min_clearance[a + b];
            const auto ba = box(surf[a]), bb = box(surf[b]);
            Vec3 gap = (ba.min() - bb.max()).cwiseMax(bb.min() - ba.max()).cwiseMax(Vec3::Zero());
            if (gap.norm() >= best) continue;  // the boxes are farther apart than the closest seen
            double d2 = 1e18;
            for (int i : surf[a])
                for (int j : surf[b]) d2 = std::min(d2, (x[i] - x[j]).squaredNorm());
            best = std::min(best, std::sqrt(d2));
        }
    }

    // Every 0.1 ms: each finger's farthest surface node beyond the symmetry plane (Record::beyond_plane).
    void plane_crossing(const ExplicitSolver& s, double t) {
        for (const auto& f : kFingers) hand::track_plane_excursion(surf[f], s.state().x, plane_z, t, r.beyond_plane[f]);
    }

    // Progress, every 0.1 s simulated.
    void log(const ExplicitSolver& s, const HandModel& hm, double t, double sb) {
        next_log += 0.1;
        const double tau = s.time();
        const auto it = r.pairs.find("fingers on football");
        fmt::print("  {} case {} t {:.2f}: football y {:+.2f} mm, x - pallet {:.2f} mm, stress {:.4f} MPa, "
                   "penetration {:.3f}, first finger contact {:.3f} s, dt {:.3g} us\n", o.name, r.id, t,
                   v.football ? 1e3 * (hm.centre_of_mass("football", s.state().x).y() - r.y0) : 0.0,
                   v.football ? 1e3 * (hm.centre_of_mass("football", s.state().x).x() - hm.plate_centre("pallet", tau).x()) : 0.0,
                   1e-6 * sb, max_penetration(), it != r.pairs.end() && it->second.first >= 0 ? it->second.first : -1.0,
                   1e6 * 0.9 * s.critical_dt());
        std::fflush(stdout);
    }

    // After the run: the CFC 60 stress, the summary, the record file.
    void finish(const RunSummary& sum, const HandModel& hm, const nlohmann::json& prefix) {
        // Stress: CFC 60 over the whole record (plots) and over the judged window alone (checks).
        const damping::SampledSignal all = cfc60(bins);
        for (double t : r.t) {
            const std::size_t i = std::min(all.size() - 1, static_cast<std::size_t>(std::max(0.0, (t - o.start) / kSample - 0.5)));
            r.s_ball_cfc.push_back(all.x[i]);
        }
        const std::size_t nw = std::min(bins.size(), static_cast<std::size_t>((o.window - o.start) / kSample));
        const damping::SampledSignal win = cfc60(std::vector<double>(bins.begin(), bins.begin() + nw));
        r.s_cfc_max = *std::max_element(win.x.begin(), win.x.end());
        r.s_raw_max = *std::max_element(bins.begin(), bins.begin() + nw);
        r.summary = sum.to_json();
        r.summary["name"] = fmt::format("{}-case-{}", o.name, r.id);
        if (!prefix.is_null()) r.summary["restarted_from"] = prefix;
        io::AtomicFile f(o.out / fmt::format("{}-case-{}.json", o.name, r.id));
        f.stream() << to_json(r).dump();
        f.commit();
        fmt::print("[ {} case {} ] {} steps{}, dt {:.3g} us, {:.0f} s wall, {:.3g} M element-cycles/s, contact {:.0f} %, "
                   "energy error {:.2g}, max penetration {:.3f} of the element\n",
                   o.name, r.id, sum.steps, prefix.is_null() ? "" : " (after its restart)", 1e6 * sum.min_dt, sum.wall_s,
                   1e-6 * sum.element_cycles_per_s, 100 * r.summary.value("contact_share", 0.0),
                   sum.energy.relative_error(), max_penetration());
        for (const auto& [f, b] : r.beyond_plane)
            if (b[3] >= 0.0)
                fmt::print("  {} case {}: finger {} beyond the symmetry plane from {:.4f} s, farthest {:.2f} mm at {:.4f} s (node {})\n",
                           o.name, r.id, f, b[3], 1e3 * b[0], b[1], static_cast<int>(b[2]));
        (void)hm;
    }
};

ExplicitOptions solver_options(const RunOptions& o, int id) {
    ExplicitOptions opt;
    opt.end_time = o.end - o.start;
    opt.print_summary = false;
    opt.progress = false;
    opt.history_interval = kRow;   // energies for the balance; the observer watches every cycle
    opt.observer_interval = 0.0;
    // Viscous work booked first-order (ExplicitOptions: ~15 % of a hex8 step saved): bulk viscosity
    // only, no beta damping; energy/balance-and-hourglass judges the balance that results (with
    // exact booking the first complete runs had ~1e-7 of the largest energy).
    opt.exact_viscous_energy = false;
    opt.name = fmt::format("{}-case-{}", o.name, id);
    opt.health_until = o.window - o.start;  // the run summary's energy health over the judged window
    return opt;
}

// Whether the football is out of reach of pallet `p` at model time tau: no football node within
// kReachNormal above the plate's top or below its contact depth, unless it is kReachSide beyond the
// plate's edges. lib/contact pushes only nodes that are below the top (at most `depth`) and project
// onto the plate within its edge tolerance (5 % of a 100 mm segment); the test runs every cycle, in
// which a node moves ~4 um, so a pallet out of reach exerts no force and changes nothing else in a
// run (its contact search finds nothing).
constexpr double kReachNormal = 0.002, kReachSide = 0.01;
bool out_of_reach(const Plate& p, const HandModel& hm, const NodalState& s, double tau) {
    const Vec3 c = p.motion().position(p.centre, tau);
    const Vec3 n = p.u.cross(p.v).normalized();
    const double hu = 0.5 * p.u.norm(), hv = 0.5 * p.v.norm();
    const Vec3 eu = p.u.normalized(), ev = p.v.normalized();
    for (int i : hm.part_nodes("football")) {
        const Vec3 d = s.x[i] - c;
        const double h = d.dot(n);
        if (h > kReachNormal || h < -p.depth - kReachNormal) continue;  // above or below the plate's reach
        if (std::abs(d.dot(eu)) > hu + kReachSide || std::abs(d.dot(ev)) > hv + kReachSide) continue;  // beside it
        return false;
    }
    return true;
}

// Runs cases[0] from t = 0. The other cases are the same run until their speed switch: the run
// writes a restart dump 0.1 ms before each switch (core's restart, ExplicitOptions::restart_times),
// and when one is written a child process is forked that builds the case's model (its pallet
// schedule) and restarts from the dump (a "full deck restart" that changes a motion), keeping the
// observer's record so far. Each process writes <out>/<name>-case-<id>.json; the children then exit.
// A case whose switch comes when the football is out of reach of both pallets (this run's and the
// case's: Case 2, the football thrown off before 1.38 s) is this run, bit for bit, for as long as
// that lasts: its child is forked from its dump only when the football comes within reach of either
// pallet (the child recomputes the cycles since the dump); if it never does, the case's record is
// this run's (README "Cost").
// Returns cases[0]'s record.
Record run(const Variant& v, const RunOptions& o) {
    std::vector<Case> pending(o.cases.begin() + 1, o.cases.end());
    std::sort(pending.begin(), pending.end(), [](const Case& a, const Case& b) { return a.t_switch < b.t_switch; });
    HandModel hm(football_scene(o.cases.front(), v, o.start));
    ExplicitOptions opt = solver_options(o, o.cases.front().id);
    if (!pending.empty()) {
        std::filesystem::create_directories(o.dumps);
        opt.restart_dir = o.dumps;
        for (const auto& c : pending) {
            if (c.t_switch - kSample <= o.start) throw InputError(fmt::format(
                "football_sweep: case {} switches at {} s, before the start {} s", c.id, c.t_switch, o.start));
            opt.restart_times.push_back(c.t_switch - kSample - o.start);
        }
    }
    Recorder rec(v, o, hm, o.cases.front().id);
    std::size_t forked = 0;
    // Cases sharing this run: their dump, when it was written, and the recorder as it was then (a
    // case that leaves the shared run restarts from its dump with it, as if forked at the dump).
    struct Shared {
        Case c;
        std::filesystem::path dump;
        double time = 0;
        long steps = 0;
        std::shared_ptr<Recorder> saved;
    };
    std::vector<Shared> shared;
    ExplicitSolver solver(hm.model(), opt);
    auto fork_case = [&](Shared& sh) {
        std::fflush(stdout);
        const pid_t pid = fork();
        if (pid < 0) throw SolverError("football_sweep: fork() failed");
        if (pid > 0) return;
        // The child: case sh.c from the dump, with the record up to it.
        HandModel child_model(football_scene(sh.c, v, o.start));
        ExplicitOptions copt = solver_options(o, sh.c.id);
        copt.restart_from = sh.dump;
        ExplicitSolver child(child_model.model(), copt);
        Recorder& crec = *sh.saved;
        crec.r.id = sh.c.id;
        crec.sharers.clear();
        child.observer = [&](const ExplicitSolver& cs) { crec.cycle(cs, child_model); };
        const RunSummary sum = child.run();
        crec.finish(sum, child_model, {{"file", sh.dump.filename().string()}, {"time", sh.time + o.start},
                                       {"steps_before", sh.steps}});
        std::fflush(stdout);
        std::_Exit(0);
    };
    solver.observer = [&](const ExplicitSolver& s) {
        while (forked < s.restart_files().size() && forked < pending.size()) {
            const Case next = pending[forked];
            shared.push_back({next, s.restart_files()[forked++], s.time(), s.step(), std::make_shared<Recorder>(rec)});
            rec.sharers.push_back({next.id, football_scene(next, v, o.start).plates.at(0), rec.r.t.size(), rec.r.snap_t.size(), {}, {}});
        }
        // Fork every case whose pallet, or this run's, may touch the football now.
        for (std::size_t k = 0; k < shared.size();) {
            const auto sh = std::find_if(rec.sharers.begin(), rec.sharers.end(), [&](const auto& q) { return q.id == shared[k].c.id; });
            if (v.football && out_of_reach(sh->pallet, hm, s.state(), s.time()) &&
                out_of_reach(hm.scene().plates.at(0), hm, s.state(), s.time())) {
                ++k;
                continue;
            }
            if (s.time() > shared[k].time + kSample)
                fmt::print("  case {} leaves the shared run at t {:.4f} s\n", shared[k].c.id, s.time() + o.start);
            fork_case(shared[k]);
            rec.sharers.erase(sh);
            shared.erase(shared.begin() + static_cast<std::ptrdiff_t>(k));
        }
        rec.cycle(s, hm);
    };
    const RunSummary sum = solver.run();
    rec.finish(sum, hm, nullptr);
    // The cases that shared the whole run: its record under their id, with their pallet.
    for (const auto& sh : rec.sharers) {
        Record r = rec.r;
        r.id = sh.id;
        std::copy(sh.rel_x.begin(), sh.rel_x.end(), r.rel_x.begin() + static_cast<std::ptrdiff_t>(sh.row0));
        for (std::size_t k = 0; k < sh.snap_pallet.size(); ++k)
            for (const auto& [n, x] : sh.snap_pallet[k])
                for (int d = 0; d < 3; ++d) r.snap_x[sh.snap0 + k][3 * n + d] = x[d];
        r.summary["name"] = fmt::format("{}-case-{}", o.name, sh.id);
        const double from = std::find_if(shared.begin(), shared.end(), [&](const Shared& q) { return q.c.id == sh.id; })->time + o.start;
        r.summary["shared_run"] = {{"of", fmt::format("{}-case-{}", o.name, rec.r.id)}, {"from", from},
                                   {"why", "the football out of reach of both pallets from the case's switch on"}};
        io::AtomicFile f(o.out / fmt::format("{}-case-{}.json", o.name, r.id));
        f.stream() << to_json(r).dump();
        f.commit();
        fmt::print("[ {} case {} ] the run of case {} from {:.4f} s (the football out of reach of both pallets)\n", o.name,
                   sh.id, rec.r.id, from);
    }
    return rec.r;
}

// Waits for every child process; throws when one failed.
void wait_children() {
    int status = 0;
    bool failed = false;
    while (wait(&status) > 0)
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) failed = true;
    if (failed) throw SolverError("football_sweep: a forked run failed (see its message above)");
}

Record load(const std::filesystem::path& p) {
    std::ifstream f(p);
    if (!f) throw InputError(fmt::format("football_sweep: missing run record {}", p.string()));
    return from_json(json::parse(f));
}

// --- outputs ----------------------------------------------------------------------------------------

void write_case(const std::filesystem::path& path, const Record& r) {
    io::Table t;
    auto scaled = [](const std::vector<double>& v, double k, double minus = 0) {
        std::vector<double> o;
        for (double x : v) o.push_back(k * (x - minus));
        return o;
    };
    t.add("t_s", r.t).add("x_mm", scaled(r.x, 1e3)).add("uy_mm", scaled(r.y, 1e3, r.y0)).add("rel_x_mm", scaled(r.rel_x, 1e3))
        .add("s_ball_raw_MPa", scaled(r.s_ball, 1e-6)).add("s_ball_cfc60_MPa", scaled(r.s_ball_cfc, 1e-6))
        .add("s_fingers_MPa", scaled(r.s_fingers, 1e-6));
    for (const auto& f : kFingers) t.add("tip_uy_" + f + "_mm", scaled(r.tip_y.at(f), 1e3));
    for (const auto& f : kFingers) t.add("impulse_" + f + "_Ns", r.impulse.at(f));
    io::write_dat(path, t);
}

// Surface quads of the fingers and the football at each snapshot, for gnuplot splot (blocks per
// snapshot; each quad 5 points and a blank line) [mm], plus the pallet and the drum outline.
void write_snapshots(const std::filesystem::path& dir, const std::string& stem, const Record& r, const Variant& v,
                     const Case& c, double t0) {
    HandModel hm(football_scene(c, v, t0));
    std::vector<std::pair<std::string, contact::ContactSurface>> surfaces;
    for (const auto& f : kFingers)
        surfaces.emplace_back("finger-" + f, contact::ContactSurface::from_part(hm.mesh(), "finger-" + f, hm.scene().hand.rubber));
    surfaces.emplace_back("football", contact::ContactSurface::from_part(hm.mesh(), "football", hm.scene().objects[0].material));
    io::PvdSeries pvd(dir / (stem + ".pvd"));  // the same states for ParaView
    for (std::size_t k = 0; k < r.snap_t.size(); ++k) {
        io::AtomicFile f(dir / fmt::format("{}-{}.dat", stem, k));
        auto& o = f.stream();
        const auto& X = r.snap_x[k];
        const double t = r.snap_t[k];
        std::vector<Vec3> x(hm.mesh().node_count());
        io::Field u{"displacement", 3, {}};
        for (int n = 0; n < hm.mesh().node_count(); ++n) {
            x[n] = Vec3(X[3 * n], X[3 * n + 1], X[3 * n + 2]);
            for (int d = 0; d < 3; ++d) u.values.push_back(x[n][d] - hm.mesh().nodes[n][d]);
        }
        pvd.add(t, hm.mesh(), io::VtuData{{u}, {}}, x);
        o << "# t = " << t << " s; index 0: fingers, 1: football, 2: pallet, 3: drum (quads, mm)\n";
        auto pt = [&](int n) { o << 1e3 * X[3 * n] << ' ' << 1e3 * X[3 * n + 1] << ' ' << 1e3 * X[3 * n + 2] << '\n'; };
        for (std::size_t sI = 0; sI < surfaces.size(); ++sI) {
            for (const auto& seg : surfaces[sI].second.segments) {
                for (int a = 0; a < seg.count; ++a) pt(seg.n[a]);
                pt(seg.n[0]);
                o << '\n';
            }
            if (sI + 2 >= surfaces.size()) o << "\n";  // after the last finger and after the football
        }
        const Vec3 pc = hm.plate_centre("pallet", t - t0);
        for (auto [dx, dz] : {std::pair{-0.1, 0.0}, {0.1, 0.0}, {0.1, -50e-3}, {-0.1, -50e-3}, {-0.1, 0.0}})
            o << 1e3 * (pc.x() + dx) << ' ' << 1e3 * pc.y() << ' ' << 1e3 * (184e-3 + dz) << '\n';
        o << "\n\n";
        for (const auto& l : hm.scene().hand.drum.levels) {
            for (double y : {l.y_bottom, l.y_top}) {
                for (int i = 0; i <= 48; ++i) {
                    const double phi = 2 * std::numbers::pi * i / 48;
                    o << 1e3 * l.radius * std::sin(phi) << ' ' << 1e3 * y << ' ' << -1e3 * l.radius * std::cos(phi) << '\n';
                }
                o << '\n';
            }
        }
        f.commit();
    }
}

}  // namespace

int main(int argc, char** argv) {
    return check::run_study("football_sweep", argc, argv, [](check::Study& study) {
        const auto& out = study.results_dir();
        par::set_threads(1);  // one thread per process: the cases run as forked processes
        std::signal(SIGUSR1, request_stop_signal);
        // Development switches: FOOTBALL_END=<s> caps the simulated time, FOOTBALL_ONLY=<case> runs one
        // case (no checks), FOOTBALL_MIRROR=1 with it: the mirror R_x roll sign; FOOTBALL_MIRROR_WALL and
        // FOOTBALL_CASE below.
        // FOOTBALL_CASE=<file> (development, with FOOTBALL_ONLY): a copy of the case file instead of the
        // study's, e.g. the friction decay c_d of Eq 2-35 (README "Friction with c_d > 0").
        const char* case_file = std::getenv("FOOTBALL_CASE");
        if (case_file && !std::getenv("FOOTBALL_ONLY")) throw InputError("football_sweep: FOOTBALL_CASE needs FOOTBALL_ONLY (no checks on a variant)");
        g_case_scene = explicit_case::hand_scene(explicit_case::read_case(
            case_file ? std::filesystem::path(case_file) : study.source_dir() / "studies/football_sweep/football_sweep.toml"));
        // FOOTBALL_MIRROR_WALL=0|1 (development, with FOOTBALL_ONLY): the fingers against their mirror
        // images across the football's symmetry plane off or on (the case file's [hand] mirror_contact,
        // on in the judged runs; README reconstruction 9).
        if (const char* w = std::getenv("FOOTBALL_MIRROR_WALL")) {
            if (!std::getenv("FOOTBALL_ONLY")) throw InputError("football_sweep: FOOTBALL_MIRROR_WALL needs FOOTBALL_ONLY (no checks on a variant)");
            g_case_scene.mirror_contact = std::string(w) != "0";
        }
        RunOptions o;
        o.window = kWindow;  // the judged window (README "Cost"): checks use t <= kWindow only
        // The judged runs start at kStart (README "Cost": the fingers spin up undeformed and settle
        // into their damped steady rotation before the first contact), with and without --full;
        // --full adds Case 4 from t = 0 to 3 s (shown: how much the later start changes).
        o.start = std::getenv("FOOTBALL_START") ? std::atof(std::getenv("FOOTBALL_START")) : kStart;
        o.end = std::getenv("FOOTBALL_END") ? std::atof(std::getenv("FOOTBALL_END")) : o.window;
        o.out = out;
        o.cases = kCases;
        if (const char* only = std::getenv("FOOTBALL_ONLY")) o.cases = {kCases.at(std::atoi(only) - 1)};
        const bool full = study.full() && !std::getenv("FOOTBALL_ONLY");
        // FOOTBALL_REPLOT=1: no runs, the outputs and checks from the run records already in the
        // results folder (e.g. after changing a figure).
        if (std::getenv("FOOTBALL_REPLOT")) {
            // The results folder is a fresh staging folder (io::RunFolder) inside the published one:
            // take the last run's records from there.
            for (const auto& e : std::filesystem::directory_iterator(out.parent_path()))
                if (e.path().extension() == ".json" && e.path().filename().string().find("-case-") != std::string::npos)
                    std::filesystem::copy_file(e.path(), out / e.path().filename(), std::filesystem::copy_options::overwrite_existing);
        } else {
            // The co-rotating damping variant (fingers only, to the lag time) runs beside the cases.
            std::fflush(stdout);
            const pid_t lag_pid = fork();
            if (lag_pid < 0) throw SolverError("football_sweep: fork() failed");
            if (lag_pid == 0) {
                RunOptions lo = o;
                lo.start = 0.0, lo.end = kLagTime + 1e-3, lo.window = lo.end, lo.name = "corotating", lo.cases = {kCases[0]};
                Variant corot;
                corot.frame = DampingFrame::drum, corot.football = false;
                run(corot, lo);
                std::fflush(stdout);
                std::_Exit(0);
            }
            if (full) {  // Case 4 from t = 0 to the thesis's 3 s, beside the judged runs
                std::fflush(stdout);
                const pid_t full_pid = fork();
                if (full_pid < 0) throw SolverError("football_sweep: fork() failed");
                if (full_pid == 0) {
                    RunOptions fo = o;
                    fo.start = 0.0, fo.end = 3.0, fo.window = 3.0, fo.name = "full", fo.cases = {kCases[3]};
                    run(Variant{}, fo);
                    std::fflush(stdout);
                    std::_Exit(0);
                }
            }
            o.dumps = std::filesystem::temp_directory_path() / fmt::format("football_sweep-{}", getpid());
            Variant cases_variant;
            // FOOTBALL_MIRROR=1 (development, with FOOTBALL_ONLY): the mirror reading of R_x
            // (HandSpec::roll_sign = -1, README reconstruction 3).
            if (std::getenv("FOOTBALL_MIRROR") && std::getenv("FOOTBALL_ONLY")) cases_variant.roll_sign = -1.0;
            run(cases_variant, o);
            wait_children();
            std::filesystem::remove_all(o.dumps);
        }
        std::map<int, Record> res;
        for (const auto& c : o.cases) {
            res[c.id] = load(out / fmt::format("football-case-{}.json", c.id));
            study.record_run({res[c.id].summary.value("name", ""), res[c.id].summary});
            write_case(out / fmt::format("case-{}.dat", c.id), res[c.id]);
        }
        const Record corot = load(out / "corotating-case-1.json");
        study.record_run({"corotating-fingers-only", corot.summary});
        for (const auto& c : o.cases)
            if (c.id == 4 || c.id == 2) write_snapshots(out, fmt::format("snap-case-{}", c.id), res[c.id], Variant{}, c, o.start);
        if (std::getenv("FOOTBALL_ONLY")) return;

        // --- Table 4-2: counts ---
        const HandModel model(football_scene(kCases[3], Variant{}));
        const auto& m = model.mesh();
        const double ea = m.blocks[m.blocks_of_part("finger-A")[0]].size(), ec = m.blocks[m.blocks_of_part("finger-C")[0]].size();
        study.check("table-4-2/finger-elements", std::vector<double>{ea, ec});
        study.check("table-4-2/finger-nodes", std::vector<double>{double(model.part_nodes("finger-A").size()),
                                                                   double(model.part_nodes("finger-C").size())});
        study.check("table-4-2/football-elements", m.blocks[m.blocks_of_part("football")[0]].size());
        study.check("table-4-2/football-nodes", model.part_nodes("football").size(),
                    fmt::format("football mass {:.4f} kg (half model), density {:.1f} kg/m3", model.part_mass("football"),
                                model.scene().objects[0].material.density));

        // --- Table 4-4 ---
        // Window-limited views of a record.
        auto rows = [&](const Record& r) {
            std::size_t n = 0;
            while (n < r.t.size() && r.t[n] <= r.window + 1e-12) ++n;
            return n;
        };
        auto max_y = [&](const Record& r) {
            std::size_t k = 0;
            for (std::size_t i = 0; i < rows(r); ++i)
                if (r.y[i] > r.y[k]) k = i;
            return std::pair{1e3 * (r.y[k] - r.y0), r.t[k]};
        };
        std::vector<double> uy, sig;
        std::string notes_y, notes_s;
        for (const auto& c : kCases) {
            const Record& r = res.at(c.id);
            const auto [u, t] = max_y(r);
            uy.push_back(u);
            sig.push_back(r.s_cfc_max / 1e6);
            notes_y += fmt::format("{}case {}: {:.2f} mm at {:.3f} s", notes_y.empty() ? "" : "; ", c.id, u, t);
            notes_s += fmt::format("{}case {}: raw 0.1 ms maxima {:.4f} MPa", notes_s.empty() ? "" : "; ", c.id, r.s_raw_max / 1e6);
        }
        study.check("table-4-4/max-y-displacement", uy, notes_y);
        study.check("table-4-4/max-stress", sig, notes_s);
        auto argmin = [](const std::vector<double>& v) { return fmt::format("case-{}", 1 + std::min_element(v.begin(), v.end()) - v.begin()); };
        study.trend("table-4-4/case-2-smallest-displacement", argmin(uy), fmt::format("max y [mm] by case: {:.2f}", fmt::join(uy, ", ")));
        study.trend("table-4-4/case-2-smallest-stress", argmin(sig), fmt::format("max stress [MPa] by case: {:.4f}", fmt::join(sig, ", ")));

        // --- Fig 4-3, 4-4: Case 4 ---
        const Record& c4 = res.at(4);
        const auto [u4, t4] = max_y(c4);
        study.check("fig-4-3/case-4/time-of-max-y", t4, fmt::format("maximum {:.2f} mm", u4));
        study.check("fig-4-3/case-4/above-experiment", u4 - 19.4);
        // Before the first finger touches the football (from the start on).
        const double first_touch = c4.pairs.count("fingers on football") ? c4.pairs.at("fingers on football").first : -1.0;
        double rel0 = 0;
        int nrel = 0;
        for (std::size_t i = 0; i < rows(c4); ++i)
            if (first_touch < 0 || c4.t[i] < first_touch) rel0 += c4.rel_x[i], ++nrel;
        rel0 = 1e3 * rel0 / std::max(1, nrel);
        study.check("fig-4-4/case-4/initial-relative-x", rel0);
        std::size_t kmax = 0;
        for (std::size_t i = 0; i < rows(c4); ++i)
            if (c4.rel_x[i] > c4.rel_x[kmax]) kmax = i;
        double after = c4.rel_x[kmax];
        for (std::size_t i = kmax; i < rows(c4); ++i) after = std::min(after, c4.rel_x[i]);
        const double relmax = 1e3 * c4.rel_x[kmax], relafter = 1e3 * after;
        study.trend_holds("fig-4-4/case-4/grows-then-shrinks", relmax > rel0 + 2 && relmax - relafter > 2,
                          fmt::format("{:.2f} mm before contact, up to {:.2f} mm at {:.3f} s, then down to {:.2f} mm by {:.2f} s",
                                      rel0, relmax, c4.t[kmax], relafter, c4.window));

        // --- --full: Case 4 from t = 0 to 3 s against the judged run (shown, runs.json and a table) ---
        if (std::filesystem::exists(out / "full-case-4.json")) {
            const Record f4 = load(out / "full-case-4.json");
            study.record_run({"full-case-4 (0-3 s)", f4.summary});
            write_case(out / "case-4-full.dat", f4);
            const auto [uf, tf] = max_y(f4);
            study.write_markdown("full-case-4.md", fmt::format(
                "| Case 4 | start | max y (mm) | at (s) | max stress CFC 60 (MPa) | raw (MPa) |\n|---|---|---|---|---|---|\n"
                "| judged run (to {} s) | {} s | {:.2f} | {:.3f} | {:.4f} | {:.4f} |\n| --full (to 3 s) | 0 s | {:.2f} | {:.3f} | {:.4f} | {:.4f} |\n",
                c4.window, o.start, u4, t4, c4.s_cfc_max / 1e6, c4.s_raw_max / 1e6, uf, tf, f4.s_cfc_max / 1e6, f4.s_raw_max / 1e6));
        }

        // --- Fig 4-10, 4-11: Case 2 ---
        const Record& c2 = res.at(2);
        const std::size_t n2 = rows(c2);
        std::vector<std::pair<double, std::string>> imp;
        for (const auto& f : kFingers) imp.emplace_back(c2.impulse.at(f)[n2 - 1], f);
        std::sort(imp.begin(), imp.end());
        std::vector<std::string> least{imp[0].second, imp[1].second};
        std::sort(least.begin(), least.end());
        std::string imps;
        for (const auto& [v, f] : imp) imps += fmt::format("{}{} {:.3f}", imps.empty() ? "" : ", ", f, v);
        study.trend("fig-4-10/case-2/least-contact", least[0] + " and " + least[1],
                    fmt::format("contact impulse (N s) by finger: {}", imps));
        std::string largest;
        double best = -1, t_b = 0;
        std::string tips;
        for (const auto& f : kFingers) {
            double mx = 0, tm = 0;
            for (std::size_t i = 0; i < n2; ++i)
                if (std::abs(c2.tip_y.at(f)[i]) > mx) mx = std::abs(c2.tip_y.at(f)[i]), tm = c2.t[i];
            tips += fmt::format("{}{} {:.2f} mm at {:.3f} s", tips.empty() ? "" : ", ", f, 1e3 * mx, tm);
            if (mx > best) best = mx, largest = f;
            if (f == "B") t_b = tm;
        }
        study.trend("fig-4-11/case-2/largest-tip-deflection", largest, "largest |tip u_y|: " + tips);
        study.check("fig-4-11/case-2/time-of-largest-tip-deflection", t_b, "largest |tip u_y|: " + tips);

        // --- damping frame ---
        const Record& c1 = res.at(1);
        std::vector<double> lag_abs, lag_rot;
        for (const auto& f : kFingers) lag_abs.push_back(1e3 * c1.lag.at(f)), lag_rot.push_back(1e3 * corot.lag.at(f));
        study.check("sec-4-2/damping/tip-lag-D", lag_abs[3]);
        study.check("sec-4-2/damping/tip-lag-absolute", lag_abs, fmt::format("at t = {} s", kLagTime));
        study.check("sec-4-2/damping/tip-lag-corotating", lag_rot, fmt::format("at t = {} s", kLagTime));

        // --- numerical health ---
        double pen = 0, bal = 0, hg = 0;
        for (const auto& [id, r] : res)
            pen = std::max(pen, r.pen_window), bal = std::max(bal, r.summary.at("energy_balance_relative_error").get<double>()),
            hg = std::max(hg, r.summary.at("hourglass_fraction_of_internal").get<double>());
        std::string clear;
        for (const auto& [pairname, d] : c2.min_clearance) clear += fmt::format("{}{} {:.1f} mm", clear.empty() ? "" : ", ", pairname, 1e3 * d);
        study.trend_holds("contact/penetration-below-limit", pen < 0.2,
                          fmt::format("largest penetration {:.3f} of the element size (all pairs, all cases, t <= {} s)", pen, o.window),
                          "closest surface nodes of neighbouring fingers (Case 2): " + clear);
        // The run summaries' energy health (EnergySummary over the judged window, the measures and
        // limits that check/run_health judges every run by), over all cases.
        study.trend_holds("energy/balance-and-hourglass", bal <= check::kMaxBalanceError && hg <= check::kMaxHourglassFraction,
                          fmt::format("largest balance error {:.2g} of the largest total energy (initial + work done), hourglass / "
                                      "internal {:.3f} (largest values up to {} s)", bal, hg, o.window));
        study.plot();
    });
}
