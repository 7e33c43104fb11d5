#include "mesh/gmsh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "core/error.hpp"

namespace fem {
namespace {

std::recursive_mutex& gmsh_mutex() {
    static std::recursive_mutex m;
    return m;
}
int gmsh_depth = 0;  // live GmshSession objects; guarded by gmsh_mutex()

// Gmsh element type number -> our shape (see the header for the list); nullopt when unsupported.
std::optional<ElementShape> shape_of_gmsh_type(int type) {
    switch (type) {
        case 15: return ElementShape::Point1;
        case 1: return ElementShape::Beam2;
        case 2: return ElementShape::Tri3;
        case 3: return ElementShape::Quad4;
        case 16: return ElementShape::Quad8;
        case 4: return ElementShape::Tet4;
        case 11: return ElementShape::Tet10;
        case 5: return ElementShape::Hex8;
        default: return std::nullopt;
    }
}

std::string gmsh_type_name(int type) {
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> local;
    try {
        gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
    } catch (...) {
        return "type " + std::to_string(type);
    }
    return name + " (Gmsh type " + std::to_string(type) + ")";
}

// The elements of one Gmsh entity, as returned by getElements.
struct EntityElements {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags;
    std::vector<std::vector<std::size_t>> nodes;
};

EntityElements elements_of(int dim, int tag) {
    EntityElements e;
    gmsh::model::mesh::getElements(e.types, e.tags, e.nodes, dim, tag);
    return e;
}

// Gmsh 4.8 indexes its table of physical names by dimension without checking it: a $PhysicalNames
// entry of dimension 4, 6 or -1 in an MSH 4 file crashes the process inside GModel::setPhysicalName
// (found by the fuzz target tests/fuzz/fuzz_gmsh, 2026-12-02; MSH 2.2 files skip such an entry). So
// the entries are checked here before Gmsh reads the file, read the way Gmsh's _readMSH4 reads them:
// a section starts wherever a 256-byte fgets() chunk begins with "$PhysicalNames" (a prefix test, and
// a chunk may begin in mid-line after an fscanf), then fscanf("%d") for the count and, per entry,
// "%d %d" and an fgets() of the rest of the line for the name. Every occurrence of the keyword is
// checked, a superset of the places Gmsh can take for a section header.
void check_physical_name_dimensions(const std::filesystem::path& path, const std::string& where) {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const char* const begin = text.c_str();
    const char* const end = begin + text.size();
    constexpr std::size_t kGmshLineBuffer = 255;  // fgets(str, 256, fp) reads at most 255 bytes
    // After an fgets() from `from`: the byte after the newline, or after 255 bytes.
    auto after_fgets = [&](const char* from) {
        const char* limit = std::min(end, from + kGmshLineBuffer);
        const char* newline = std::find(from, limit, '\n');
        return newline == limit ? limit : newline + 1;
    };
    auto read_int = [&](const char*& at, long& value) {  // fscanf("%d"): skips white space, stops at a non-digit
        char* stop = nullptr;
        value = std::strtol(at, &stop, 10);
        if (stop == at) return false;
        at = stop;
        return true;
    };
    const std::string keyword = "$PhysicalNames";
    for (std::size_t found = text.find(keyword); found != std::string::npos; found = text.find(keyword, found + 1)) {
        const char* at = after_fgets(begin + found);
        long count = 0;
        if (!read_int(at, count)) continue;  // Gmsh refuses the section itself
        for (long i = 0; i < count && at < end; ++i) {
            long dimension = 0, tag = 0;
            if (!read_int(at, dimension) || !read_int(at, tag)) break;
            if (dimension < 0 || dimension > 3) {
                const long line = 1 + std::count(begin, at, '\n');
                throw InputError(where + " is malformed: line " + std::to_string(line) + ": physical name of dimension " +
                                 std::to_string(dimension) + " (a physical group is of dimension 0, 1, 2 or 3)");
            }
            at = after_fgets(at);
        }
    }
}
}  // namespace

GmshSession::GmshSession() {
    gmsh_mutex().lock();
    if (gmsh_depth++ == 0) {
        try {
            // No configuration files: results must not depend on a user's ~/.gmshrc.
            gmsh::initialize(0, nullptr, false);
            gmsh::option::setNumber("General.Terminal", 0);
            gmsh::option::setNumber("General.Verbosity", 0);
            gmsh::option::setNumber("General.NumThreads", 1);  // deterministic meshes
        } catch (...) {
            --gmsh_depth;
            gmsh_mutex().unlock();
            throw;
        }
    }
}

GmshSession::~GmshSession() {
    if (--gmsh_depth == 0) {
        try {
            gmsh::finalize();
        } catch (...) {  // a destructor must not throw; Gmsh has nothing left to give back
        }
    }
    gmsh_mutex().unlock();
}

Mesh mesh_from_gmsh_model(const std::string& source) {
    // Every node of the model, by tag.
    std::vector<std::size_t> node_tags;
    std::vector<double> coord, parametric;
    gmsh::model::mesh::getNodes(node_tags, coord, parametric, -1, -1, false, false);
    std::unordered_map<std::size_t, std::size_t> position;  // tag -> index into node_tags
    position.reserve(node_tags.size());
    for (std::size_t i = 0; i < node_tags.size(); ++i) position.emplace(node_tags[i], i);

    // Nodes of elements of dimension above d, for the boundary-only test (header).
    std::vector<std::unordered_set<std::size_t>> nodes_above(4);
    for (int d = 3; d >= 1; --d) {
        EntityElements e = elements_of(d, -1);
        for (int below = 0; below < d; ++below)
            for (const auto& list : e.nodes) nodes_above[below].insert(list.begin(), list.end());
    }
    auto boundary_only = [&](int dim, const EntityElements& e) {
        if (dim >= 3 || nodes_above[dim].empty()) return false;
        for (const auto& list : e.nodes)
            for (std::size_t n : list)
                if (!nodes_above[dim].count(n)) return false;
        return true;
    };

    // Element blocks keyed by (part, Gmsh type), in order of first appearance; connectivity kept
    // in Gmsh tags until the nodes are renumbered.
    struct RawBlock { std::string part; ElementShape shape; std::vector<std::size_t> tags; };
    std::vector<RawBlock> raw;
    std::map<std::pair<std::string, int>, std::size_t> block_index;
    std::map<std::string, std::vector<std::size_t>> raw_sets;

    auto add_entity = [&](const std::string& part, int dim, int tag) {
        EntityElements e = elements_of(dim, tag);
        if (boundary_only(dim, e)) return;
        for (std::size_t t = 0; t < e.types.size(); ++t) {
            if (e.tags[t].empty()) continue;
            auto shape = shape_of_gmsh_type(e.types[t]);
            if (!shape)
                throw InputError(source + ": part '" + part + "' has elements of type " + gmsh_type_name(e.types[t]) +
                                 ", which the library does not support (supported: point, line2, tri3, quad4, quad8, "
                                 "tet4, tet10, hex8)");
            auto key = std::make_pair(part, e.types[t]);
            auto it = block_index.find(key);
            if (it == block_index.end()) {
                it = block_index.emplace(key, raw.size()).first;
                raw.push_back({part, *shape, {}});
            }
            auto& dst = raw[it->second].tags;
            dst.insert(dst.end(), e.nodes[t].begin(), e.nodes[t].end());
        }
    };

    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    if (groups.empty()) {
        gmsh::vectorpair entities;
        gmsh::model::getEntities(entities);
        for (const auto& [dim, tag] : entities) add_entity("mesh", dim, tag);
    }
    for (const auto& [dim, tag] : groups) {
        std::string name;
        gmsh::model::getPhysicalName(dim, tag, name);
        if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
        std::vector<int> entities;
        gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
        for (int ent : entities) add_entity(name, dim, ent);
        if (dim < 3) {
            std::vector<std::size_t> set_tags;
            std::vector<double> set_coord;
            gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, set_tags, set_coord);
            auto& dst = raw_sets[name];
            dst.insert(dst.end(), set_tags.begin(), set_tags.end());
        }
    }
    if (raw.empty()) throw InputError(source + " has no elements");

