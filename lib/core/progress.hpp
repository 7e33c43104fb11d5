#pragma once
// Runs a user can watch and stop: progress of long runs (explicit solves, topology iterations) on
// stderr, and Ctrl-C (SIGINT) as a clean stop.
//
// Progress: on a terminal one updating line (percent, the run's own details such as simulated time,
// steps and element-cycles/s, and the time left), redrawn at most twice a second; otherwise (CI
// logs, files) one line per 10 %. Programs turn it off with --quiet (Progress::set_quiet).
//
//   Progress progress("drop", end_time);                       // mode from isatty(stderr)
//   while (t < end_time) {
//       ...
//       if (progress.due(t)) progress.show(t, fmt::format("t = {:.4g} s, step {}", t, step));
//       if (interrupt_requested()) break;                       // Ctrl-C: stop after this cycle
//   }
//   progress.finish();
//
// Interrupts: while an InterruptGuard lives, the first SIGINT only sets a flag that the run polls
// (interrupt_requested()); every run going on stops at the end of its cycle or iteration, writes
// what it has with a note that it is partial, and throws Interrupted, which run_program turns into
// exit status 130 (128 + SIGINT, the shell's convention) and clears the flag. A second Ctrl-C kills
// the process as usual.
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace fem {

class Progress {
public:
    enum class Mode { Auto, Terminal, Log, Quiet };
    /// `name` starts each line; `total` is what done counts up to (end time, iterations). Auto:
    /// Terminal when stderr is a terminal, else Log; Quiet when set_quiet(true) was called.
    Progress(std::string name, double total, Mode mode = Mode::Auto, std::FILE* out = stderr);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// True when a line is due at `done` (cheap: call it every cycle and build the details only
    /// when it says so).
    bool due(double done);
    /// Prints the line for `done` with the run's details ("t = 1.2e-3 s, step 340, 2.1e6
    /// element-cycles/s"); the percentage and the time left are added.
    void show(double done, const std::string& details);
    /// Ends the updating line (Terminal).
    void finish();

    Mode mode() const { return mode_; }
    /// Every Progress made afterwards with Mode::Auto is quiet (a program's --quiet).
    static void set_quiet(bool quiet);

private:
    std::string name_;
    double total_;
    Mode mode_;
    std::FILE* out_;
    std::chrono::steady_clock::time_point start_, last_;
    int next_tenth_ = 1;  // Log: the next 10 % mark to print
    bool open_line_ = false;
};

/// Thrown by a run stopped by Ctrl-C after it wrote its partial results; run_program exits 130.
class Interrupted : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// While alive, SIGINT sets the interrupt flag instead of killing the process (once: a second
/// SIGINT has the default effect). Restores the previous handler when destroyed. Nests.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
};

/// True once SIGINT arrived under an InterruptGuard (until clear_interrupt()).
bool interrupt_requested();
/// Resets the flag (a program that handled the interrupt, tests).
void clear_interrupt();

}  // namespace fem
