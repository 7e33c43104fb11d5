#include "contact/contact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/hdf5.hpp"

namespace fem::contact {

// One node-to-segment pass: the nodes of `slave` against the faces of `master`.
struct ContactInterface::Pass {
    const ContactSurface* slave = nullptr;
    const ContactSurface* master = nullptr;
    bool rigid = false;
    CandidateList list;
    std::vector<double> depth, lateral, size;  // per master segment: capture region (search.hpp), sqrt(area)
    double turn_factor = 1.0;                   // f of the rebuild rule (search.hpp)
    std::vector<int> master_nodes;      // every node the master faces use
    std::vector<Vec3> slave_x;          // gathered slave positions
    struct History {
        Vec3 force = Vec3::Zero();      // elastic tangential force (friction spring)
        int segment = -1;               // segment of the last cycle (-1: not in contact)
        int side = 0;                   // two-sided (shell) segment: the side the node touches (+-1)
        Vec3 normal = Vec3::Zero();     // the contact normal of the last cycle (side applied)
    };
    std::vector<History> history;       // per slave node
    // ContactOptions::track_approach_side: per slave node, the side of the master surface it was last
    // seen on (+1 in front or in contact, -1 behind, 0 not yet seen near a face).
    std::vector<signed char> approach;
    // ContactOptions::skip_far_candidates: each master segment's box of this evaluation (built on
    // first use: `stamp` counts the evaluations), and the candidates phase 1 left unprojected.
    std::vector<SegmentBox> box;
    std::vector<long> box_stamp;
    long stamp = 0;
    std::vector<int> skipped;
    double edge_tolerance = 0.05;

    const SegmentBox& box_of(int s, std::span<const Vec3> x) {
        if (box_stamp[s] != stamp) {
            const auto& seg = master->segments[s];
            box[s] = seg.count == 4 ? segment_box(x[seg.n[0]], x[seg.n[1]], x[seg.n[2]], x[seg.n[3]])
                                    : segment_box(x[seg.n[0]], x[seg.n[1]], x[seg.n[2]]);
            box_stamp[s] = stamp;
        }
        return box[s];
    }

    // False only when candidate s provably cannot capture the node at p (pen < 0) or, a capture with
    // penetration pen >= 0 found, cannot veto it (evaluate's rules). Either needs the tangential
    // offset t <= L (the edge tolerance; a front veto: t <= 1e-9 size) and a raw gap g (Projection::gap
    // before the offsets O are taken off) with, for a capture, -depth <= g - O < 0, for a veto
    // 0 < g - O < pen. So the node is within |g| + t <= (depth or pen) + O + L of the segment, and
    // (one-sided segment, SegmentBox's height bounds) a capture has height <= w + O + L (g < O), a
    // veto -w - L <= height <= w + pen + O + L (O < g < pen + O). Slack 1e-9 size for rounding.
    bool may_matter(int s, std::span<const Vec3> x, const Vec3& p, double node_offset, double pen) {
        const auto& seg = master->segments[s];
        const SegmentBox& b = box_of(s, x);
        const double O = seg.offset + node_offset;
        const double L = (std::max(edge_tolerance, 1e-9) + 1e-9) * size[s];
        const double reach = (pen < 0.0 ? depth[s] : pen) + O + L;
        if (b.distance_below(p) > reach) return false;
        if (!seg.two_sided && b.normal_bounded) {
            const double h = b.height(p);
            if (h > b.w + std::max(pen, 0.0) + O + L) return false;  // in front
            if (pen >= 0.0 && h < -b.w - L) return false;             // behind: no veto
        }
        return true;
    }

