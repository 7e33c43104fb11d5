#include "multibody/lumped_bird.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "damping/gsl_guard.hpp"

namespace fem::multibody {
namespace {

Vec2 e(double p) { return {std::cos(p), std::sin(p)}; }
Vec2 eperp(double p) { return {-std::sin(p), std::cos(p)}; }
Vec2 rotate(const Vec2& v, double a) { return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()}; }

// The right-hand side as GSL wants it; exceptions are parked (not thrown through C).
struct OdeContext {
    const LumpedBirdModel* model = nullptr;
    std::exception_ptr error;
};

// Hessian of V (gravity and the springs) in (phi1, phi2); the rest angles do not enter.
Eigen::Matrix2d potential_hessian(const LumpedBird& b, const LumpedBirdState& s) {
    const double S1 = b.m1 * b.c1 + b.m2 * b.L1, S2 = b.m2 * b.l2;
    Eigen::Matrix2d K;
    K << -b.g * S1 * std::sin(s.phi1) + b.k1 + b.k2, -b.k2, -b.k2, -b.g * S2 * std::sin(s.phi2) + b.k2;
    return K;
}

int rhs(double t, const double y[], double dydt[], void* params) {
    auto* ctx = static_cast<OdeContext*>(params);
    try {
        const LumpedBirdState s{t, y[0], y[1], y[2], y[3]};
        const Vec2 a = ctx->model->accelerations(s);
        dydt[0] = y[2];
        dydt[1] = y[3];
        dydt[2] = a.x();
        dydt[3] = a.y();
        return GSL_SUCCESS;
    } catch (...) {
        ctx->error = std::current_exception();
        return GSL_EBADFUNC;
    }
}

}  // namespace

void LumpedBird::validate() const {
    auto bad = [](const std::string& what) { throw InputError("LumpedBird: " + what); };
    for (auto [v, name] : {std::pair{m1, "m1"}, {c1, "c1"}, {I1, "I1"}, {L1, "L1"}, {m2, "m2"}, {l2, "l2"}, {I2, "I2"},
                           {k1, "k1"}, {k2, "k2"}, {alpha, "alpha"}, {g, "g"}})
        if (!(v >= 0.0) || !std::isfinite(v)) bad(fmt::format("{} must be finite and >= 0 (got {})", name, v));
    if (!(L1 > 0.0)) bad("L1 must be positive");
    // det M >= (I1 + m1 c1^2)(I2 + m2 l2^2) + m2 L1^2 I2 > 0 needs both links to carry inertia.
    if (!((I1 + m1 * c1 * c1 + m2 * L1 * L1) > 0.0 && (I2 + m2 * l2 * l2) > 0.0 && (I1 + m1 * c1 * c1 > 0.0 || I2 > 0.0)))
        bad("the mass matrix is singular: give both links inertia");
}

ShackleMotion ShackleMotion::fixed(const Vec2& paw) {
    ShackleMotion m;
    m.pivot0 = paw;
    m.paw0 = paw;
    return m;
}

ShackleMotion ShackleMotion::translation_step(const Vec2& paw, const Vec2& velocity, double duration) {
    ShackleMotion m = fixed(paw);
    m.times = {0.0, duration};
    m.pivot_velocity = {velocity, Vec2(0.0, 0.0)};
    m.rate = {0.0, 0.0};
    return m;
}

ShackleMotion ShackleMotion::rotation_step(const Vec2& paw, const Vec2& pivot, double rate_, double duration) {
    ShackleMotion m;
    m.pivot0 = pivot;
    m.paw0 = paw;
    m.times = {0.0, duration};
    m.pivot_velocity = {Vec2(0.0, 0.0), Vec2(0.0, 0.0)};
    m.rate = {rate_, 0.0};
    return m;
}

void ShackleMotion::validate() const {
    if (times.empty() || times[0] != 0.0) throw InputError("ShackleMotion: times must start at 0");
    if (pivot_velocity.size() != times.size() || rate.size() != times.size())
        throw InputError("ShackleMotion: one pivot velocity and one rate per segment");
    for (std::size_t k = 1; k < times.size(); ++k)
        if (!(times[k] > times[k - 1])) throw InputError("ShackleMotion: times must increase");
}