    // Renumber: the nodes used by a block or a node set, in increasing tag (unused nodes would be
    // massless in an explicit solver, so they are left out).
    std::vector<std::size_t> used;
    for (const auto& b : raw) used.insert(used.end(), b.tags.begin(), b.tags.end());
    for (const auto& [name, s] : raw_sets) used.insert(used.end(), s.begin(), s.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::unordered_map<std::size_t, int> index;
    index.reserve(used.size());
    Mesh mesh;
    mesh.nodes.reserve(used.size());
    for (std::size_t tag : used) {
        auto it = position.find(tag);
        if (it == position.end())
            throw InputError(source + ": an element refers to node " + std::to_string(tag) + ", which does not exist");
        const double* x = &coord[3 * it->second];
        index.emplace(tag, mesh.add_node(Vec3(x[0], x[1], x[2])));
    }
    for (const auto& b : raw) {
        ElementBlock block{b.part, b.shape, {}};
        block.connectivity.reserve(b.tags.size());
        for (std::size_t tag : b.tags) block.connectivity.push_back(index.at(tag));
        mesh.blocks.push_back(std::move(block));
    }
    for (const auto& [name, s] : raw_sets) {
        auto& ids = mesh.node_sets[name];
        for (std::size_t tag : s) ids.push_back(index.at(tag));
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    }
    return mesh;
}

Mesh read_gmsh(const std::filesystem::path& path) {
    const std::string where = "Gmsh mesh file '" + path.string() + "'";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(where + " does not exist");
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(where + " is not a regular file");
    if (path.extension() != ".msh")
        throw InputError(where + " does not end in .msh (only Gmsh mesh files are read, not geometry or scripts)");
    if (!std::ifstream(path)) throw InputError(where + " cannot be opened for reading");
    if (std::filesystem::file_size(path, ec) == 0) throw InputError(where + " is empty");

    check_physical_name_dimensions(path, where);

    GmshSession session;
    Mesh mesh;
    try {
        gmsh::clear();
        // Gmsh reads some malformed files with a warning only: a node or element id given twice is
        // "skipped" (one of the two silently wins, and the mesh is then wrong in a way that shows up
        // much later, as an inverted element). Such warnings are errors here.
        gmsh::option::setNumber("General.Verbosity", 2);  // warnings reach the logger (not the terminal)
        gmsh::logger::start();
        // merge, not open: gmsh::open holds a process-wide "busy" lock that a read which fails midway
        // never releases, and every later open in the process then reads nothing ("I'm busy! Ask me
        // that later...", Gmsh 4.8; found by the fuzz target tests/fuzz/fuzz_gmsh). After clear(),
        // merge reads a .msh file into the empty model the same way.
        gmsh::merge(path.string());
        std::vector<std::string> log;
        gmsh::logger::get(log);
        gmsh::logger::stop();
        gmsh::option::setNumber("General.Verbosity", 0);
        for (const std::string& line : log)
            if (line.rfind("Warning", 0) == 0 && line.find("uplicate") != std::string::npos)
                throw InputError(where + " is malformed: " + line.substr(line.find(':') + 2) +
                                 " (an id given twice; Gmsh would keep only one of them)");
        mesh = mesh_from_gmsh_model(where);
        gmsh::clear();
    } catch (const std::string& gmsh_error) {  // Gmsh's API throws its last error message
        // The logged errors and warnings say more than the last one ("Error loading ...").
        std::vector<std::string> log;
        gmsh::logger::get(log);
        gmsh::logger::stop();
        gmsh::option::setNumber("General.Verbosity", 0);
        gmsh::clear();
        std::string detail;
        for (const std::string& line : log)
            if ((line.rfind("Error", 0) == 0 || line.rfind("Warning", 0) == 0) && line.find(gmsh_error) == std::string::npos)
                detail += (detail.empty() ? " (" : "; ") + line.substr(line.find(':') + 2);
        if (detail.empty() && gmsh_error.rfind("Error loading", 0) == 0)
            detail = " (Gmsh stopped reading it: a truncated file, a section with fewer lines than its count, or a line with "
                     "missing fields";
        throw InputError(where + " is malformed: " + gmsh_error + (detail.empty() ? "" : detail + ")"));
    } catch (...) {
        gmsh::logger::stop();
        gmsh::option::setNumber("General.Verbosity", 0);
        gmsh::clear();
        throw;
    }
    try {
        validate(mesh);
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
    return mesh;
}

}  // namespace fem