    Pass(const ContactSurface& s, const ContactSurface& m, bool is_rigid, const ContactOptions& o)
        : slave(&s), master(&m), rigid(is_rigid),
          list(o.margin > 0 ? o.margin : 0.25 * m.mean_segment_size(), o.max_rebuild_interval) {
        std::set<int> nodes;
        double slave_offset = 0.0;
        for (double t : s.node_offset) slave_offset = std::max(slave_offset, t);
        for (const auto& seg : m.segments) {
            const double h = std::sqrt(seg.area);
            size.push_back(h);
            // A node in contact lies within depth behind the face (its offset contact surface, shell
            // thickness: both offsets added) and edge_tolerance x h beside it.
            depth.push_back((std::isfinite(seg.depth) ? seg.depth : h) + seg.offset + slave_offset);
            lateral.push_back(o.edge_tolerance * h);
            if (h > 0) turn_factor = std::max(turn_factor, 1.0 + 2.0 * depth.back() / h);
            for (int i = 0; i < seg.count; ++i) nodes.insert(seg.n[i]);
        }
        master_nodes.assign(nodes.begin(), nodes.end());
        history.resize(s.nodes.size());
        if (o.track_approach_side) approach.assign(s.nodes.size(), 0);
        box.resize(m.segments.size());
        box_stamp.assign(m.segments.size(), -1);
        edge_tolerance = o.edge_tolerance;
        slave_x.resize(s.nodes.size());
    }
};

ContactInterface::ContactInterface(std::string name, ContactSurface slave, ContactSurface master, ContactOptions o)
    : name_(std::move(name)), opt_(o), slave_(std::make_unique<ContactSurface>(std::move(slave))),
      master_(std::make_unique<ContactSurface>(std::move(master))) {
    validate_options();
    if (slave_->nodes.empty() || master_->segments.empty())
        throw InputError(fmt::format("contact '{}': the slave side has no nodes or the master side no faces", name_));
    if (slave_->rigid)
        throw InputError(fmt::format("contact '{}': the slave side '{}' is rigid; make the rigid part the master", name_,
                                     slave_->name));
    if (slave_->node_size.size() != slave_->nodes.size())
        throw InputError(fmt::format("contact '{}': the slave surface '{}' has no node sizes (build it with "
                                     "ContactSurface::from_part)",
                                     name_, slave_->name));
    passes_.push_back(std::make_unique<Pass>(*slave_, *master_, master_->rigid, opt_));
    if (opt_.two_way) {
        if (master_->rigid)
            throw InputError(fmt::format("contact '{}': two-way contact needs a deformable master (the rigid part "
                                         "'{}' has no slave nodes)",
                                         name_, master_->name));
        if (master_->nodes.empty() || slave_->segments.empty())
            throw InputError(fmt::format("contact '{}': two-way contact needs faces and nodes on both sides", name_));
        passes_.push_back(std::make_unique<Pass>(*master_, *slave_, false, opt_));
    }
    if (opt_.track_approach_side)
        for (const auto& P : passes_)
            for (const auto& seg : P->master->segments)
                if (seg.two_sided)
                    throw InputError(fmt::format("contact '{}': track_approach_side needs one-sided master faces; '{}' has "
                                                 "two-sided shell faces (they keep their own side)",
                                                 name_, P->master->name));
}

void ContactInterface::validate_options() const {
    opt_.friction.validate(fmt::format("contact '{}'", name_).c_str());
    if (!(opt_.penalty_scale > 0.0) || !(opt_.edge_tolerance >= 0.0) || !(opt_.margin >= 0.0))
        throw InputError(fmt::format("contact '{}': penalty_scale {} must be > 0, edge_tolerance {} and margin {} >= 0",
                                     name_, opt_.penalty_scale, opt_.edge_tolerance, opt_.margin));
}

ContactInterface::~ContactInterface() = default;
ContactInterface::ContactInterface(ContactInterface&&) noexcept = default;

long ContactInterface::rebuilds() const { return passes_[0]->list.rebuilds(); }
long ContactInterface::cycles() const { return passes_[0]->list.cycles(); }

void ContactInterface::check(std::span<const Vec3> x) const {
    auto bad = [&](const ContactSurface& s) {
        for (int n : s.nodes)
            if (n < 0 || n >= static_cast<int>(x.size())) return n;
        for (const auto& seg : s.segments)
            for (int i = 0; i < seg.count; ++i)
                if (seg.n[i] < 0 || seg.n[i] >= static_cast<int>(x.size())) return seg.n[i];
        return -1;
    };
    int n = bad(*slave_);
    if (n < 0) n = bad(*master_);
    if (n >= 0)
        throw InputError(fmt::format("contact '{}': node {} is out of range (the model has {} nodes)", name_, n, x.size()));
}

void ContactInterface::evaluate(std::span<const Vec3> x, std::span<const Vec3> v, double t, double dt,
                                std::span<Vec3> force) {
    if (passes_[0]->list.cycles() == 0) check(x);
    stored_ = 0.0;
    f_master_.setZero();
    m_master_.setZero();
    points_.clear();
    double rigid_power = 0.0;
    std::vector<Vec3> zero_v;
    if (v.empty()) zero_v.assign(x.size(), Vec3::Zero());
    std::span<const Vec3> vs = v.empty() ? std::span<const Vec3>(zero_v) : v;

    for (std::size_t p = 0; p < passes_.size(); ++p) {
        Pass& P = *passes_[p];
        const auto& snodes = P.slave->nodes;
        const auto& segs = P.master->segments;
        std::span<const Vec3> xm = x, vm = vs;
        for (std::size_t i = 0; i < snodes.size(); ++i) P.slave_x[i] = x[snodes[i]];
        ++P.stamp;  // the segment boxes of the last evaluation are stale
        const bool self = !P.rigid;  // a node never contacts a face it belongs to
        const auto search0 = std::chrono::steady_clock::now();
        P.list.update(P.slave_x, xm, segs, P.depth, P.lateral, P.master_nodes, P.turn_factor, [&](int i, int s) {
            if (!self) return false;
            const auto& seg = segs[s];
            for (int k = 0; k < seg.count; ++k)
                if (seg.n[k] == snodes[i]) return true;
            return false;
        });
        search_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - search0).count();

        for (std::size_t i = 0; i < snodes.size(); ++i) {
            const int node = snodes[i];
            const Vec3& xs = x[node];
            // The admissible segment: the one of the last cycle while it stays admissible (contact
            // persists across the edge region of two faces), else the nearest. A gap within
            // round-off of zero is no penetration: a node on the plane of a coplanar side face
            // (two bars end to end) must not be captured by it instead of the face it entered.
            // Outside veto: a node in front of a face it projects onto (0 < gap < the candidate's
            // depth) is outside the master body, however deep it lies behind another face whose
            // edge tolerance it falls in (a finger beside a thick object, level with its faces).
            auto& hist = P.history[i];
            const std::span<const int> candidates = P.list.candidates(static_cast<int>(i));
            if (candidates.empty()) {  // most nodes, most cycles: no segment near, nothing to project
                if (hist.segment >= 0) hist = {};  // separated (a node out of contact has the default)
                continue;                          // (its approach side stays what it was)
            }
            // track_approach_side: what the projections show of the node's side (see the update below).
            signed char* approach = P.approach.empty() ? nullptr : &P.approach[i];
            bool front_on_face = false, behind_on_face = false;
            double nearest_distance = std::numeric_limits<double>::infinity(), nearest_gap = 0.0;
            int best = -1, best_side = 0;
            Projection bp;
            // Outside veto, two strengths. A face the node projects onto from in front vetoes any
            // capture. A face the node is only beside (within the edge tolerance) and clearly in
            // front of vetoes only a capture that is itself made beside its face: next to a convex
            // edge of a coarse faceted rim, inside means behind both planes, so a node in front of one
            // is outside. A node that projects squarely into a face it penetrates keeps that capture:
            // near a concave edge (a dent the fingers press into a soft object) it may lie in front
            // of the neighbour's extended plane while being inside the body.
            double nearest_front = std::numeric_limits<double>::infinity();
            double nearest_front_beside = std::numeric_limits<double>::infinity();
            const double node_offset = P.slave->node_offset.empty() ? 0.0 : P.slave->node_offset[i];
            // Projects the node onto candidate s: its veto terms, and (may_capture) whether it is the
            // admissible segment.
            auto consider = [&](int s, bool may_capture) {
                ++projections_;
                const auto& seg = segs[s];
                Projection pr = seg.count == 4
                                    ? project_quad(xs, xm[seg.n[0]], xm[seg.n[1]], xm[seg.n[2]], xm[seg.n[3]])
                                    : project_triangle(xs, xm[seg.n[0]], xm[seg.n[1]], xm[seg.n[2]]);
                // Shell thickness (surface.hpp): a two-sided segment is touched from the side the node
                // is on (kept while the contact lasts); the gap is measured from the offset surfaces.
                int side = 0;
                if (seg.two_sided) {
                    if (hist.segment >= 0 && hist.side != 0)  // in contact: stay on the same side, also
                        side = s == hist.segment ? hist.side : (pr.normal.dot(hist.normal) >= 0.0 ? 1 : -1);  // sliding on
                    else
                        side = pr.gap >= 0.0 ? 1 : -1;
                    pr.gap *= side;
                    pr.normal *= side;
                }
                pr.gap -= seg.offset + node_offset;
                const double tiny = 1e-9 * P.size[s];
                // In front: projecting inside the face (beyond round-off); or beside it within the edge
                // tolerance a capture would allow, clearly in front of its plane (a clamped bilinear
                // projection carries ~1e-7 x size of iteration error: two bars end to end).
                if (pr.gap > tiny && pr.tangential_offset <= tiny)
                    nearest_front = std::min(nearest_front, pr.gap);
                else if (pr.gap > 1e-3 * P.size[s] && pr.tangential_offset <= opt_.edge_tolerance * P.size[s])
                    nearest_front_beside = std::min(nearest_front_beside, pr.gap);
                if (approach) {
                    if (pr.tangential_offset <= opt_.edge_tolerance * P.size[s]) {
                        if (pr.gap >= -tiny) front_on_face = true;  // (on the face, within round-off: in front)
                        if (pr.gap < -tiny) behind_on_face = true;
                    }
                    if (pr.distance < nearest_distance) nearest_distance = pr.distance, nearest_gap = pr.gap;
                }
                if (!may_capture || !(pr.gap < -tiny) || -pr.gap > P.depth[s] ||
                    pr.tangential_offset > opt_.edge_tolerance * P.size[s] || (approach && *approach < 0))
                    return;
                const bool kept = s == hist.segment;
                if (best < 0 || kept || (best != hist.segment && pr.distance < bp.distance)) {
                    best = s;
                    best_side = side;
                    bp = pr;
                }
            };
            if (!opt_.skip_far_candidates || approach) {
                for (int s : candidates) consider(s, true);
            } else {
                // The same choice with fewer projections (same segment, same projection, same veto:
                // the forces to the last bit; test ContactPenalty.SkippingFarCandidatesChangesNothing).
                // (1) The segment of the last cycle first: while it stays admissible it is the one
                // whatever the others give, and they matter only through the outside veto. (2) A
                // candidate is projected only when its box (SegmentBox) says it may capture the node
                // (phase 1) or veto the capture found (phase 2, with that penetration).
                const auto& skipped = P.skipped;
                P.skipped.clear();
                int kept = -1;
                if (hist.segment >= 0 && std::find(candidates.begin(), candidates.end(), hist.segment) != candidates.end()) {
                    kept = hist.segment;
                    consider(kept, true);
                }
                for (int s : candidates) {
                    if (s == kept) continue;
                    if (best < 0 || best != kept) {  // no capture kept: may s capture?
                        if (P.may_matter(s, xm, xs, node_offset, -1.0)) {
                            consider(s, true);
                            continue;
                        }
                    }
                    P.skipped.push_back(s);
                }
                if (best >= 0)
                    for (int s : skipped)
                        if (P.may_matter(s, xm, xs, node_offset, -bp.gap)) consider(s, false);
            }
            if (best >= 0 && (nearest_front < -bp.gap ||
                              (bp.tangential_offset > 1e-9 * P.size[best] && nearest_front_beside < -bp.gap)))
                best = -1;
            if (approach) {
                if (best >= 0 || front_on_face) *approach = 1;  // in contact, or in front of a face it projects onto
                else if (behind_on_face) {
                    if (*approach == 0) *approach = -1;  // first seen behind a face, not captured: came from behind
                } else if (std::isfinite(nearest_distance)) {
                    *approach = nearest_gap >= 0.0 ? 1 : -1;  // beside every face: the nearest face's plane decides
                }
            }
            if (best < 0) {
                hist = {};  // separated: the friction spring relaxes
                continue;
            }
            const auto& seg = segs[best];
            const double k = opt_.penalty_scale * std::min(P.slave->node_stiffness[i], seg.stiffness);
            const double fn = -k * bp.gap;  // Eq 2-30
            Vec3 F = fn * bp.normal;        // on the slave node
            ContactPoint cp{node, best, static_cast<int>(p), xs, bp.point, bp.normal, bp.gap, fn, Vec3::Zero(), false};
            stored_ += 0.5 * k * bp.gap * bp.gap;
            max_penetration_ = std::max(max_penetration_, -bp.gap);
            max_penetration_fraction_ = std::max(max_penetration_fraction_, -bp.gap / P.slave->node_size[i]);
            // Velocity of the master point under the node (shape-function interpolation).
            Vec3 vmp = Vec3::Zero();
            for (int a = 0; a < seg.count; ++a) vmp += bp.shape[a] * vm[seg.n[a]];
            if (opt_.friction.active()) {
                const Vec3 vr = vs[node] - vmp;
                const Vec3 vt = vr - vr.dot(bp.normal) * bp.normal;
                // A pair that changed segment keeps its spring force (transported onto the new
                // tangent plane by the return map); a new contact starts unstretched.
                const FrictionUpdate fr = coulomb_return_map(hist.force, bp.normal, vr * dt, vt.norm(), k, fn, opt_.friction);
                hist.force = fr.force;
                dissipated_ += fr.dissipation;
                stored_ += fr.force.squaredNorm() / (2.0 * k);
                F += fr.force;
                cp.tangential_force = fr.force;
                cp.slipping = fr.slipping;
            }
            hist.segment = best;
            hist.side = best_side;
            hist.normal = bp.normal;
            force[node] += F;
            if (P.rigid) {
                rigid_power += F.dot(vmp);
            } else {
                for (int a = 0; a < seg.count; ++a) force[seg.n[a]] -= bp.shape[a] * F;
            }
            // Resultant on the master side (pass 1 has the roles swapped: its slave is our master).
            const Vec3 Fm = p == 0 ? Vec3(-F) : F;
            const Vec3 at = p == 0 ? bp.point : xs;
            f_master_ += Fm;
            m_master_ += at.cross(Fm);
            points_.push_back(cp);
        }
    }
    if (master_->rigid) {
        rigid_work_ += 0.5 * (rigid_power_ + rigid_power) * dt;  // trapezoidal rule
        rigid_power_ = rigid_power;
    }
}

