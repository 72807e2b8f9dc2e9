// Progress of the batch tools (loa-prefilter, loa-palette) on stderr: a redrawn bar (items
// done/total, rate, ETA, the current item) when stderr is a terminal, one line per item
// otherwise. Messages (skips, notes) always print on their own line. Thread-safe.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace loa
{

/** "12.3 s", "4m05s", "2h03m". */
std::string durationText(double seconds);

class ProgressBar
{
public:
    /** `unit` names the items in the bar ("images", "textures"); quiet draws no bar and prints
     *  no per-item lines, but still prints messages. */
    ProgressBar(std::string tool, std::size_t total, std::string unit, bool quiet = false);

    /** A line of its own, "tool: line", also when quiet. */
    void message(const std::string& line);
    /** The item being worked on (shown at the end of the bar). */
    void start(const std::string& label);
    /** One item done: "tool: [i/n] line" when stderr is not a terminal (unless quiet); on a
     *  terminal the bar is redrawn (at most every 100 ms). With asMessage the line is also a
     *  message (printed on a terminal and when quiet). */
    void done(const std::string& line, bool asMessage = false);
    /** Ends the bar's line. */
    void finish();
    double elapsed() const;

private:
    using clock = std::chrono::steady_clock;
    void draw(clock::time_point now);
    void say(const std::string& line);

    std::string _tool, _unit, _current;
    std::size_t _total, _done = 0;
    bool _tty, _quiet, _drawn = false;
    clock::time_point _start, _lastDraw;
    mutable std::mutex _mutex;
};

} // namespace loa