int ShackleMotion::segment(double t) const {
    int k = 0;
    while (k + 1 < static_cast<int>(times.size()) && t >= times[k + 1]) ++k;
    return k;
}

double ShackleMotion::angle(double t) const {
    double a = 0.0;
    for (int k = 0; k < static_cast<int>(times.size()); ++k) {
        const double end = k + 1 < static_cast<int>(times.size()) ? std::min(t, times[k + 1]) : t;
        if (end > times[k]) a += rate[k] * (end - times[k]);
    }
    return a;
}

Vec2 ShackleMotion::pivot(double t) const {
    Vec2 p = pivot0;
    for (int k = 0; k < static_cast<int>(times.size()); ++k) {
        const double end = k + 1 < static_cast<int>(times.size()) ? std::min(t, times[k + 1]) : t;
        if (end > times[k]) p += pivot_velocity[k] * (end - times[k]);
    }
    return p;
}

Vec2 ShackleMotion::position(double t) const { return pivot(t) + rotate(paw0 - pivot0, angle(t)); }

Vec2 ShackleMotion::velocity(double t) const {
    const int k = segment(t);
    const Vec2 r = position(t) - pivot(t);
    return pivot_velocity[k] + rate[k] * Vec2(-r.y(), r.x());
}

Vec2 ShackleMotion::acceleration(double t) const {
    const int k = segment(t);
    return -rate[k] * rate[k] * (position(t) - pivot(t));
}

LumpedBirdModel::LumpedBirdModel(LumpedBird bird, ShackleMotion motion) : bird_(bird), motion_(std::move(motion)) {
    bird_.validate();
    motion_.validate();
}

Eigen::Matrix2d LumpedBirdModel::mass_matrix(const LumpedBirdState& s) const {
    const LumpedBird& b = bird_;
    Eigen::Matrix2d M;
    M(0, 0) = b.I1 + b.m1 * b.c1 * b.c1 + b.m2 * b.L1 * b.L1;
    M(1, 1) = b.I2 + b.m2 * b.l2 * b.l2;
    M(0, 1) = M(1, 0) = b.m2 * b.L1 * b.l2 * std::cos(s.phi2 - s.phi1);
    return M;
}

Vec2 LumpedBirdModel::accelerations(const LumpedBirdState& s) const {
    const LumpedBird& b = bird_;
    const Eigen::Matrix2d M = mass_matrix(s);
    const double s1 = b.m1 * b.c1 + b.m2 * b.L1, s2 = b.m2 * b.l2;
    const double h = b.m2 * b.L1 * b.l2 * std::sin(s.phi2 - s.phi1);
    const Vec2 load = motion_.acceleration(s.t) + Vec2(0.0, b.g), bdot = motion_.velocity(s.t);
    const double spring1 = b.k1 * (s.phi1 - motion_.angle(s.t) - b.rest1), spring2 = b.k2 * (s.phi2 - s.phi1 - b.rest2);
    const Vec2 qdot(s.dphi1, s.dphi2);
    const Vec2 p = M * qdot + Vec2(s1 * eperp(s.phi1).dot(bdot), s2 * eperp(s.phi2).dot(bdot));  // dT/dq'
    Vec2 Q;
    Q.x() = h * s.dphi2 * s.dphi2 - s1 * eperp(s.phi1).dot(load) - spring1 + spring2 - b.alpha * p.x();
    Q.y() = -h * s.dphi1 * s.dphi1 - s2 * eperp(s.phi2).dot(load) - spring2 - b.alpha * p.y();
    return M.ldlt().solve(Q);
}

