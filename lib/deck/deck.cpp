#include "deck/deck.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"
#include "input/numbers.hpp"
#include "io/atomic_file.hpp"

namespace fem::deck {
namespace {

namespace fs = std::filesystem;

// ---- lines ------------------------------------------------------------------------------------

struct Line {
    std::string text;
    input::Where where;  // file and line; key filled per field
};

std::string trim(std::string_view s) {
    std::size_t a = 0, b = s.size();
    while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
    return std::string(s.substr(a, b - a));
}

std::string upper(std::string_view s) {
    std::string u(s);
    for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return u;
}

// Comma-separated fields, blanks trimmed; a trailing empty field (a line ending in a comma) dropped.
std::vector<std::string> split(std::string_view s) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = s.find(',', start);
        out.push_back(trim(s.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    if (!out.empty() && out.back().empty()) out.pop_back();
    return out;
}

bool is_keyword(const std::string& t) { return t.size() >= 1 && t[0] == '*' && (t.size() < 2 || t[1] != '*'); }
bool is_comment(const std::string& t) { return t.rfind("**", 0) == 0; }

// ---- keyword lines ----------------------------------------------------------------------------

struct Keyword {
    std::string name;                                 // "*SOLID SECTION" (upper case, single blanks)
    std::vector<std::pair<std::string, std::string>> params;  // KEY (upper) -> value as written ("" for a flag)
    input::Where where;

    // Refuses parameters outside `known` (with "did you mean").
    void allow(std::initializer_list<const char*> known) const {
        std::vector<std::string> names(known.begin(), known.end());
        for (const auto& [k, v] : params)
            if (std::find(names.begin(), names.end(), k) == names.end())
                input::fail(where, fmt::format("{}: unknown parameter '{}'{} (known: {})", name, k, input::did_you_mean(k, names),
                                               names.empty() ? std::string("none") : input::one_of(names)));
    }
    std::optional<std::string> get(const std::string& key) const {
        for (const auto& [k, v] : params)
            if (k == key) return v;
        return std::nullopt;
    }
    bool flag(const std::string& key) const { return get(key).has_value(); }
    std::string require(const std::string& key) const {
        auto v = get(key);
        if (!v || v->empty()) input::fail(where, fmt::format("{}: parameter {}= is missing", name, key));
        return *v;
    }
};

Keyword parse_keyword(const std::string& text, const input::Where& where) {
    Keyword kw;
    kw.where = where;
    auto fields = split(text);
    std::string name;
    for (char c : fields.at(0)) {  // collapse blanks: "*SOLID   SECTION" -> "*SOLID SECTION"
        if (std::isspace(static_cast<unsigned char>(c))) {
            if (!name.empty() && name.back() != ' ') name += ' ';
        } else {
            name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        }
    }
    kw.name = trim(name);
    for (std::size_t i = 1; i < fields.size(); ++i) {
        if (fields[i].empty()) continue;
        const auto eq = fields[i].find('=');
        if (eq == std::string::npos) kw.params.emplace_back(upper(fields[i]), "");
        else kw.params.emplace_back(upper(trim(fields[i].substr(0, eq))), trim(fields[i].substr(eq + 1)));
    }
    return kw;
}

// ---- the reader ---------------------------------------------------------------------------------

struct ElementRecord {
    std::string type;
    int id = 0;
    std::vector<int> nodes;  // mesh node indices, library order
    input::Where where;
};

class Reader {
public:
    explicit Reader(Deck& deck) : d_(deck) {}

    void load(std::string_view text, const std::string& source, const fs::path& base, int depth) {
        if (depth > 20) throw InputError(source + ": *INCLUDE nested more than 20 deep (does a file include itself?)");
        std::istringstream in{std::string(text)};
        std::string raw;
        int number = 0;
        while (std::getline(in, raw)) {
            ++number;
            if (!raw.empty() && raw.back() == '\r') raw.pop_back();
            const std::string t = trim(raw);
            if (t.empty() || is_comment(t)) continue;
            const input::Where where{source, number, ""};
            // A keyword line that ends in a comma continues on the next non-comment line.
            if (is_keyword(t)) {
                std::string full = t;
                while (!full.empty() && full.back() == ',') {
                    std::string next;
                    do {
                        if (!std::getline(in, next)) input::fail(where, "keyword line ends in a comma but the file ends");
                        ++number;
                        if (!next.empty() && next.back() == '\r') next.pop_back();
                        next = trim(next);
                    } while (next.empty() || is_comment(next));
                    full += next;
                }
                const Keyword kw = parse_keyword(full, where);
                if (kw.name == "*INCLUDE") {
                    kw.allow({"INPUT"});
                    const fs::path file = base / kw.require("INPUT");
                    std::ifstream f(file);
                    if (!f) input::fail(where, "*INCLUDE: cannot open '" + file.string() + "'");
                    std::stringstream ss;
                    ss << f.rdbuf();
                    load(ss.str(), file.string(), file.parent_path(), depth + 1);
                    continue;
                }
                lines_.push_back({full, where});
                continue;
            }
            lines_.push_back({t, where});
        }
    }

    void run() {
        std::size_t i = 0;
        while (i < lines_.size()) {
            const Line& head = lines_[i];
            if (!is_keyword(head.text))
                input::fail(head.where, "data line before any keyword: '" + head.text.substr(0, 40) + "'");
            const Keyword kw = parse_keyword(head.text, head.where);
            std::size_t j = i + 1;
            while (j < lines_.size() && !is_keyword(lines_[j].text)) ++j;
            const std::span<const Line> data(lines_.data() + i + 1, j - i - 1);
            dispatch(kw, data);
            i = j;
        }
        finish();
    }

private:
    Deck& d_;
    std::vector<Line> lines_;
    std::map<int, int> node_index_;  // deck id -> mesh index
    std::map<int, std::size_t> element_index_;  // deck id -> elements_ index
    std::vector<ElementRecord> elements_;
    std::map<std::string, std::vector<int>> elsets_;  // name -> deck element ids
    std::string material_;  // the *MATERIAL being defined
    std::map<std::string, input::Where> material_where_;
    std::vector<input::Where> section_where_;
    int steps_ = 0;
    bool in_step_ = false;

    static std::vector<std::string> known_keywords() {
        return {"*NODE", "*ELEMENT", "*NSET", "*ELSET", "*INCLUDE", "*MATERIAL", "*ELASTIC", "*DENSITY", "*SOLID SECTION",
                "*SHELL SECTION", "*BOUNDARY", "*EQUATION", "*STEP", "*FREQUENCY", "*END STEP", "*HEADING",
                "*NODE FILE", "*EL FILE", "*NODE PRINT", "*EL PRINT", "*NODE OUTPUT", "*ELEMENT OUTPUT", "*OUTPUT"};
    }

    void dispatch(const Keyword& kw, std::span<const Line> data) {
        const std::string& k = kw.name;
        if (k == "*NODE") return nodes(kw, data);
        if (k == "*ELEMENT") return elements(kw, data);
        if (k == "*NSET") return node_set(kw, data);
        if (k == "*ELSET") return element_set(kw, data);
        if (k == "*MATERIAL") {
            kw.allow({"NAME"});
            material_ = upper(kw.require("NAME"));
            if (d_.materials.count(material_) || material_where_.count(material_))
                input::fail(kw.where, "*MATERIAL: material '" + material_ + "' is defined twice");
            material_where_[material_] = kw.where;
            no_data(kw, data);
            return;
        }
        if (k == "*ELASTIC") return elastic(kw, data);
        if (k == "*DENSITY") return density(kw, data);
        if (k == "*SOLID SECTION" || k == "*SHELL SECTION") return section(kw, data);
        if (k == "*BOUNDARY") return boundary(kw, data);
        if (k == "*EQUATION") return equation(kw, data);
        if (k == "*STEP") {
            kw.allow({"PERTURBATION", "NLGEOM", "INC"});
            if (auto nl = kw.get("NLGEOM"); nl && upper(*nl) != "NO")
                input::fail(kw.where, "*STEP: NLGEOM is not supported (a frequency step about the undeformed state only)");
            if (in_step_) input::fail(kw.where, "*STEP inside a step (missing *END STEP)");
            if (++steps_ > 1) input::fail(kw.where, "*STEP: only one step (a *FREQUENCY step) is supported");
            in_step_ = true;
            no_data(kw, data);
            return;
        }
        if (k == "*END STEP") {
            kw.allow({});
            if (!in_step_) input::fail(kw.where, "*END STEP without *STEP");
            in_step_ = false;
            no_data(kw, data);
            return;
        }
        if (k == "*FREQUENCY") return frequency(kw, data);
        if (k == "*HEADING") {
            kw.allow({});
            return;
        }
        if (k == "*NODE FILE" || k == "*EL FILE" || k == "*NODE PRINT" || k == "*EL PRINT" || k == "*NODE OUTPUT" ||
            k == "*ELEMENT OUTPUT" || k == "*OUTPUT") {
            d_.notes.push_back(kw.where.str() + ": " + k +
                               " (an output request: not acted upon; fem-modal writes frequencies.csv, modes.h5 and "
                               "VTU shapes instead)");
            return;
        }
        const auto known = known_keywords();
        input::fail(kw.where, "unsupported keyword '" + k + "'" + input::did_you_mean(k, known) +
                                  " (this reader takes " + input::one_of(known) + ")");
    }

    static void no_data(const Keyword& kw, std::span<const Line> data) {
        if (!data.empty()) input::fail(data.front().where, kw.name + " takes no data lines, got '" + data.front().text + "'");
    }

    static input::Where field(const Line& line, const std::string& keyword, std::size_t index, std::string_view what) {
        input::Where w = line.where;
        w.key = fmt::format("{}, field {} ({})", keyword, index + 1, what);
        return w;
    }

    int node_of(const std::string& text, const input::Where& where) const {
        const int id = input::parse_integer<int>(text, where, {.min = 1});
        auto it = node_index_.find(id);
        if (it == node_index_.end()) input::fail(where, fmt::format("node {} is not defined (by a *NODE before this line)", id));
        return it->second;
    }

    void nodes(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"NSET"});
        const std::string nset = kw.get("NSET") ? upper(kw.require("NSET")) : "";
        for (const Line& l : data) {
            const auto f = split(l.text);
            if (f.size() < 2 || f.size() > 4)
                input::fail(l.where, fmt::format("*NODE: a node line is 'id, x[, y[, z]]', got {} fields", f.size()));
            const int id = input::parse_integer<int>(f[0], field(l, "*NODE", 0, "node number"), {.min = 1});
            Vec3 x = Vec3::Zero();
            for (std::size_t c = 1; c < f.size(); ++c)
                x[static_cast<int>(c - 1)] = input::parse_real(f[c], field(l, "*NODE", c, std::string(1, "xyz"[c - 1])));
            if (node_index_.count(id)) input::fail(l.where, fmt::format("*NODE: node {} is defined twice", id));
            node_index_[id] = d_.mesh.add_node(x);
            d_.node_ids.push_back(id);
            if (!nset.empty()) d_.mesh.node_sets[nset].push_back(node_index_[id]);
        }
    }