void ContactInterface::save_state(io::H5Writer& w, const std::string& prefix) const {
    w.write(prefix + "scalars", std::vector<double>{stored_, dissipated_, rigid_work_, rigid_power_, max_penetration_,
                                                    max_penetration_fraction_});
    Eigen::MatrixXd fm(2, 3);
    fm.row(0) = f_master_.transpose();
    fm.row(1) = m_master_.transpose();
    w.write(prefix + "master_resultant", fm);
    for (std::size_t p = 0; p < passes_.size(); ++p) {
        const Pass& P = *passes_[p];
        const std::string pp = prefix + "pass" + std::to_string(p) + "/";
        P.list.save_state(w, pp + "search/");
        Eigen::MatrixXd force(P.history.size(), 3), normal(P.history.size(), 3);
        std::vector<long long> segment(P.history.size()), side(P.history.size());
        for (std::size_t i = 0; i < P.history.size(); ++i) {
            force.row(i) = P.history[i].force.transpose();
            segment[i] = P.history[i].segment;
            side[i] = P.history[i].side;
            normal.row(i) = P.history[i].normal.transpose();
        }
        w.write(pp + "friction_force", force);
        w.write_ints(pp + "segment", segment);
        // A two-sided (shell) contact keeps the side it started on while it lasts (evaluate).
        w.write_ints(pp + "side", side);
        w.write(pp + "contact_normal", normal);
        if (!P.approach.empty()) w.write_ints(pp + "approach", std::vector<long long>(P.approach.begin(), P.approach.end()));
    }
    // The last evaluation's contact points (outputs: an observer reads them before the next cycle).
    Eigen::MatrixXd pts(points_.size(), 17);
    for (std::size_t i = 0; i < points_.size(); ++i) {
        const ContactPoint& c = points_[i];
        pts.row(i) << c.node, c.segment, c.pass, c.position.transpose(), c.point.transpose(), c.normal.transpose(), c.gap,
            c.normal_force, c.tangential_force.transpose(), c.slipping ? 1.0 : 0.0;
    }
    w.write(prefix + "points", pts);
}