double LumpedBirdModel::kinetic_energy(const LumpedBirdState& s) const {
    const LumpedBird& b = bird_;
    const Vec2 bdot = motion_.velocity(s.t);
    const Vec2 v1 = bdot + b.c1 * s.dphi1 * eperp(s.phi1);
    const Vec2 v2 = bdot + b.L1 * s.dphi1 * eperp(s.phi1) + b.l2 * s.dphi2 * eperp(s.phi2);
    return 0.5 * (b.m1 * v1.squaredNorm() + b.I1 * s.dphi1 * s.dphi1 + b.m2 * v2.squaredNorm() + b.I2 * s.dphi2 * s.dphi2);
}

double LumpedBirdModel::potential_energy(const LumpedBirdState& s) const {
    const LumpedBird& b = bird_;
    const Vec2 base = motion_.position(s.t);
    const double y1 = base.y() + b.c1 * std::sin(s.phi1), y2 = base.y() + b.L1 * std::sin(s.phi1) + b.l2 * std::sin(s.phi2);
    const double d1 = s.phi1 - motion_.angle(s.t) - b.rest1, d2 = s.phi2 - s.phi1 - b.rest2;
    return b.g * (b.m1 * y1 + b.m2 * y2) + 0.5 * b.k1 * d1 * d1 + 0.5 * b.k2 * d2 * d2;
}

LumpedBirdSample LumpedBirdModel::sample(const LumpedBirdState& s) const {
    LumpedBirdSample out;
    out.state = s;
    out.paw = motion_.position(s.t);
    out.joint2 = out.paw + bird_.L1 * e(s.phi1);
    out.body_point = out.joint2 + rotate(bird_.body_point, s.phi2 - bird_.phi2_ref);
    out.kinetic = kinetic_energy(s);
    out.potential = potential_energy(s);
    return out;
}

std::vector<LumpedBirdSample> LumpedBirdModel::run(const LumpedBirdState& start, double end_time,
                                                   const LumpedBirdOptions& o) const {
    if (!(end_time > start.t)) throw InputError("LumpedBirdModel::run: end_time must be after the start");
    if (!(o.output_interval > 0.0)) throw InputError("LumpedBirdModel::run: output_interval must be positive");
    damping::detail::GslErrorsOff quiet;
    OdeContext ctx{this, nullptr};
    gsl_odeiv2_system sys{rhs, nullptr, 4, &ctx};
    gsl_odeiv2_driver* driver = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-6, o.abs_tolerance, o.rel_tolerance);
    std::vector<LumpedBirdSample> out;
    double y[4] = {start.phi1, start.phi2, start.dphi1, start.dphi2};
    double t = start.t;
    const LumpedBird& b = bird_;
    const double s1 = b.m1 * b.c1 + b.m2 * b.L1, s2 = b.m2 * b.l2;
    auto state = [&] { return LumpedBirdState{t, y[0], y[1], y[2], y[3]}; };
    // The velocity jump at a switch of the shackle's motion (impulse equations in the header).
    auto jump = [&](double at) {
        const Vec2 before = at <= motion_.times.front() ? Vec2(0.0, 0.0) : motion_.velocity(std::nextafter(at, -INFINITY));
        const Vec2 db = motion_.velocity(at) - before;  // the shackle is at rest before t = 0
        if (db.squaredNorm() == 0.0) return;
        const Eigen::Matrix2d M = mass_matrix(state());
        const Vec2 dq = M.ldlt().solve(Vec2(-s1 * eperp(y[0]).dot(db), -s2 * eperp(y[1]).dot(db)));
        y[2] += dq.x();
        y[3] += dq.y();
    };
    // Velocity jumps at switches at or before the start (t = 0: the motion starts).
    for (double sw : motion_.times)
        if (sw == t) jump(sw);
    out.push_back(sample(state()));
    const double tiny = 1e-12 * std::max(1.0, end_time);
    double next_output = t + o.output_interval;
    while (t < end_time - tiny) {
        double target = std::min(next_output, end_time);
        double switch_at = INFINITY;
        for (double sw : motion_.times)
            if (sw > t + tiny && sw < switch_at) switch_at = sw;
        const bool at_switch = switch_at <= target + tiny;
        if (at_switch) target = switch_at;
        const int status = gsl_odeiv2_driver_apply(driver, &t, target, y);
        if (ctx.error) {
            gsl_odeiv2_driver_free(driver);
            std::rethrow_exception(ctx.error);
        }
        if (status != GSL_SUCCESS) {
            gsl_odeiv2_driver_free(driver);
            throw SolverError(fmt::format("LumpedBirdModel::run: GSL's integrator failed at t = {} s: {}", t, gsl_strerror(status)));
        }
        if (at_switch) {
            jump(switch_at);
            gsl_odeiv2_driver_reset(driver);
        }
        out.push_back(sample(state()));
        if (std::abs(t - next_output) <= tiny) next_output += o.output_interval;
    }
    gsl_odeiv2_driver_free(driver);
    return out;
}

