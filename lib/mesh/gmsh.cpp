#include "mesh/gmsh.hpp"

#include <gmsh.h>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <type_traits>
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

// What the conversion to a Mesh needs from a Gmsh model, copied out of Gmsh: read_gmsh has Gmsh read
// the file in a child process and hands this copy back through a pipe (see read_gmsh below), and the
// finger meshers convert the model they meshed in-process the same way (mesh_from_gmsh_model).
struct GmshEntity {
    int dim = 0, tag = 0;
    std::vector<int> types;                         // Gmsh element types
    std::vector<std::vector<std::size_t>> elements; // per type: the element tags (ElementBlock::ids)
    std::vector<std::vector<std::size_t>> nodes;    // per type: the node tags of its elements, concatenated
    template <class Io> void fields(Io& io) { io(dim, tag, types, elements, nodes); }
};
struct GmshGroup {
    int dim = 0, tag = 0;
    std::string name;
    std::vector<int> entities;
    std::vector<std::size_t> nodes;  // getNodesForPhysicalGroup (groups of dimension 0-2 only)
    template <class Io> void fields(Io& io) { io(dim, tag, name, entities, nodes); }
};
struct GmshModelCopy {
    std::vector<std::size_t> node_tags;
    std::vector<double> coord;         // x, y, z per node tag
    std::vector<GmshEntity> entities;  // every entity of the model, in Gmsh's order
    std::vector<GmshGroup> groups;
    std::vector<int> unsupported_types;  // types without a library element, with their Gmsh names
    std::vector<std::string> unsupported_names;
    template <class Io> void fields(Io& io) { io(node_tags, coord, entities, groups, unsupported_types, unsupported_names); }
};

// The current Gmsh model as a GmshModelCopy (the caller holds a session or is the reading child).
GmshModelCopy copy_of_gmsh_model() {
    GmshModelCopy c;
    std::vector<double> parametric;
    gmsh::model::mesh::getNodes(c.node_tags, c.coord, parametric, -1, -1, false, false);
    std::set<std::pair<int, int>> copied;
    auto copy_entity = [&](int dim, int tag) {
        if (!copied.emplace(dim, tag).second) return;
        GmshEntity e{dim, tag, {}, {}, {}};
        gmsh::model::mesh::getElements(e.types, e.elements, e.nodes, dim, tag);
        for (int type : e.types)
            if (!shape_of_gmsh_type(type) &&
                std::find(c.unsupported_types.begin(), c.unsupported_types.end(), type) == c.unsupported_types.end()) {
                c.unsupported_types.push_back(type);
                c.unsupported_names.push_back(gmsh_type_name(type));
            }
        c.entities.push_back(std::move(e));
    };
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities);
    for (const auto& [dim, tag] : entities) copy_entity(dim, tag);
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
        GmshGroup g{dim, tag, {}, {}, {}};
        gmsh::model::getPhysicalName(dim, tag, g.name);
        gmsh::model::getEntitiesForPhysicalGroup(dim, tag, g.entities);
        for (int ent : g.entities) copy_entity(dim, ent);
        if (dim < 3) {
            std::vector<double> set_coord;
            gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, g.nodes, set_coord);
        }
        c.groups.push_back(std::move(g));
    }
    return c;
}

// A GmshModelCopy through a pipe: one function, fields(), lists the members for both directions.
// Numbers and vectors of numbers go as raw bytes (the child is a fork of this very program, so the
// layout is the same at both ends), every vector and string preceded by its length.
class Packer {
public:
    std::string bytes;
    template <class... T> void operator()(T&... values) { (put(values), ...); }

private:
    template <class T> void put(T& v) {
        if constexpr (std::is_arithmetic_v<T>) {
            bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
        } else if constexpr (std::is_same_v<T, std::string>) {
            put_size(v.size());
            bytes.append(v);
        } else {
            v.fields(*this);
        }
    }
    template <class T> void put(std::vector<T>& v) {
        put_size(v.size());
        if constexpr (std::is_arithmetic_v<T>) {
            if (!v.empty()) bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
        } else {
            for (T& x : v) put(x);
        }
    }
    void put_size(std::uint64_t n) { put(n); }
};

