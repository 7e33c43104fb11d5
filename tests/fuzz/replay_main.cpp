// The fuzz targets in the normal build: a main() that feeds LLVMFuzzerTestOneInput, without libFuzzer.
//
//   fuzz_<target> [--mutations N] [--seed S] [--save DIR] CORPUS...
//
// First every file of the CORPUS folders (or files) once: CTest replays tests/fuzz/corpus/<target> on
// every build. Then, with --mutations N, N inputs made from the corpus by a fixed-seed mutator (byte
// and bit flips, insertions of random bytes or of tokens a parser trips on, deletions, duplicated
// ranges, truncation, splicing two corpus files): a short, deterministic fuzz run in CTest, the
// gcc-built sibling of `make fuzz` (which links the same targets with libFuzzer and the sanitizers).
// An input that crashes the target (a signal, an exception other than InputError escaping it) or
// takes more than 20 s is written to DIR/fuzz-<target>-<seed>-<n>.input and its name printed;
// `fuzz_<target> that-file` replays it. The same seed always makes the same inputs (the mutator uses
// no library distribution, only std::mt19937_64's specified sequence).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

Bytes read_bytes(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Tokens the readers must refuse or take whole (numbers at their limits, TOML and Gmsh syntax).
const std::vector<std::string_view> kTokens = {
    "0",   "-1",  "1e308", "-1e308", "1e-320", "nan",          "inf",        "-inf",        "4294967298", "9223372036854775808",
    "2.5", "\"",  "'",     "[",      "]",      "[[",           "]]",         "{",           "}",          "=",
    ",",   ".",   "#",     "\n",     "\r\n",   "\"\"\"",       "true",       "\\u0000",     "$Nodes",     "$EndNodes",
    "$Elements", "$EndElements", "$MeshFormat", "*NODE", "*ELEMENT", "*INCLUDE", "*STEP", "1,2,3", "\t", " "};

// The mutator: a few edits of a corpus input, drawn from a fixed-seed generator.
class Mutator {
public:
    Mutator(std::uint64_t seed, const std::vector<Bytes>& corpus) : rng_(seed), corpus_(corpus) {}

    Bytes next(std::size_t& from) {
        from = below(corpus_.size());
        Bytes b = corpus_[from];
        const std::size_t edits = 1 + below(4);
        for (std::size_t e = 0; e < edits; ++e) edit(b);
        return b;
    }

private:
    std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }

    void edit(Bytes& b) {
        const std::size_t at = below(b.size() + 1);
        switch (below(8)) {
            case 0:  // flip one bit
                if (!b.empty()) b[std::min(at, b.size() - 1)] ^= static_cast<std::uint8_t>(1u << below(8));
                break;
            case 1:  // replace a byte
                if (!b.empty()) b[std::min(at, b.size() - 1)] = static_cast<std::uint8_t>(below(256));
                break;
            case 2: {  // insert random bytes
                const std::size_t n = 1 + below(8);
                for (std::size_t k = 0; k < n; ++k) b.insert(b.begin() + static_cast<long>(at), static_cast<std::uint8_t>(below(256)));
                break;
            }
            case 3: {  // insert a token
                const std::string_view t = kTokens[below(kTokens.size())];
                b.insert(b.begin() + static_cast<long>(at), t.begin(), t.end());
                break;
            }
            case 4: {  // delete a range
                const std::size_t n = std::min(b.size() - std::min(at, b.size()), 1 + below(32));
                b.erase(b.begin() + static_cast<long>(at), b.begin() + static_cast<long>(at + n));
                break;
            }
            case 5: {  // duplicate a range (repeated keys, sections, lines)
                const std::size_t n = std::min(b.size() - std::min(at, b.size()), 1 + below(64));
                const Bytes piece(b.begin() + static_cast<long>(at), b.begin() + static_cast<long>(at + n));
                const std::size_t to = below(b.size() + 1);
                b.insert(b.begin() + static_cast<long>(to), piece.begin(), piece.end());
                break;
            }
            case 6:  // truncate
                b.resize(at);
                break;
            default: {  // splice: this input's head, another corpus file's tail
                const Bytes& other = corpus_[below(corpus_.size())];
                const std::size_t from = below(other.size() + 1);
                b.resize(at);
                b.insert(b.end(), other.begin() + static_cast<long>(from), other.end());
                break;
            }
        }
    }

    std::mt19937_64 rng_;
    const std::vector<Bytes>& corpus_;
};