LumpedBirdState LumpedBirdModel::equilibrium(double t, const LumpedBirdState& guess) const {
    const LumpedBird& b = bird_;
    // The shackle frozen as it is at time t (its rotation folded into the J1 spring's rest angle),
    // the chain overdamped and run to rest, then Newton on dV/dq = 0 with the exact Hessian.
    LumpedBird frozen = b;
    frozen.rest1 = b.rest1 + motion_.angle(t);
    LumpedBirdState s = guess;
    s.t = 0.0;
    s.dphi1 = s.dphi2 = 0.0;
    const double S1 = b.m1 * b.c1 + b.m2 * b.L1, S2 = b.m2 * b.l2;
    auto gradient = [&](const LumpedBirdState& q) {
        const double d2 = q.phi2 - q.phi1 - frozen.rest2;
        return Vec2(b.g * S1 * std::cos(q.phi1) + b.k1 * (q.phi1 - frozen.rest1) - b.k2 * d2, b.g * S2 * std::cos(q.phi2) + b.k2 * d2);
    };
    {
        // Overdamped: alpha = 2 x an upper bound of the chain's frequencies; runs of 20 / omega_bound
        // until the gradient is small (each run removes the slow part by exp(-20 omega_min^2 / omega_bound^2)).
        const Eigen::Matrix2d M = mass_matrix(s);
        const double kbound = b.k1 + 2.0 * b.k2 + b.g * (S1 + S2);
        const double omega = std::sqrt(kbound / std::min(M(0, 0), M(1, 1)));
        frozen.alpha = 2.0 * omega;
        const LumpedBirdModel heavy(frozen, ShackleMotion::fixed(motion_.position(t)));
        LumpedBirdOptions o;
        o.output_interval = 20.0 / omega;
        const double scale = b.g * (S1 + S2) + b.k1 + b.k2;
        for (int run = 0; run < 2000 && gradient(s).norm() > 1e-3 * scale; ++run) s = heavy.run(s, s.t + 20.0 / omega, o).back().state;
    }
    for (int it = 0; it < 50; ++it) {
        const Vec2 step = potential_hessian(b, s).ldlt().solve(gradient(s));
        s.phi1 -= step.x();
        s.phi2 -= step.y();
        if (step.norm() < 1e-14) break;
    }
    s.t = t;
    s.dphi1 = s.dphi2 = 0.0;
    const Vec2 w2 = linearised_omega_squared(s);
    if (!(w2.minCoeff() > 0.0) || !(gradient(s).norm() < 1e-9 * (b.g * (S1 + S2) + b.k1 + b.k2)))
        throw SolverError(fmt::format("LumpedBirdModel::equilibrium: no stable rest state found (omega^2 = {}, {})", w2.x(), w2.y()));
    return s;
}

Vec2 LumpedBirdModel::linearised_omega_squared(const LumpedBirdState& s) const {
    return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>(potential_hessian(bird_, s), mass_matrix(s)).eigenvalues();
}

Eigen::Matrix2d LumpedBirdModel::linearised_modes(const LumpedBirdState& s) const {
    return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>(potential_hessian(bird_, s), mass_matrix(s)).eigenvectors();
}

}  // namespace fem::multibody