class Unpacker {
public:
    explicit Unpacker(std::string_view bytes) : rest_(bytes) {}
    template <class... T> void operator()(T&... values) { (get(values), ...); }
    bool at_end() const { return rest_.empty(); }

private:
    std::string_view rest_;
    void take(void* to, std::size_t n) {
        if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not get
        if (n > rest_.size()) throw std::runtime_error("the Gmsh reader process sent a truncated model");
        std::memcpy(to, rest_.data(), n);
        rest_.remove_prefix(n);
    }
    std::size_t get_size(std::size_t element_bytes) {
        std::uint64_t n = 0;
        take(&n, sizeof n);
        if (n > rest_.size() / element_bytes) throw std::runtime_error("the Gmsh reader process sent a truncated model");
        return static_cast<std::size_t>(n);
    }
    template <class T> void get(T& v) {
        if constexpr (std::is_arithmetic_v<T>) {
            take(&v, sizeof v);
        } else if constexpr (std::is_same_v<T, std::string>) {
            v.resize(get_size(1));
            take(v.data(), v.size());
        } else {
            v.fields(*this);
        }
    }
    template <class T> void get(std::vector<T>& v) {
        if constexpr (std::is_arithmetic_v<T>) {
            v.resize(get_size(sizeof(T)));
            take(v.data(), v.size() * sizeof(T));
        } else {
            v.resize(get_size(sizeof(std::uint64_t)));  // every element takes at least one length
            for (T& x : v) get(x);
        }
    }
};

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

// Starts Gmsh quietly: no configuration files (results must not depend on a user's ~/.gmshrc), no
// terminal output, one thread (deterministic meshes).
void start_gmsh() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
    gmsh::option::setNumber("General.NumThreads", 1);
}