// The input being run, for the signal handler and the watchdog (set before each call).
std::string g_target;
const Bytes* g_input = nullptr;
char g_save_path[4096] = {};
std::atomic<long> g_started{-1};  // steady-clock seconds when the current input started; -1 between inputs
pid_t g_pid = 0;  // this process (a target's helper process, e.g. read_gmsh's reader fork, reports nothing)

// Writes the current input to g_save_path with async-signal-safe calls only, and says so on stderr.
void save_current(const char* what) {
    if (g_input == nullptr || g_save_path[0] == '\0') return;
    const int fd = ::open(g_save_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        std::size_t done = 0;
        while (done < g_input->size()) {
            const ssize_t n = ::write(fd, g_input->data() + done, g_input->size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        ::close(fd);
    }
    const auto say = [](const char* s) { (void)!::write(2, s, std::strlen(s)); };
    say("\n");
    say(g_target.c_str());
    say(": ");
    say(what);
    say(" on a mutated input, written to ");
    say(g_save_path);
    say(" (replay: ");
    say(g_target.c_str());
    say(" ");
    say(g_save_path);
    say(")\n");
}

extern "C" void on_crash(int sig) {
    if (::getpid() == g_pid)
        save_current(sig == SIGSEGV ? "SIGSEGV" : sig == SIGABRT ? "SIGABRT" : sig == SIGFPE ? "SIGFPE" : "a fatal signal");
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

long now_s() {
    return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
    g_target = fs::path(argv[0]).filename().string();
    long mutations = 0;
    std::uint64_t seed = 1;
    fs::path save = ".";
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if ((a == "--mutations" || a == "--seed" || a == "--save") && i + 1 < argc) {
            const char* v = argv[++i];
            if (a == "--mutations") mutations = std::strtol(v, nullptr, 10);
            else if (a == "--seed") seed = std::strtoull(v, nullptr, 10);
            else save = v;
        } else if (fs::is_directory(a)) {
            for (const auto& e : fs::recursive_directory_iterator(a))
                if (e.is_regular_file()) files.push_back(e.path());
        } else if (fs::is_regular_file(a)) {
            files.push_back(a);
        } else {
            std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] [--save DIR] CORPUS...\n(no file or folder '%s')\n",
                         g_target.c_str(), argv[i]);
            return 2;
        }
    }
    std::sort(files.begin(), files.end());
    std::vector<Bytes> corpus;
    for (const auto& f : files) {
        corpus.push_back(read_bytes(f));
        LLVMFuzzerTestOneInput(corpus.back().data(), corpus.back().size());
    }
    std::printf("replayed %zu inputs without a crash\n", files.size());
    std::fflush(stdout);  // before a mutated input may crash the process
    if (files.empty()) return 1;
    if (mutations <= 0) return 0;

    g_pid = ::getpid();
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL}) std::signal(sig, on_crash);
    // The watchdog: an input that runs more than 20 s is a hang (the slowest corpus input takes 0.1 s).
    std::thread([] {
        for (;;) {
            std::this_thread::sleep_for(std::chrono::seconds(1));
            const long started = g_started.load();
            if (started >= 0 && now_s() - started > 20) {
                save_current("a hang (more than 20 s)");
                std::_Exit(1);
            }
        }
    }).detach();

    const auto t0 = std::chrono::steady_clock::now();
    Mutator mutator(seed, corpus);
    for (long n = 0; n < mutations; ++n) {
        std::size_t from = 0;
        const Bytes input = mutator.next(from);
        const std::string path = (save / (g_target + "-" + std::to_string(seed) + "-" + std::to_string(n) + ".input")).string();
        std::snprintf(g_save_path, sizeof g_save_path, "%s", path.c_str());
        g_input = &input;
        g_started = now_s();
        try {
            LLVMFuzzerTestOneInput(input.data(), input.size());
        } catch (const std::exception& e) {
            save_current((std::string("an exception escaped (") + e.what() + ")").c_str());
            return 1;
        } catch (...) {
            save_current("an unknown exception escaped");
            return 1;
        }
        g_started = -1;
        g_input = nullptr;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("ran %ld mutated inputs (seed %llu) without a crash in %.1f s\n", mutations,
                static_cast<unsigned long long>(seed), seconds);
    return 0;
}
