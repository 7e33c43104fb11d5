// Progress lines and the Ctrl-C flag (core/progress.hpp).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <string>

#include "core/progress.hpp"

using namespace fem;

namespace {
std::string contents(std::FILE* f) {
    std::rewind(f);
    std::string s;
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, f)) s.append(buffer, n);
    return s;
}
int count(const std::string& s, const std::string& what) {
    int n = 0;
    for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
}
}  // namespace

// Not a terminal (a CI log): one line per 10 %, whatever the number of updates.
TEST(Progress, LogModePrintsOneLinePerTenPercent) {
    std::FILE* f = std::tmpfile();
    {
        Progress p("run", 2.0, Progress::Mode::Log, f);
        for (int k = 0; k <= 1000; ++k) {
            const double done = 2.0 * k / 1000;
            if (p.due(done)) p.show(done, "step " + std::to_string(k));
        }
    }
    const std::string s = contents(f);
    std::fclose(f);
    EXPECT_EQ(count(s, "\n"), 10) << s;
    EXPECT_NE(s.find("run:  10.0 %  step 100  ("), std::string::npos) << s;
    EXPECT_NE(s.find("run: 100.0 %  step 1000  ("), std::string::npos) << s;
    EXPECT_NE(s.find(" left)"), std::string::npos) << s;
}

// A terminal: the line is redrawn in place (carriage return, clear to the end of the line), at most
// twice a second, and ended by a newline.
TEST(Progress, TerminalModeRedrawsOneLine) {
    std::FILE* f = std::tmpfile();
    {
        Progress p("run", 1.0, Progress::Mode::Terminal, f);
        int shown = 0;
        for (int k = 0; k < 100000; ++k)
            if (p.due(k * 1e-5)) p.show(k * 1e-5, "x"), ++shown;
        EXPECT_LE(shown, 2);  // 100000 cheap updates take far less than a second
        p.show(0.5, "half");
    }
    const std::string s = contents(f);
    std::fclose(f);
    EXPECT_NE(s.find("\rrun:  50.0 %  half  ("), std::string::npos) << s;
    EXPECT_EQ(count(s, "\n"), 1);
    EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, QuietPrintsNothing) {
    std::FILE* f = std::tmpfile();
    Progress::set_quiet(true);
    {
        Progress p("run", 1.0, Progress::Mode::Auto, f);
        EXPECT_EQ(p.mode(), Progress::Mode::Quiet);
        for (int k = 0; k <= 10; ++k)
            if (p.due(k / 10.0)) p.show(k / 10.0, "x");
    }
    Progress::set_quiet(false);
    EXPECT_EQ(contents(f), "");
    std::fclose(f);
}

// Under an InterruptGuard SIGINT sets the flag (the process goes on); the guard restores the
// previous handler when it ends.
TEST(Interrupt, GuardTurnsSigintIntoAFlag) {
    clear_interrupt();
    {
        const InterruptGuard guard;
        EXPECT_FALSE(interrupt_requested());
        std::raise(SIGINT);
        EXPECT_TRUE(interrupt_requested());
        clear_interrupt();
    }
    struct sigaction now {};
    sigaction(SIGINT, nullptr, &now);
    EXPECT_EQ(now.sa_handler, SIG_DFL);
    EXPECT_FALSE(interrupt_requested());
}