    void elements(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"TYPE", "ELSET"});
        const std::string type = upper(kw.require("TYPE"));
        const auto& types = supported_element_types();
        if (std::find(types.begin(), types.end(), type) == types.end()) {
            input::fail(kw.where, "*ELEMENT: unknown element type '" + type + "'" + input::did_you_mean(type, types) +
                                      "; supported: " + input::one_of(types));
        }
        const ElementShape shape = shape_of_type(type);
        const int n = node_count(shape);
        const std::string elset = kw.get("ELSET") ? upper(kw.require("ELSET")) : "";
        // An element's line continues on the next ones until it has its nodes (C3D10 often spans two).
        std::size_t i = 0;
        while (i < data.size()) {
            const Line& first = data[i];
            std::vector<std::string> f = split(first.text);
            std::vector<input::Where> at(f.size(), first.where);
            while (static_cast<int>(f.size()) < n + 1 && i + 1 < data.size()) {
                ++i;
                const auto more = split(data[i].text);
                f.insert(f.end(), more.begin(), more.end());
                at.insert(at.end(), more.size(), data[i].where);
            }
            ++i;
            if (static_cast<int>(f.size()) != n + 1)
                input::fail(first.where, fmt::format("*ELEMENT, TYPE={}: an element needs its number and {} nodes, got {} "
                                                     "fields",
                                                     type, n, f.size()));
            ElementRecord e;
            e.type = type;
            e.where = first.where;
            e.id = input::parse_integer<int>(f[0], field(first, "*ELEMENT", 0, "element number"), {.min = 1});
            std::vector<int> deck_order(n);
            for (int k = 0; k < n; ++k) {
                input::Where w = at[k + 1];
                w.key = fmt::format("*ELEMENT {}, node {}", e.id, k + 1);
                deck_order[k] = node_of(f[k + 1], w);
            }
            // CalculiX/Abaqus C3D10 numbers the mid-edge nodes 01 12 20 03 13 23, the library (Gmsh)
            // 01 12 20 03 23 13; the other types share the library's order.
            e.nodes = deck_order;
            if (shape == ElementShape::Tet10) std::swap(e.nodes[8], e.nodes[9]);
            if (element_index_.count(e.id)) input::fail(first.where, fmt::format("*ELEMENT: element {} is defined twice", e.id));
            element_index_[e.id] = elements_.size();
            elements_.push_back(std::move(e));
            if (!elset.empty()) elsets_[elset].push_back(elements_.back().id);
        }
    }

    // Members of a *NSET / *ELSET: numbers, or names of sets defined before; GENERATE: first, last, step.
    template <class Resolve, class Named>
    void set_members(const Keyword& kw, std::span<const Line> data, Resolve resolve, Named named) {
        for (const Line& l : data) {
            const auto f = split(l.text);
            if (kw.flag("GENERATE")) {
                if (f.size() < 2 || f.size() > 3)
                    input::fail(l.where, kw.name + ", GENERATE: a line is 'first, last[, step]'");
                const int a = input::parse_integer<int>(f[0], field(l, kw.name, 0, "first"), {.min = 1});
                const int b = input::parse_integer<int>(f[1], field(l, kw.name, 1, "last"), {.min = a});
                const int s = f.size() == 3 ? input::parse_integer<int>(f[2], field(l, kw.name, 2, "step"), {.min = 1}) : 1;
                for (long long id = a; id <= b; id += s) resolve(std::to_string(id), field(l, kw.name, 0, "generated member"));
                continue;
            }
            for (std::size_t c = 0; c < f.size(); ++c) {
                if (f[c].empty()) continue;
                const bool number = std::isdigit(static_cast<unsigned char>(f[c][0])) || f[c][0] == '-' || f[c][0] == '+';
                if (number) resolve(f[c], field(l, kw.name, c, "member"));
                else named(upper(f[c]), field(l, kw.name, c, "set name"));
            }
        }
    }

    void node_set(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"NSET", "GENERATE"});
        const std::string name = upper(kw.require("NSET"));
        std::vector<int> members;
        set_members(
            kw, data, [&](const std::string& t, const input::Where& w) { members.push_back(node_of(t, w)); },
            [&](const std::string& set, const input::Where& w) {
                auto it = d_.mesh.node_sets.find(set);
                if (it == d_.mesh.node_sets.end()) input::fail(w, "node set '" + set + "' is not defined before this line");
                members.insert(members.end(), it->second.begin(), it->second.end());
            });
        auto& s = d_.mesh.node_sets[name];
        s.insert(s.end(), members.begin(), members.end());
    }

    void element_set(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"ELSET", "GENERATE"});
        const std::string name = upper(kw.require("ELSET"));
        std::vector<int> members;
        set_members(
            kw, data,
            [&](const std::string& t, const input::Where& w) {
                const int id = input::parse_integer<int>(t, w, {.min = 1});
                if (!element_index_.count(id)) input::fail(w, fmt::format("element {} is not defined before this line", id));
                members.push_back(id);
            },
            [&](const std::string& set, const input::Where& w) {
                auto it = elsets_.find(set);
                if (it == elsets_.end()) input::fail(w, "element set '" + set + "' is not defined before this line");
                members.insert(members.end(), it->second.begin(), it->second.end());
            });
        auto& s = elsets_[name];
        s.insert(s.end(), members.begin(), members.end());
    }

    const std::string& current_material(const Keyword& kw) const {
        if (material_.empty()) input::fail(kw.where, kw.name + " outside a *MATERIAL");
        return material_;
    }

    // The single data line of *ELASTIC / *DENSITY (temperature-dependent tables are refused).
    static std::vector<std::string> one_line(const Keyword& kw, std::span<const Line> data, std::size_t fields) {
        if (data.size() != 1)
            input::fail(kw.where, fmt::format("{}: expects one data line, got {} (temperature-dependent properties are not "
                                              "supported)",
                                              kw.name, data.size()));
        auto f = split(data[0].text);
        if (f.size() != fields)
            input::fail(data[0].where, fmt::format("{}: expects {} value{}, got {} (temperature-dependent properties are "
                                                   "not supported)",
                                                   kw.name, fields, fields > 1 ? "s" : "", f.size()));
        return f;
    }

    std::map<std::string, std::pair<double, double>> elastic_;  // E, nu per material
    std::map<std::string, double> density_;

    void elastic(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"TYPE"});
        if (auto t = kw.get("TYPE"); t && upper(*t) != "ISO" && upper(*t) != "ISOTROPIC")
            input::fail(kw.where, "*ELASTIC: TYPE=" + *t + " is not supported (isotropic only)");
        const std::string& m = current_material(kw);
        if (elastic_.count(m)) input::fail(kw.where, "*ELASTIC given twice for material '" + m + "'");
        const auto f = one_line(kw, data, 2);
        const double E = input::parse_real(f[0], field(data[0], "*ELASTIC", 0, "E"), input::Range::positive());
        const double nu = input::parse_real(f[1], field(data[0], "*ELASTIC", 1, "nu"), input::Range::open(-1.0, 0.5));
        elastic_[m] = {E, nu};
    }

    void density(const Keyword& kw, std::span<const Line> data) {
        kw.allow({});
        const std::string& m = current_material(kw);
        if (density_.count(m)) input::fail(kw.where, "*DENSITY given twice for material '" + m + "'");
        const auto f = one_line(kw, data, 1);
        density_[m] = input::parse_real(f[0], field(data[0], "*DENSITY", 0, "rho"), input::Range::positive());
    }

    void section(const Keyword& kw, std::span<const Line> data) {
        Section s;
        s.kind = kw.name == "*SHELL SECTION" ? Section::Shell : Section::Solid;
        if (s.kind == Section::Shell) kw.allow({"ELSET", "MATERIAL", "OFFSET"});
        else kw.allow({"ELSET", "MATERIAL"});
        s.elset = upper(kw.require("ELSET"));
        s.material = upper(kw.require("MATERIAL"));
        if (auto off = kw.get("OFFSET")) {
            const double o = input::parse_real(*off, {kw.where.file, kw.where.line, kw.name + ", OFFSET"});
            if (o != 0.0) input::fail(kw.where, kw.name + ": OFFSET other than 0 is not supported (midsurface shells only)");
        }
        if (!elsets_.count(s.elset)) {
            std::vector<std::string> known;
            for (const auto& [name, ids] : elsets_) known.push_back(name);
            input::fail(kw.where, kw.name + ": element set '" + s.elset + "' is not defined" + input::did_you_mean(s.elset, known));
        }
        if (s.kind == Section::Shell) {
            if (data.size() != 1) input::fail(kw.where, "*SHELL SECTION: expects one data line (the thickness)");
            const auto f = split(data[0].text);
            if (f.size() != 1) input::fail(data[0].where, "*SHELL SECTION: expects the thickness only (one value)");
            s.thickness = input::parse_real(f[0], field(data[0], "*SHELL SECTION", 0, "thickness"), input::Range::positive());
        } else if (!data.empty()) {
            // A solid section's data line (plane thickness) means nothing for 3D solids: it must be empty.
            for (const Line& l : data)
                if (!split(l.text).empty()) input::fail(l.where, "*SOLID SECTION: a data line has no meaning for 3D solids");
        }
        d_.sections.push_back(s);
        section_where_.push_back(kw.where);
    }

    // A node number or a node set name -> mesh indices.
    std::vector<int> nodes_named(const std::string& text, const input::Where& where) const {
        if (!text.empty() && (std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-' || text[0] == '+'))
            return {node_of(text, where)};
        auto it = d_.mesh.node_sets.find(upper(text));
        if (it == d_.mesh.node_sets.end()) {
            std::vector<std::string> known;
            for (const auto& [name, ids] : d_.mesh.node_sets) known.push_back(name);
            input::fail(where, "node set '" + upper(text) + "' is not defined" + input::did_you_mean(upper(text), known));
        }
        return it->second;
    }

    void boundary(const Keyword& kw, std::span<const Line> data) {
        kw.allow({});
        if (in_step_) input::fail(kw.where, "*BOUNDARY inside the frequency step: give supports in the model part, before *STEP");
        for (const Line& l : data) {
            const auto f = split(l.text);
            if (f.size() < 2 || f.size() > 4)
                input::fail(l.where, "*BOUNDARY: a line is 'node or set, first DOF[, last DOF[, value]]'");
            const int first = input::parse_integer<int>(f[1], field(l, "*BOUNDARY", 1, "first DOF"), {.min = 1, .max = 6});
            const int last =
                f.size() >= 3 && !f[2].empty() ? input::parse_integer<int>(f[2], field(l, "*BOUNDARY", 2, "last DOF"), {.min = first, .max = 6})
                                               : first;
            if (f.size() == 4) {
                const double v = input::parse_real(f[3], field(l, "*BOUNDARY", 3, "value"));
                if (v != 0.0) input::fail(field(l, "*BOUNDARY", 3, "value"), fmt::format("a prescribed displacement ({:g}) has no meaning in a frequency analysis; only 0 is supported", v));
            }
            for (int node : nodes_named(f[0], field(l, "*BOUNDARY", 0, "node or node set")))
                d_.boundaries.push_back({node, first, last});
        }
    }

    void equation(const Keyword& kw, std::span<const Line> data) {
        kw.allow({});
        std::size_t i = 0;
        while (i < data.size()) {
            const Line& head = data[i++];
            const auto h = split(head.text);
            if (h.size() != 1) input::fail(head.where, "*EQUATION: the first line of an equation is its number of terms");
            const int terms = input::parse_integer<int>(h[0], field(head, "*EQUATION", 0, "number of terms"), {.min = 2});
            if (terms != 2)
                input::fail(head.where, fmt::format("*EQUATION with {} terms: only two-term equations u_a - u_b = 0 (coupled "
                                                    "DOFs) are supported",
                                                    terms));
            std::vector<std::string> f;
            std::vector<input::Where> at;
            while (static_cast<int>(f.size()) < 3 * terms && i < data.size()) {
                const auto more = split(data[i].text);
                f.insert(f.end(), more.begin(), more.end());
                at.insert(at.end(), more.size(), data[i].where);
                ++i;
            }
            if (static_cast<int>(f.size()) != 3 * terms)
                input::fail(head.where, "*EQUATION: expects node, DOF, coefficient for each of the 2 terms");
            auto w = [&](int k, const char* what) {
                input::Where x = at[k];
                x.key = fmt::format("*EQUATION, term {} {}", k / 3 + 1, what);
                return x;
            };
            Equation e;
            e.node_a = node_of(f[0], w(0, "node"));
            e.node_b = node_of(f[3], w(3, "node"));
            e.dof = input::parse_integer<int>(f[1], w(1, "DOF"), {.min = 1, .max = 6});
            const int dof_b = input::parse_integer<int>(f[4], w(4, "DOF"), {.min = 1, .max = 6});
            const double ca = input::parse_real(f[2], w(2, "coefficient"));
            const double cb = input::parse_real(f[5], w(5, "coefficient"));
            if (dof_b != e.dof || ca == 0.0 || cb != -ca)
                input::fail(head.where, fmt::format("*EQUATION {:g} u{}({}) + {:g} u{}({}) = 0: only equal DOFs with opposite "
                                                    "coefficients (u_a = u_b, coupled DOFs) are supported",
                                                    ca, d_.node_ids[e.node_a], e.dof, cb, d_.node_ids[e.node_b], dof_b));
            if (e.node_a == e.node_b) input::fail(head.where, "*EQUATION couples a node with itself");
            d_.equations.push_back(e);
        }
    }

    void frequency(const Keyword& kw, std::span<const Line> data) {
        kw.allow({"STORAGE", "SOLVER", "MATRIXSTORAGE"});
        if (auto s = kw.get("SOLVER")) d_.notes.push_back(kw.where.str() + ": *FREQUENCY, SOLVER=" + *s +
                                                          " (not acted upon: fem-modal uses shift-and-invert Lanczos)");
        if (kw.get("STORAGE") || kw.get("MATRIXSTORAGE"))
            d_.notes.push_back(kw.where.str() + ": *FREQUENCY STORAGE/MATRIXSTORAGE (not acted upon: no .eig/.mtx file)");
        if (!in_step_) input::fail(kw.where, "*FREQUENCY outside a *STEP");
        if (d_.frequency) input::fail(kw.where, "*FREQUENCY given twice");
        if (data.size() != 1) input::fail(kw.where, "*FREQUENCY: expects one data line (the number of modes)");
        const auto f = split(data[0].text);
        if (f.empty()) input::fail(data[0].where, "*FREQUENCY: the number of modes is missing");
        Frequency fr;
        fr.modes = input::parse_integer<int>(f[0], field(data[0], "*FREQUENCY", 0, "number of modes"), {.min = 1});
        for (std::size_t c = 1; c < f.size(); ++c)
            if (!f[c].empty())
                input::fail(field(data[0], "*FREQUENCY", c, c == 1 ? "lower frequency" : c == 2 ? "upper frequency" : "option"),
                            "only the number of modes is supported (a frequency range or other options are not)");
        d_.frequency = fr;
    }

    void finish() {
        if (in_step_) throw InputError(d_.file.string() + ": *STEP without *END STEP");
        // Materials.
        for (const auto& [name, where] : material_where_) {
            auto e = elastic_.find(name);
            if (e == elastic_.end()) input::fail(where, "*MATERIAL '" + name + "' has no *ELASTIC");
            auto r = density_.find(name);
            if (r == density_.end()) input::fail(where, "*MATERIAL '" + name + "' has no *DENSITY (a frequency analysis needs the mass)");
            d_.materials.emplace(name, ElasticMaterial::make(name, e->second.first, e->second.second, r->second));
        }
        // Each element in exactly one section, of a kind that fits its type.
        std::vector<int> section_of(elements_.size(), -1);
        for (std::size_t s = 0; s < d_.sections.size(); ++s) {
            const Section& sec = d_.sections[s];
            if (!d_.materials.count(sec.material)) {
                std::vector<std::string> known;
                for (const auto& [name, m] : d_.materials) known.push_back(name);
                input::fail(section_where_[s], "section of element set '" + sec.elset + "': material '" + sec.material +
                                                   "' is not defined" + input::did_you_mean(sec.material, known));
            }
            for (int id : elsets_.at(sec.elset)) {
                const std::size_t e = element_index_.at(id);
                if (section_of[e] >= 0 && section_of[e] != static_cast<int>(s))
                    input::fail(section_where_[s], fmt::format("element {} is in two sections (element sets '{}' and '{}')", id,
                                                               d_.sections[section_of[e]].elset, sec.elset));
                const bool shell = shape_of_type(elements_[e].type) == ElementShape::Quad4;
                if (shell != (sec.kind == Section::Shell))
                    input::fail(section_where_[s], fmt::format("element {} ({}) needs a {} section", id, elements_[e].type,
                                                               shell ? "*SHELL SECTION" : "*SOLID SECTION"));
                section_of[e] = static_cast<int>(s);
            }
        }
        // Blocks: one per (type, section), in order of first appearance.
        std::map<std::pair<std::string, int>, int> block_of;
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            const ElementRecord& r = elements_[e];
            if (section_of[e] < 0)
                input::fail(r.where, fmt::format("element {} ({}) is in no *SOLID SECTION or *SHELL SECTION", r.id, r.type));
            const auto key = std::make_pair(r.type, section_of[e]);
            auto it = block_of.find(key);
            if (it == block_of.end()) {
                it = block_of.emplace(key, static_cast<int>(d_.mesh.blocks.size())).first;
                d_.mesh.blocks.push_back({d_.sections[section_of[e]].elset, shape_of_type(r.type), {}});
                d_.block_types.push_back(r.type);
                d_.block_section.push_back(section_of[e]);
            }
            d_.mesh.blocks[it->second].add(r.nodes);
            d_.mesh.blocks[it->second].ids.push_back(r.id);
        }
        for (auto& [name, ids] : d_.mesh.node_sets) {
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        }
        validate(d_.mesh);
    }
};

