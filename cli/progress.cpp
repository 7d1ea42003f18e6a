#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

namespace edacrt::cli {
namespace {

// Often enough that elapsed time visibly moves, rarely enough to cost nothing.
constexpr auto kRedrawInterval = std::chrono::milliseconds(250);
constexpr std::size_t kBarWidth = 10;

int terminal_columns() {
    winsize size{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    return 80;
}

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

}  // namespace

ProgressStyle progress_style(bool quiet) {
    if (quiet) return ProgressStyle::quiet;
    const char* term = std::getenv("TERM");
    const bool dumb = term && std::strcmp(term, "dumb") == 0;
    return isatty(STDERR_FILENO) && !dumb ? ProgressStyle::terminal : ProgressStyle::lines;
}

void add_quiet_option(CLI::App& command, bool& quiet) {
    command.add_flag("--quiet,-q", quiet,
                     "no progress on stderr (on a terminal a line updated in place, otherwise a "
                     "line per step)");
}

std::string format_duration(double seconds) {
    const long long s = std::llround(std::max(seconds, 0.0));
    char text[48];
    if (seconds < 10.0)
        std::snprintf(text, sizeof text, "%.1f s", std::max(seconds, 0.0));
    else if (s < 60)
        std::snprintf(text, sizeof text, "%lld s", s);
    else if (s < 3600)
        std::snprintf(text, sizeof text, "%lld min %02lld s", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lld h %02lld min", s / 3600, s / 60 % 60);
    return text;
}

std::string format_clock(double seconds) {
    const long long s = std::llround(std::max(seconds, 0.0));
    char text[32];
    if (s < 3600)
        std::snprintf(text, sizeof text, "%lld:%02lld", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
    return text;
}

Progress::Progress(ProgressStyle style, std::string task, Unit unit)
    : style_(style), task_(std::move(task)), unit_(unit) {
    if (style_ == ProgressStyle::terminal) ticker_ = std::thread([this] { tick(); });
}

Progress::~Progress() { finish(); }

void Progress::expect_seconds(double seconds) {
    const std::lock_guard lock(mutex_);
    expected_seconds_ = seconds;
}

void Progress::begin(std::string what) {
    const std::lock_guard lock(mutex_);
    what_ = std::move(what);
    detail_.clear();
    draw();
}

void Progress::update(double fraction, double amount, std::string what, std::string detail) {
    const std::lock_guard lock(mutex_);
    fraction_ = std::min(fraction, 1.0);
    amount_ = amount;
    step_seconds_ = std::chrono::duration<double>(Clock::now() - start_).count();
    what_ = std::move(what);
    detail_ = std::move(detail);
    draw();
}

void Progress::step(double fraction, double amount, std::string what, std::string detail) {
    update(fraction, amount, std::move(what), std::move(detail));
    if (style_ != ProgressStyle::lines) return;
    const std::lock_guard lock(mutex_);
    std::cerr << line(false) << std::endl;
}

void Progress::print(std::ostream& out, const std::string& text) {
    const std::lock_guard lock(mutex_);
    if (drawn_) std::cerr << "\r\033[K" << std::flush;
    out << text << std::endl;
    if (drawn_) draw();
}

void Progress::clear() {
    const std::lock_guard lock(mutex_);
    if (drawn_) std::cerr << "\r\033[K" << std::flush;
    drawn_ = false;
}

void Progress::finish() {
    {
        const std::lock_guard lock(mutex_);
        if (finished_) return;
        finished_ = true;
        if (drawn_) std::cerr << "\r\033[K" << std::flush;
        drawn_ = false;
    }
    wake_.notify_all();
    if (ticker_.joinable()) ticker_.join();
}

std::string Progress::line(bool terminal) const {
    const double now = std::chrono::duration<double>(Clock::now() - start_).count();
    const bool known = fraction_ >= 0.0;
    std::string rate;
    if (amount_ > 0.0 && step_seconds_ > 0.0)
        rate = unit_ == Unit::rays ? format("%.3g Mrays/s", amount_ / step_seconds_ * 1e-6)
                                   : format("%.3g spp/s", amount_ / step_seconds_);
    // From the fraction's pace at the last update, counting down between updates; before the
    // first, from the estimate made up front.
    const bool done = known && fraction_ >= 1.0;
    std::optional<double> left;
    if (!done && known && fraction_ > 0.0)
        left = std::max(step_seconds_ / fraction_ - now, 0.0);
    else if (!done && expected_seconds_)
        left = std::max(*expected_seconds_ - now, 0.0);

    if (!terminal) {
        std::vector<std::string> parts;
        if (known) parts.push_back(format("%.1f%%", 100.0 * fraction_));
        if (!rate.empty()) parts.push_back(rate);
        if (!detail_.empty()) parts.push_back(detail_);
        parts.push_back(format_duration(now) + " elapsed");
        if (left) parts.push_back("about " + format_duration(*left) + " left");
        std::string text = task_ + ": " + what_ + " (";
        for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? ", " : "") + parts[i];
        return text + ")";
    }
    // The most telling first: a narrow terminal cuts the end.
    std::string text = task_ + " ";
    if (known) {
        const auto filled = std::size_t(fraction_ * kBarWidth);
        text += "[" + std::string(filled, '#') + std::string(kBarWidth - filled, '-') + "] " +
                format("%3.0f%%", 100.0 * fraction_);
    } else {
        text += "|/-\\"[spinner_ % 4];
    }
    text += "  " + what_ + "  " + format_clock(now) + " elapsed";
    if (left) text += ", " + format_clock(*left) + " left";
    if (!rate.empty()) text += "  " + rate;
    if (!detail_.empty()) text += "  " + detail_;
    return text;
}

void Progress::draw() {
    if (style_ != ProgressStyle::terminal || finished_) return;
    std::string text = line(true);
    // A line that wraps cannot be redrawn in place.
    const auto columns = std::size_t(std::max(terminal_columns() - 1, 10));
    if (text.size() > columns) text.resize(columns);
    std::cerr << "\r" << text << "\033[K" << std::flush;
    drawn_ = true;
}

void Progress::tick() {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, kRedrawInterval, [this] { return finished_; })) {
        ++spinner_;
        if (drawn_) draw();
    }
}

}  // namespace edacrt::cli