void ContactInterface::restore_state(const io::H5Reader& r, const std::string& prefix) {
    const auto bad = [&](const std::string& what) {
        return InputError(fmt::format("restart file '{}': contact '{}': {}", r.path().string(), name_, what));
    };
    const auto sc = r.read(prefix + "scalars");
    if (sc.size() != 6) throw bad("bad " + prefix + "scalars");
    stored_ = sc[0], dissipated_ = sc[1], rigid_work_ = sc[2], rigid_power_ = sc[3];
    max_penetration_ = sc[4], max_penetration_fraction_ = sc[5];
    const Eigen::MatrixXd fm = r.read_matrix(prefix + "master_resultant");
    f_master_ = fm.row(0).transpose();
    m_master_ = fm.row(1).transpose();
    for (std::size_t p = 0; p < passes_.size(); ++p) {
        Pass& P = *passes_[p];
        const std::string pp = prefix + "pass" + std::to_string(p) + "/";
        if (!r.has(pp + "segment")) throw bad(fmt::format("the file has no contact pass {} (one-way vs two-way?)", p));
        const Eigen::MatrixXd force = r.read_matrix(pp + "friction_force");
        const auto segment = r.read_ints(pp + "segment");
        if (segment.size() != P.history.size())
            throw bad(fmt::format("pass {} has {} slave nodes in the file, {} here", p, segment.size(), P.history.size()));
        for (std::size_t i = 0; i < P.history.size(); ++i) {
            P.history[i].force = force.row(i).transpose();
            P.history[i].segment = static_cast<int>(segment[i]);
            if (P.history[i].segment >= static_cast<int>(P.master->segments.size()))
                throw bad(fmt::format("pass {}: segment {} of the file is not a master segment here", p, segment[i]));
        }
        if (r.has(pp + "side")) {
            const auto side = r.read_ints(pp + "side");
            const Eigen::MatrixXd normal = r.read_matrix(pp + "contact_normal");
            if (side.size() != P.history.size() || normal.rows() != static_cast<Eigen::Index>(P.history.size()))
                throw bad(fmt::format("pass {} has {} contact sides in the file, {} slave nodes here", p, side.size(), P.history.size()));
            for (std::size_t i = 0; i < P.history.size(); ++i) {
                P.history[i].side = static_cast<int>(side[i]);
                P.history[i].normal = normal.row(i).transpose();
            }
        } else {
            // Written before the sides were saved: fine unless a node is in contact with a two-sided face.
            for (const auto& h : P.history)
                if (h.segment >= 0 && P.master->segments[h.segment].two_sided)
                    throw bad(fmt::format("pass {}: a node is in contact with a two-sided (shell) face, and the file does not "
                                          "say on which side (written before contact sides were saved)", p));
        }
        if (!P.approach.empty()) {
            if (!r.has(pp + "approach"))
                throw bad(fmt::format("pass {} has no approach sides in the file (written without track_approach_side)", p));
            const auto approach = r.read_ints(pp + "approach");
            if (approach.size() != P.approach.size())
                throw bad(fmt::format("pass {} has {} approach sides in the file, {} here", p, approach.size(), P.approach.size()));
            for (std::size_t i = 0; i < approach.size(); ++i) P.approach[i] = static_cast<signed char>(approach[i]);
        }
        P.list.restore_state(r, pp + "search/");
    }
    if (r.has(prefix + "pass" + std::to_string(passes_.size()) + "/segment"))
        throw bad("the file has more contact passes than this interface (two-way vs one-way?)");
    const Eigen::MatrixXd pts = r.read_matrix(prefix + "points");
    points_.clear();
    for (Eigen::Index i = 0; i < pts.rows(); ++i) {
        const auto row = pts.row(i);
        ContactPoint c;
        c.node = static_cast<int>(row(0)), c.segment = static_cast<int>(row(1)), c.pass = static_cast<int>(row(2));
        c.position = row.segment<3>(3).transpose(), c.point = row.segment<3>(6).transpose();
        c.normal = row.segment<3>(9).transpose(), c.gap = row(12), c.normal_force = row(13);
        c.tangential_force = row.segment<3>(14).transpose();
        c.slipping = row(16) != 0.0;
        points_.push_back(c);
    }
}