// A Mesh from a copy of a Gmsh model (rules in the header). `source` names the model in messages.
Mesh mesh_from_copy(const GmshModelCopy& model, const std::string& source) {
    std::unordered_map<std::size_t, std::size_t> position;  // node tag -> index into node_tags
    position.reserve(model.node_tags.size());
    for (std::size_t i = 0; i < model.node_tags.size(); ++i) position.emplace(model.node_tags[i], i);

    // Nodes of elements of dimension above d, for the boundary-only test (header).
    std::vector<std::unordered_set<std::size_t>> nodes_above(4);
    for (const GmshEntity& e : model.entities)
        for (int below = 0; below < std::clamp(e.dim, 0, 3); ++below)
            for (const auto& list : e.nodes) nodes_above[below].insert(list.begin(), list.end());
    auto boundary_only = [&](const GmshEntity& e) {
        if (e.dim >= 3 || e.dim < 0 || nodes_above[e.dim].empty()) return false;
        for (const auto& list : e.nodes)
            for (std::size_t n : list)
                if (!nodes_above[e.dim].count(n)) return false;
        return true;
    };
    std::map<std::pair<int, int>, const GmshEntity*> entity;
    for (const GmshEntity& e : model.entities) entity.emplace(std::make_pair(e.dim, e.tag), &e);

    // Element blocks keyed by (part, Gmsh type), in order of first appearance; connectivity kept
    // in Gmsh tags until the nodes are renumbered.
    struct RawBlock { std::string part; ElementShape shape; std::vector<std::size_t> tags; std::vector<long> ids; };
    std::vector<RawBlock> raw;
    std::map<std::pair<std::string, int>, std::size_t> block_index;
    std::map<std::string, std::vector<std::size_t>> raw_sets;

    auto add_entity = [&](const std::string& part, const GmshEntity& e) {
        if (boundary_only(e)) return;
        for (std::size_t t = 0; t < e.types.size() && t < e.nodes.size(); ++t) {
            if (e.nodes[t].empty()) continue;
            auto shape = shape_of_gmsh_type(e.types[t]);
            if (!shape) {
                const auto named = std::find(model.unsupported_types.begin(), model.unsupported_types.end(), e.types[t]);
                const std::size_t k = static_cast<std::size_t>(named - model.unsupported_types.begin());
                throw InputError(source + ": part '" + part + "' has elements of type " +
                                 (k < model.unsupported_names.size() ? model.unsupported_names[k]
                                                                     : "type " + std::to_string(e.types[t])) +
                                 ", which the library does not support (supported: point, line2, tri3, quad4, quad8, "
                                 "tet4, tet10, hex8)");
            }
            auto key = std::make_pair(part, e.types[t]);
            auto it = block_index.find(key);
            if (it == block_index.end()) {
                it = block_index.emplace(key, raw.size()).first;
                raw.push_back({part, *shape, {}, {}});
            }
            auto& dst = raw[it->second].tags;
            dst.insert(dst.end(), e.nodes[t].begin(), e.nodes[t].end());
            if (t < e.elements.size()) {
                auto& ids = raw[it->second].ids;
                ids.insert(ids.end(), e.elements[t].begin(), e.elements[t].end());
            }
        }
    };

    if (model.groups.empty())
        for (const GmshEntity& e : model.entities) add_entity("mesh", e);
    for (const GmshGroup& g : model.groups) {
        const std::string name =
            g.name.empty() ? "physical_" + std::to_string(g.dim) + "_" + std::to_string(g.tag) : g.name;
        for (int ent : g.entities) add_entity(name, *entity.at(std::make_pair(g.dim, ent)));
        if (g.dim < 3) {
            auto& dst = raw_sets[name];
            dst.insert(dst.end(), g.nodes.begin(), g.nodes.end());
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
        if (it == position.end() || 3 * it->second + 2 >= model.coord.size())
            throw InputError(source + ": an element refers to node " + std::to_string(tag) + ", which does not exist");
        const double* x = &model.coord[3 * it->second];
        index.emplace(tag, mesh.add_node(Vec3(x[0], x[1], x[2])));
    }
    for (const auto& b : raw) {
        ElementBlock block{b.part, b.shape, {}, {}};
        block.connectivity.reserve(b.tags.size());
        for (std::size_t tag : b.tags) block.connectivity.push_back(index.at(tag));
        if (b.ids.size() == static_cast<std::size_t>(block.size())) block.ids = b.ids;  // else numbered 1, 2, ...
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

// Gmsh reads the file into its (cleared) model; returns a copy of it. Runs in the reading child.
// `read_on` is cleared when a C++ exception ended Gmsh's read (its state may be half-changed).
GmshModelCopy copy_of_gmsh_file(const std::filesystem::path& path, const std::string& where, bool& read_on) {
    gmsh::clear();
    // Gmsh reads some malformed files with a warning only: a node or element id given twice is
    // "skipped" (one of the two silently wins, and the mesh is then wrong in a way that shows up
    // much later, as an inverted element). Such warnings are errors here.
    gmsh::option::setNumber("General.Verbosity", 2);  // warnings reach the logger (not the terminal)
    gmsh::logger::start();
    struct Quiet {  // the reader reads on: the next file's log starts empty, and Gmsh is quiet again
        ~Quiet() {
            try {
                gmsh::logger::stop();
                gmsh::option::setNumber("General.Verbosity", 0);
            } catch (...) {  // a destructor must not throw
            }
        }
    } quiet_afterwards;
    try {
        // merge into the cleared model rather than open: in Gmsh 4.8 a failed open() leaves a
        // process-wide "busy" lock behind, and every later open in the process reads nothing
        // (found by tests/fuzz/fuzz_gmsh).
        try {
            gmsh::merge(path.string());
        } catch (const std::bad_alloc&) {
            read_on = false;
            throw InputError(where + " is malformed: Gmsh ran out of memory reading it (a count in the file larger than "
                                     "this machine can hold?)");
        } catch (const std::exception& e) {  // e.g. std::length_error for a count near 2^64 (found by fuzz_gmsh)
            read_on = false;
            throw InputError(where + " is malformed: Gmsh's reader failed with \"" + e.what() + "\" (a count in the file "
                                     "too large?)");
        }
        std::vector<std::string> log;
        gmsh::logger::get(log);
        for (const std::string& line : log)
            if (line.rfind("Warning", 0) == 0 && line.find("uplicate") != std::string::npos)
                throw InputError(where + " is malformed: " + line.substr(line.find(':') + 2) +
                                 " (an id given twice; Gmsh would keep only one of them)");
        return copy_of_gmsh_model();
    } catch (const std::string& gmsh_error) {  // Gmsh's API throws its last error message
        // The logged errors and warnings say more than the last one ("Error loading ...").
        std::vector<std::string> log;
        gmsh::logger::get(log);
        std::string detail;
        for (const std::string& line : log)
            if ((line.rfind("Error", 0) == 0 || line.rfind("Warning", 0) == 0) && line.find(gmsh_error) == std::string::npos)
                detail += (detail.empty() ? " (" : "; ") + line.substr(line.find(':') + 2);
        if (detail.empty() && gmsh_error.rfind("Error loading", 0) == 0)
            detail = " (Gmsh stopped reading it: a truncated file, a section with fewer lines than its count, or a line with "
                     "missing fields";
        throw InputError(where + " is malformed: " + gmsh_error + (detail.empty() ? "" : detail + ")"));
    }
}

// The reader process and this one talk through a socket pair (send with MSG_NOSIGNAL: a reader that
// died must not kill this process with SIGPIPE), in messages of a length and that many bytes. A
// request is the file's path and its name for messages; a reply whether the reader leaves after it
// (kLeaving or kStaying), a kind byte, then the model or the message of the error.
constexpr char kModel = 'M', kInputError = 'I', kOtherError = 'E';
constexpr char kLeaving = 'L', kStaying = 'S';

bool send_message(int fd, const std::string& bytes) {
    const std::uint64_t length = bytes.size();
    std::string message(reinterpret_cast<const char*>(&length), sizeof length);
    message += bytes;
    std::string_view rest = message;
    while (!rest.empty()) {
        const ssize_t n = ::send(fd, rest.data(), rest.size(), MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        rest.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

// Reading from the other process: ok, closed (it died or left), or out of time (the deadline passed).
enum class Received { ok, closed, out_of_time };
using Deadline = std::optional<std::chrono::steady_clock::time_point>;

Received receive_exactly(int fd, char* to, std::size_t n, Deadline deadline) {
    while (n > 0) {
        if (deadline) {
            const auto left = std::chrono::ceil<std::chrono::milliseconds>(*deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) return Received::out_of_time;
            pollfd wait_for{fd, POLLIN, 0};
            const int ready = ::poll(&wait_for, 1, static_cast<int>(std::min<long long>(left.count(), 1 << 30)));
            if (ready < 0 && errno != EINTR) return Received::closed;
            if (ready <= 0) continue;
        }
        const ssize_t got = ::read(fd, to, n);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return Received::closed;
        to += got;
        n -= static_cast<std::size_t>(got);
    }
    return Received::ok;
}

Received receive_message(int fd, std::string& bytes, Deadline deadline = std::nullopt) {
    std::uint64_t length = 0;
    if (Received r = receive_exactly(fd, reinterpret_cast<char*>(&length), sizeof length, deadline); r != Received::ok)
        return r;
    bytes.resize(length);
    return receive_exactly(fd, bytes.data(), bytes.size(), deadline);
}

// Set by a sanitizer runtime (ASan, UBSan, libFuzzer's driver); weak, so null in a plain build.
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

// Reads this many files at most, then leaves to a fresh fork: libgmsh keeps some allocations of each
// read until exit, and a long fuzzing run would otherwise grow the reader without bound.
constexpr int kReadsPerReader = 1000;

// The reader process's whole life: read the requested files with Gmsh and reply, until this process
// closes its end (or exits). A crash inside Gmsh must end it by its signal and nothing else, which
// this process then reports:
//   - the default actions are restored for the signals a crash raises, and a sanitizer's "death
//     callback" is removed: under libFuzzer both would save the input as a crash of the fuzz target;
//     SIGINT is ignored: a Ctrl-C reaches the whole process group, and the handler inherited from
//     the parent (libFuzzer's: exit 72) would end the reader mid-read, misreported as a bad file;
//   - stderr goes to /dev/null: Gmsh prints nothing there (General.Terminal = 0), and what a
//     sanitizer would print (say, libgmsh asking for 2^51 bytes for a count in a malformed file,
//     which AddressSanitizer refuses with a report and an abort) is the crash this process reports;
//   - no core file; it dies with the thread that forked it (a fuzzer's timeout kills the fuzzer);
//   - _exit, not exit: no atexit handlers or static destructors (Gmsh's, the sanitizers' leak
//     check) and no flush of stdio buffers copied from this process.
// A read that a C++ exception ended inside Gmsh (std::length_error, std::bad_alloc) may leave Gmsh's
// state half-changed, so the reader leaves after replying to it; after Gmsh's own errors (which it
// cleans up after: ReadGmsh.AFailedReadDoesNotSpoilTheNextOne) and ours it reads on.
[[noreturn]] void serve_reads(int fd, pid_t parent) {
    for (int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTERM, SIGUSR1, SIGUSR2}) std::signal(signal, SIG_DFL);
    std::signal(SIGINT, SIG_IGN);  // Ctrl-C is the parent's to handle (a program's partial write, libFuzzer's stop)
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDERR_FILENO);
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);
    // The parent held the session lock while forking, so Gmsh's state here is consistent; the lock
    // itself is the parent thread's and is never taken here. Gmsh is started if the parent had not,
    // and never finalized.
    bool started = gmsh_depth > 0;
    std::string request;
    for (int reads = 1; receive_message(fd, request) == Received::ok; ++reads) {
        std::string path, where;
        Unpacker in(request);
        in(path, where);
        Packer out;
        char kind = kModel;
        bool read_on = true;
        try {
            if (!started) start_gmsh();
            started = true;
            GmshModelCopy model = copy_of_gmsh_file(path, where, read_on);
            out(kind, model);
        } catch (const InputError& e) {
            out.bytes.clear();
            kind = kInputError;
            std::string message = e.what();
            out(kind, message);
        } catch (const std::exception& e) {
            out.bytes.clear();
            kind = kOtherError;
            std::string message = where + ": " + e.what();
            out(kind, message);
            read_on = false;
        } catch (...) {
            out.bytes.clear();
            kind = kOtherError;
            std::string message = where + ": an unknown error in Gmsh's reader";
            out(kind, message);
            read_on = false;
        }
        const bool leaving = !read_on || reads == kReadsPerReader;
        if (!send_message(fd, (leaving ? kLeaving : kStaying) + out.bytes) || leaving) break;
    }
    ::_exit(0);
}

// How long Gmsh may take to read a file (set_gmsh_read_time_limit; guarded by gmsh_mutex()).
struct ReadTimeLimit {
    double base_seconds = 30;
    double seconds_per_megabyte = 10;
} read_time_limit;

// The reader process of this process (guarded by gmsh_mutex()).
struct ReaderProcess {
    pid_t pid = -1;
    pid_t owner = -1;  // the process that forked it: a fork of that process must not use it
    int fd = -1;
} reader;

void forget_reader() {
    if (reader.fd >= 0) ::close(reader.fd);
    reader = ReaderProcess{};
}

// Forks the reader process (the caller holds gmsh_mutex(), so no other thread is inside Gmsh while
// the reader takes its copy of Gmsh's state; stdio is flushed so that nothing buffered is copied).
void start_reader(const std::string& where) {
    int fds[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
        throw std::runtime_error(where + ": cannot create a socket pair for the Gmsh reader: " + std::strerror(errno));
    std::fflush(nullptr);
    const pid_t parent = ::getpid();
    const pid_t child = ::fork();
    if (child == 0) {
        ::close(fds[0]);
        serve_reads(fds[1], parent);
    }
    const int fork_errno = errno;
    ::close(fds[1]);
    if (child < 0) {
        ::close(fds[0]);
        throw std::runtime_error(where + ": cannot start the Gmsh reader process: " + std::strerror(fork_errno));
    }
    reader = ReaderProcess{child, parent, fds[0]};
}

// Has the reader process read `path` and returns its reply; throws InputError when Gmsh crashed on it.
std::string reply_of_reader(const std::filesystem::path& path, const std::string& where) {
    std::lock_guard<std::recursive_mutex> lock(gmsh_mutex());
    if (reader.pid > 0 && reader.owner != ::getpid()) forget_reader();  // the reader of the process we were forked from
    if (reader.pid > 0 && ::waitpid(reader.pid, nullptr, WNOHANG) != 0)
        forget_reader();  // killed between reads (it dies with the thread that forked it)
    if (reader.pid < 0) start_reader(where);
    Packer request;
    std::string path_string = path.string(), name = where;
    request(path_string, name);
    std::error_code ec;
    const double megabytes = static_cast<double>(std::filesystem::file_size(path, ec)) / 1e6;
    const double seconds = read_time_limit.base_seconds + read_time_limit.seconds_per_megabyte * megabytes;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                                 std::chrono::duration<double>(seconds));
    std::string reply;
    const Received received = send_message(reader.fd, request.bytes) ? receive_message(reader.fd, reply, deadline)
                                                                     : Received::closed;
    if (received == Received::ok && !reply.empty()) {
        if (reply[0] == kLeaving) {
            const pid_t pid = reader.pid;
            forget_reader();
            while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
            }
        }
        return reply.substr(1);
    }
    if (received == Received::out_of_time) {
        const pid_t pid = reader.pid;
        forget_reader();
        ::kill(pid, SIGKILL);
        while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
        }
        std::ostringstream limit;
        limit << std::setprecision(3) << seconds;
        throw InputError(where + " is malformed: Gmsh did not finish reading it in " + limit.str() + " s (" +
                         std::to_string(std::filesystem::file_size(path, ec)) +
                         " bytes; a count in the file far larger than the data it holds?)");
    }

    // No reply: the reader died reading this file. Every way it can die there is the file's doing and
    // is reported alike, naming the file: a fatal signal (which one depends on what Gmsh's reader
    // does with the malformed data: SIGSEGV for a null or wild pointer, SIGBUS, SIGFPE, SIGABRT from
    // glibc's heap checks or AddressSanitizer with abort_on_error), or an exit without an answer (a
    // sanitizer's report with its default exit status 1, or libgmsh calling exit()).
    const pid_t pid = reader.pid;
    forget_reader();
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error(where + ": lost the Gmsh reader process: " + std::strerror(errno));
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        throw InputError("Gmsh crashed reading '" + path.string() + "' (signal " + std::to_string(signal) + ", " +
                         ::strsignal(signal) + "): the file is malformed");
    }
    throw InputError("Gmsh stopped reading '" + path.string() + "' without an answer (its reader process exited with status " +
                     std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                     ": a sanitizer's report on Gmsh's code, or Gmsh exiting on the file): the file is malformed");
}
}  // namespace

