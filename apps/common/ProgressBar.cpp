#include "ProgressBar.h"

#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace loa
{

std::string durationText(double s)
{
    char b[32];
    if (s < 60)
        std::snprintf(b, sizeof b, "%.1f s", s);
    else if (s < 3600)
        std::snprintf(b, sizeof b, "%dm%02ds", int(s) / 60, int(s) % 60);
    else
        std::snprintf(b, sizeof b, "%dh%02dm", int(s) / 3600, int(s) / 60 % 60);
    return b;
}

ProgressBar::ProgressBar(std::string tool, std::size_t total, std::string unit, bool quiet)
    : _tool(std::move(tool)), _unit(std::move(unit)), _total(total), _tty(::isatty(2) == 1), _quiet(quiet),
      _start(clock::now())
{
}

void ProgressBar::say(const std::string& line)
{
    if (_tty && _drawn) std::cerr << "\r\033[K";
    std::cerr << _tool << ": " << line << "\n";
    if (_tty && _drawn) draw(clock::now());
}

void ProgressBar::message(const std::string& line)
{
    std::lock_guard<std::mutex> lock(_mutex);
    say(line);
}

void ProgressBar::start(const std::string& label)
{
    std::lock_guard<std::mutex> lock(_mutex);
    _current = label;
    if (_tty && !_quiet) draw(clock::now());
}

void ProgressBar::done(const std::string& line, bool asMessage)
{
    std::lock_guard<std::mutex> lock(_mutex);
    ++_done;
    if (!_tty)
    {
        if (!_quiet)
            std::cerr << _tool << ": [" << _done << "/" << _total << "] " << line << "\n";
        else if (asMessage)
            std::cerr << _tool << ": " << line << "\n";
        return;
    }
    if (asMessage) say(line);
    if (_quiet) return;
    const auto now = clock::now();
    if (_done == _total || asMessage || now - _lastDraw > std::chrono::milliseconds(100))
    {
        draw(now);
        _lastDraw = now;
    }
}

void ProgressBar::finish()
{
    std::lock_guard<std::mutex> lock(_mutex);
    if (_tty && _drawn) std::cerr << "\n";
    _drawn = false;
}

double ProgressBar::elapsed() const
{
    return std::chrono::duration<double>(clock::now() - _start).count();
}

void ProgressBar::draw(clock::time_point now)
{
    const double t = std::chrono::duration<double>(now - _start).count();
    const double rate = t > 0 ? double(_done) / t : 0.0;
    const int width = 30;
    const int filled = _total ? int(double(width) * double(_done) / double(_total)) : width;
    std::string bar(std::size_t(filled), '#');
    bar.resize(std::size_t(width), '.');
    char b[240];
    std::snprintf(b, sizeof b, "[%s] %zu/%zu %s, %.1f/s, ETA %s %s", bar.c_str(), _done, _total,
                  _unit.c_str(), rate,
                  rate > 0 && _done < _total ? durationText(double(_total - _done) / rate).c_str() : "?",
                  _done < _total ? _current.substr(0, 40).c_str() : "");
    std::cerr << "\r\033[K" << b << std::flush;
    _drawn = true;
}

} // namespace loa
