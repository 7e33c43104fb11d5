#include "core/progress.hpp"

#include <atomic>
#include <cmath>
#include <csignal>
#include <mutex>

#include <unistd.h>

#include <fmt/format.h>

namespace fem {
namespace {

std::atomic<bool> g_quiet{false};
volatile std::sig_atomic_t g_interrupt = 0;
std::mutex g_guard_mutex;  // guards may start and end on several threads (cases run at once)
int g_guards = 0;
struct sigaction g_previous;

extern "C" void on_sigint(int) {
    g_interrupt = 1;
    // A second Ctrl-C kills as usual.
    std::signal(SIGINT, SIG_DFL);
}

std::string duration(double s) {
    if (!std::isfinite(s) || s < 0) return "?";
    if (s < 60) return fmt::format("{:.0f} s", s);
    if (s < 3600) return fmt::format("{:.0f} min {:02.0f} s", std::floor(s / 60), std::fmod(s, 60));
    return fmt::format("{:.0f} h {:02.0f} min", std::floor(s / 3600), std::floor(std::fmod(s, 3600) / 60));
}

}  // namespace

Progress::Progress(std::string name, double total, Mode mode, std::FILE* out)
    : name_(std::move(name)), total_(total), mode_(mode), out_(out), start_(std::chrono::steady_clock::now()), last_(start_) {
    if (mode_ == Mode::Auto)
        mode_ = g_quiet ? Mode::Quiet : isatty(fileno(out_)) ? Mode::Terminal : Mode::Log;
    if (!(total_ > 0)) mode_ = Mode::Quiet;
}

Progress::~Progress() { finish(); }

bool Progress::due(double done) {
    switch (mode_) {
        case Mode::Quiet: return false;
        case Mode::Log: return next_tenth_ <= 10 && done >= total_ * next_tenth_ / 10.0 * (1 - 1e-12);
        default: {
            const auto now = std::chrono::steady_clock::now();
            if (std::chrono::duration<double>(now - last_).count() < 0.5) return false;
            last_ = now;
            return true;
        }
    }
}

void Progress::show(double done, const std::string& details) {
    if (mode_ == Mode::Quiet) return;
    const double fraction = std::min(std::max(done / total_, 0.0), 1.0);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const std::string left = fraction > 0 ? duration(elapsed * (1 - fraction) / fraction) : "?";
    const std::string line = fmt::format("{}: {:5.1f} %  {}  ({} elapsed, {} left)", name_, 100 * fraction, details,
                                         duration(elapsed), left);
    if (mode_ == Mode::Terminal) {
        std::fprintf(out_, "\r%s\033[K", line.c_str());  // \033[K clears the rest of the old line
        open_line_ = true;
    } else {
        std::fprintf(out_, "%s\n", line.c_str());
        while (next_tenth_ <= 10 && done >= total_ * next_tenth_ / 10.0 * (1 - 1e-12)) ++next_tenth_;
    }
    std::fflush(out_);
}

void Progress::finish() {
    if (open_line_) std::fprintf(out_, "\n");
    open_line_ = false;
}

void Progress::set_quiet(bool quiet) { g_quiet = quiet; }

InterruptGuard::InterruptGuard() {
    const std::lock_guard<std::mutex> lock(g_guard_mutex);
    if (g_guards++ == 0) {
        struct sigaction sa {};
        sa.sa_handler = on_sigint;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGINT, &sa, &g_previous);
    }
}

InterruptGuard::~InterruptGuard() {
    const std::lock_guard<std::mutex> lock(g_guard_mutex);
    if (--g_guards == 0) sigaction(SIGINT, &g_previous, nullptr);
}

bool interrupt_requested() { return g_interrupt != 0; }
void clear_interrupt() { g_interrupt = 0; }

}  // namespace fem