namespace {
// The calling thread's OpenMP thread count (1 without OpenMP), and setting it back (GmshSession).
int omp_threads() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}
void set_omp_threads(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}
}  // namespace

GmshSession::GmshSession() : caller_threads_(omp_threads()) {
    gmsh_mutex().lock();
    if (gmsh_depth++ == 0) {
        try {
            start_gmsh();
        } catch (...) {
            --gmsh_depth;
            set_omp_threads(caller_threads_);
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
    set_omp_threads(caller_threads_);  // Gmsh set its own (gmsh.hpp)
    gmsh_mutex().unlock();
}

void set_gmsh_read_time_limit(double base_seconds, double seconds_per_megabyte) {
    std::lock_guard<std::recursive_mutex> lock(gmsh_mutex());
    read_time_limit = {base_seconds, seconds_per_megabyte};
}

Mesh mesh_from_gmsh_model(const std::string& source) { return mesh_from_copy(copy_of_gmsh_model(), source); }

// Gmsh reads the file in a reader process (a fork of this one, serve_reads), which sends a copy of
// the model back; this process converts and validates it. Why: libgmsh 4.8's readers crash on some
// malformed files (three found by tests/fuzz/fuzz_gmsh: two through $PhysicalNames, refused with a
// better message by the pre-check above, and a SIGSEGV in _associateEntityWithMeshVertices from
// _readMSH2 on a malformed MSH 2.2 $Elements section), and pre-checks cannot follow every path inside
// Gmsh. In a separate process a crash is that process's death by a signal, which becomes an
// InputError naming the file; Gmsh's leaks and global state stay there too. libgmsh stays the reader,
// rather than a parser of our own, because it reads every format a user's Gmsh writes (2.2 and 4.1,
// ASCII and binary, entities, partitions, periodic sections) and the in-process meshers need it
// anyway. One reader process serves the reads of this process, not a fork per file: under
// AddressSanitizer a fork per file made the fuzz target 5x slower (10 against 54 executions/s with
// the same seed and inputs, load 6). A read that takes longer than the time limit
// (set_gmsh_read_time_limit) is killed and refused the same way.
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

    const std::string reply = reply_of_reader(path, where);
    Unpacker in(reply);
    char kind = 0;
    in(kind);
    if (kind != kModel) {
        std::string message;
        in(message);
        if (kind == kInputError) throw InputError(message);
        throw std::runtime_error(message);
    }
    GmshModelCopy model;
    in(model);
    if (!in.at_end()) throw std::runtime_error(where + ": the Gmsh reader process sent more than a model");
    Mesh mesh = mesh_from_copy(model, where);
    try {
        validate(mesh);
    } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
    }
    return mesh;
}

}  // namespace fem
