#include "explicit/relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {
namespace {

// The staged dead load: factor(t) goes from `from` to `to` along a smoothstep over [start, start + ramp].
class StagedLoad final : public ForceProvider {
public:
    StagedLoad(std::vector<int> nodes, const Vec3& force) : nodes_(std::move(nodes)), force_(force) {}
    std::string name() const override { return "staged dead load"; }
    void add_forces(double t, const NodalState&, std::vector<Vec3>& force, std::vector<Vec3>&) override {
        const Vec3 f = factor(t) * force_;
        for (int n : nodes_) force[n] += f;
    }
    double factor(double t) const {
        if (!(ramp_ > 0.0) || t >= start_ + ramp_) return to_;
        if (t <= start_) return from_;
        const double s = (t - start_) / ramp_;
        return from_ + (to_ - from_) * s * s * (3.0 - 2.0 * s);
    }
    void next(double target, double start, double ramp) {
        from_ = to_;
        to_ = target;
        start_ = start;
        ramp_ = ramp;
    }

private:
    std::vector<int> nodes_;
    Vec3 force_;
    double from_ = 0.0, to_ = 0.0, start_ = 0.0, ramp_ = 0.0;
};

}  // namespace

RelaxationResult relax(ExplicitModel& model, const std::vector<int>& nodes, const Vec3& force_per_node,
                       const std::vector<double>& load_factors, const RelaxationOptions& o) {
    auto bad = [](const std::string& what) { throw InputError("relax: " + what); };
    if (!(o.omega_1 > 0.0) || !std::isfinite(o.omega_1)) bad(fmt::format("omega_1 must be positive (got {})", o.omega_1));
    if (!(o.ke_fraction > 0.0 && o.ke_fraction < 1.0)) bad("ke_fraction must lie in (0, 1)");
    if (!(o.ramp_periods >= 0.0) || !(o.max_stage_periods > o.ramp_periods)) bad("need 0 <= ramp_periods < max_stage_periods");
    if (!(o.samples_per_period >= 4.0)) bad("samples_per_period must be >= 4");
    if (load_factors.empty()) bad("no load factors");
    if (nodes.empty()) bad("no loaded nodes");

    const double period = 2.0 * std::numbers::pi / o.omega_1, ramp = o.ramp_periods * period;
    model.set_mass_damping(2.0 * o.omega_1);  // critical damping of the first mode (Eq 2-39)
    auto provider = std::make_unique<StagedLoad>(nodes, force_per_node);
    StagedLoad& load = *provider;
    model.add_force_provider(std::move(provider));
    load.next(load_factors[0], 0.0, ramp);

    ExplicitOptions so = o.solver;
    so.end_time = o.max_stage_periods * period * static_cast<double>(load_factors.size());
    so.history_interval = period / o.samples_per_period;
    so.pvd_path.clear();
    ExplicitSolver solver(model, so);

    RelaxationResult result;
    std::size_t stage = 0;
    double stage_start = 0.0, peak = 0.0;
    std::string failure;
    solver.observer = [&](const ExplicitSolver& s) {
        if (stage >= load_factors.size()) return;
        const double t = s.time(), ke = s.history().kinetic.back();
        peak = std::max(peak, ke);
        if (t - stage_start > o.max_stage_periods * period) {
            failure = fmt::format("stage {} (load factor {}) did not converge in {} periods: kinetic energy {:.3g} J, {:.3g} of its peak",
                                  stage + 1, load_factors[stage], o.max_stage_periods, ke, peak > 0 ? ke / peak : 0.0);
            s.request_stop();
            return;
        }
        if (t - stage_start < ramp || !(peak > 0.0) || ke > o.ke_fraction * peak) return;
        RelaxationStage done;
        done.load_factor = load_factors[stage];
        done.time = t;
        done.peak_kinetic = peak;
        done.final_kinetic = ke;
        const NodalState& st = s.state();
        done.displacement.resize(st.x.size());
        for (std::size_t i = 0; i < st.x.size(); ++i) done.displacement[i] = st.x[i] - st.X[i];
        result.stages.push_back(std::move(done));
        if (++stage == load_factors.size()) {
            s.request_stop();
            return;
        }
        load.next(load_factors[stage], t, ramp);
        stage_start = t;
        peak = 0.0;
    };
    result.summary = solver.run();
    if (!failure.empty()) throw SolverError("relax: " + failure);
    if (result.stages.size() != load_factors.size())
        throw SolverError(fmt::format("relax: only {} of {} load stages converged by t = {:.4g} s", result.stages.size(),
                                      load_factors.size(), solver.time()));
    return result;
}

}  // namespace fem