double ContactInterface::stability_frequency_squared(std::span<const double> mass) const {
    double w2 = 0.0;
    for (const auto& P : passes_) {
        double inv_master = 0.0;  // 1 / lightest master node (rigid: infinite mass)
        // The pair's spring is min(k slave node, k master segment): never stiffer than the stiffest
        // master segment (rigid: infinite).
        double k_master = std::numeric_limits<double>::infinity();
        if (!P->rigid) {
            for (int n : P->master_nodes)
                if (n < static_cast<int>(mass.size()) && mass[n] > 0.0) inv_master = std::max(inv_master, 1.0 / mass[n]);
            k_master = 0.0;
            for (const auto& seg : P->master->segments) k_master = std::max(k_master, seg.stiffness);
        }
        for (std::size_t i = 0; i < P->slave->nodes.size(); ++i) {
            const int n = P->slave->nodes[i];
            if (n >= static_cast<int>(mass.size()) || !(mass[n] > 0.0)) continue;
            const double k = opt_.penalty_scale * std::min(P->slave->node_stiffness[i], k_master);
            w2 = std::max(w2, k * (1.0 / mass[n] + inv_master));
        }
    }
    return w2 * static_cast<double>(passes_.size());
}

Resultant resultant(std::span<const int> nodes, std::span<const Vec3> f, std::span<const Vec3> x, const Vec3& about) {
    Resultant r;
    for (int n : nodes) {
        if (n < 0 || n >= static_cast<int>(f.size()) || n >= static_cast<int>(x.size()))
            throw InputError(fmt::format("resultant: node {} out of range ({} nodes)", n, f.size()));
        r.force += f[n];
        r.moment += (x[n] - about).cross(f[n]);
    }
    return r;
}