std::string number(double v) { return fmt::format("{:.17g}", v); }

}  // namespace

const std::vector<std::string>& supported_element_types() {
    static const std::vector<std::string> types = {"C3D4", "C3D10", "C3D8", "C3D8I", "C3D20", "C3D20R", "S4", "S4R"};
    return types;
}

ElementShape shape_of_type(std::string_view type) {
    if (type == "C3D4") return ElementShape::Tet4;
    if (type == "C3D10") return ElementShape::Tet10;
    if (type == "C3D8" || type == "C3D8I") return ElementShape::Hex8;
    if (type == "C3D20" || type == "C3D20R") return ElementShape::Hex20;
    if (type == "S4" || type == "S4R") return ElementShape::Quad4;
    throw InputError("deck element type '" + std::string(type) + "' is not supported; supported: " +
                     input::one_of(supported_element_types()));
}

Deck parse_deck(std::string_view text, const std::string& source, const fs::path& base) {
    Deck d;
    d.file = source;
    Reader r(d);
    r.load(text, source, base, 0);
    r.run();
    return d;
}

Deck read_deck(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError("deck '" + path.string() + "' cannot be opened (does it exist?)");
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_deck(ss.str(), path.string(), path.parent_path());
}

void write_deck(const fs::path& path, const Deck& d, std::string_view heading) {
    io::AtomicFile file(path);
    std::ostream& out = file.stream();
    const auto id_of_node = [&](int n) { return d.node_ids.empty() ? n + 1 : d.node_ids[n]; };
    out << "*HEADING\n" << heading << "\n*NODE, NSET=NALL\n";
    for (int i = 0; i < d.mesh.node_count(); ++i)
        out << fmt::format("{}, {}, {}, {}\n", id_of_node(i), number(d.mesh.nodes[i].x()),
                           number(d.mesh.nodes[i].y()), number(d.mesh.nodes[i].z()));
    long next_id = 1;
    for (const auto& blk : d.mesh.blocks)
        for (long id : blk.ids) next_id = std::max(next_id, id + 1);
    std::vector<std::string> elsets_written;
    for (std::size_t b = 0; b < d.mesh.blocks.size(); ++b) {
        const ElementBlock& blk = d.mesh.blocks[b];
        const std::string& type = d.block_types.at(b);
        const Section& sec = d.sections.at(d.block_section.at(b));
        out << fmt::format("*ELEMENT, TYPE={}, ELSET={}\n", type, sec.elset);
        for (int e = 0; e < blk.size(); ++e) {
            std::vector<int> c(blk.element(e).begin(), blk.element(e).end());
            if (blk.shape == ElementShape::Tet10) std::swap(c[8], c[9]);  // library -> C3D10 order
            const long id = blk.ids.empty() ? next_id++ : blk.id(e);
            out << id;
            for (std::size_t k = 0; k < c.size(); ++k) out << (k == 8 ? ",\n" : ", ") << id_of_node(c[k]);
            out << '\n';
        }
    }
    for (const auto& [name, m] : d.materials)
        out << fmt::format("*MATERIAL, NAME={}\n*ELASTIC\n{}, {}\n*DENSITY\n{}\n", name, number(m.youngs_modulus),
                           number(m.poissons_ratio), number(m.density));
    for (const Section& s : d.sections) {
        if (s.kind == Section::Shell)
            out << fmt::format("*SHELL SECTION, ELSET={}, MATERIAL={}\n{}\n", s.elset, s.material, number(s.thickness));
        else out << fmt::format("*SOLID SECTION, ELSET={}, MATERIAL={}\n", s.elset, s.material);
    }
    if (!d.boundaries.empty()) {
        out << "*BOUNDARY\n";
        for (const Boundary& b : d.boundaries) out << fmt::format("{}, {}, {}\n", id_of_node(b.node), b.first, b.last);
    }
    if (!d.equations.empty()) out << "*EQUATION\n";
    for (const Equation& e : d.equations)
        out << fmt::format("2\n{}, {}, 1., {}, {}, -1.\n", id_of_node(e.node_a), e.dof, id_of_node(e.node_b), e.dof);
    out << fmt::format("*STEP\n*FREQUENCY\n{}\n*END STEP\n", d.frequency ? d.frequency->modes : 10);
    file.commit();
}

}  // namespace fem::deck
