#pragma once
// Progress of long work, on stderr: stdout keeps the results that scripts read (tables, JSON).
// On a terminal, one line redrawn in place (bar, fraction done, rate, elapsed and time left),
// also between steps so that a long step still shows time passing; elsewhere (pipes, CI) one
// plain line per step, flushed, without escape codes; with --quiet, nothing.
#include <CLI/CLI.hpp>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>

namespace edacrt::cli {

enum class ProgressStyle { quiet, terminal, lines };

/// terminal when stderr is one (and TERM is not "dumb"), lines otherwise, quiet when asked.
ProgressStyle progress_style(bool quiet);

/// The --quiet flag, described once for every command that shows progress.
void add_quiet_option(CLI::App& command, bool& quiet);

class Progress {
  public:
    /// What the rate counts: rays (shown in Mrays/s) or samples per pixel (spp/s).
    enum class Unit { rays, samples };

    Progress(ProgressStyle style, std::string task, Unit unit);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Time left before the first step has measured one (an estimate made up front).
    void expect_seconds(double seconds);

    /// The work now under way, shown on a terminal until the next update.
    void begin(std::string what);

    /// Progress within a step: `fraction` of the task done (negative: unknown), `amount` the
    /// rays or samples done so far, `what` the state, `detail` less important figures (last
    /// on a terminal, where a narrow window cuts the line). Redraws the terminal line only.
    void update(double fraction, double amount, std::string what, std::string detail = {});

    /// update(), and in lines style one line for the step.
    void step(double fraction, double amount, std::string what, std::string detail = {});

    /// Writes a line of results to `out` (flushed), with the terminal line cleared around it.
    void print(std::ostream& out, const std::string& line);

    /// Clears the terminal line until the next update, for output that does not go through
    /// print() (a loader's messages).
    void clear();

    /// Clears the terminal line and stops redrawing; the destructor calls it.
    void finish();

  private:
    std::string line(bool terminal) const;  // the state as text; the caller holds mutex_
    void draw();                            // the terminal line; the caller holds mutex_
    void tick();                            // the redrawing thread

    using Clock = std::chrono::steady_clock;
    ProgressStyle style_;
    std::string task_;
    Unit unit_;
    Clock::time_point start_ = Clock::now();
    double fraction_ = 0.0, amount_ = 0.0;
    double step_seconds_ = 0.0;  // elapsed when fraction_ was measured
    std::optional<double> expected_seconds_;
    std::string what_, detail_;
    int spinner_ = 0;
    bool drawn_ = false, finished_ = false;

    std::mutex mutex_;
    std::condition_variable wake_;
    std::thread ticker_;
};

/// "4.2 s", "42 s", "3 min 05 s", "1 h 02 min": durations for people.
std::string format_duration(double seconds);

/// "0:42", "3:05", "1:02:03": durations on a progress line.
std::string format_clock(double seconds);

}  // namespace edacrt::cli