std::vector<double> ContactInterface::nodal_pressure(std::span<const Vec3> x) const {
    const int node_count = static_cast<int>(x.size());
    // Area vector of a face (quadrilateral: half the cross product of its diagonals).
    auto area_vector = [&](const Segment& seg) -> Vec3 {
        if (seg.count == 4) return 0.5 * (x[seg.n[2]] - x[seg.n[0]]).cross(x[seg.n[3]] - x[seg.n[1]]);
        return 0.5 * (x[seg.n[1]] - x[seg.n[0]]).cross(x[seg.n[2]] - x[seg.n[0]]);
    };
    // Faces around each node of the slave surface (pass 0) and of the master surface (pass 1).
    auto faces_of = [&](const ContactSurface& surface) {
        std::vector<std::vector<int>> faces(node_count);
        for (std::size_t f = 0; f < surface.segments.size(); ++f)
            for (int k = 0; k < surface.segments[f].count; ++k)
                if (surface.segments[f].n[k] >= 0 && surface.segments[f].n[k] < node_count)
                    faces[surface.segments[f].n[k]].push_back(static_cast<int>(f));
        return faces;
    };
    const auto slave_faces = faces_of(*slave_);
    const auto master_faces = passes_.size() > 1 ? faces_of(*master_) : std::vector<std::vector<int>>(node_count);
    std::vector<double> p(node_count, 0.0);
    for (const ContactPoint& c : points_) {
        if (c.node < 0 || c.node >= node_count) continue;
        const ContactSurface& surface = c.pass == 0 ? *slave_ : *master_;
        double area = 0.0;
        for (int f : (c.pass == 0 ? slave_faces : master_faces)[c.node]) {
            const Segment& seg = surface.segments[f];
            area += std::abs(area_vector(seg).dot(c.normal)) / seg.count;
        }
        if (area > 0) p[c.node] += c.normal_force / area;
    }
    return p;
}

}  // namespace fem::contact
