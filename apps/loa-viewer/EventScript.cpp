// EventScript: scripted osgGA events for loa-viewer.
#include "EventScript.h"

#include <osgGA/GUIEventAdapter>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace loa
{

namespace
{
int keyCode(const std::string& name)
{
    typedef osgGA::GUIEventAdapter E;
    if (name.size() == 1) return static_cast<unsigned char>(name[0]);
    if (name == "tab") return E::KEY_Tab;
    if (name == "return" || name == "enter") return E::KEY_Return;
    if (name == "escape") return E::KEY_Escape;
    if (name == "delete") return E::KEY_Delete;
    if (name == "space") return ' ';
    if (name.size() >= 2 && name[0] == 'f')
    {
        const int n = std::atoi(name.c_str() + 1);
        if (n >= 1 && n <= 12) return E::KEY_F1 + n - 1;
    }
    return -1;
}

// osgGA::EventQueue takes X11's button numbers: 1 left, 2 middle, 3 right.
unsigned buttonNumber(int button)
{
    return unsigned(button);
}
} // namespace

EventScript EventScript::read(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error("--script: cannot read '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), path);
}

EventScript EventScript::parse(const std::string& text, const std::string& label)
{
    EventScript script;
    std::istringstream lines(text);
    int lineNo = 0;
    for (std::string line; std::getline(lines, line);)
    {
        ++lineNo;
        const std::size_t hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string word; words >> word;)
            w.push_back(word);
        if (w.empty()) continue;
        auto fail = [&](const std::string& why)
        { throw std::runtime_error(label + ":" + std::to_string(lineNo) + ": " + why); };
        auto number = [&](std::size_t i)
        {
            if (i >= w.size()) fail("'" + w[0] + "' needs more numbers");
            char* end = nullptr;
            const double v = std::strtod(w[i].c_str(), &end);
            if (!end || *end || !std::isfinite(v)) fail("'" + w[i] + "' is not a number");
            return v;
        };
        Step s;
        s.command = w[0];
        s.line = lineNo;
        std::size_t rest = 1;
        if (s.command == "key")
        {
            if (w.size() < 2) fail("key needs a key");
            s.key = keyCode(w[1]);
            if (s.key < 0) fail("unknown key '" + w[1] + "'");
            for (rest = 2; rest < w.size(); ++rest)
                if (w[rest] == "ctrl")
                    s.mods |= osgGA::GUIEventAdapter::MODKEY_CTRL;
                else if (w[rest] == "shift")
                    s.mods |= osgGA::GUIEventAdapter::MODKEY_SHIFT;
                else
                    fail("unknown key modifier '" + w[rest] + "'");
        }
        else if (s.command == "click" || s.command == "move" || s.command == "drag")
        {
            const std::size_t n = s.command == "drag" ? 4 : 2;
            for (std::size_t i = 1; i <= n; ++i)
                s.numbers.push_back(number(i));
            for (rest = n + 1; rest < w.size(); ++rest)
            {
                if (w[rest] == "left")
                    s.button = 1;
                else if (w[rest] == "middle")
                    s.button = 2;
                else if (w[rest] == "right")
                    s.button = 3;
                else if (w[rest] == "steps" && s.command == "drag")
                {
                    const double v = number(++rest);
                    if (v < 1 || v > 1000) fail("steps must be 1 to 1000");
                    s.steps = unsigned(v);
                }
                else
                    fail("unexpected '" + w[rest] + "'");
            }
        }
        else if (s.command == "wait")
        {
            const double v = number(1);
            if (v < 0 || v > 100000) fail("wait takes 0 to 100000 frames");
            s.numbers.push_back(v);
            if (w.size() > 2) fail("unexpected '" + w[2] + "'");
        }
        else if (s.command == "screenshot")
        {
            if (w.size() != 2) fail("screenshot needs one file name");
            s.text = w[1];
        }
        else if (s.command == "quit")
        {
            if (w.size() > 1) fail("unexpected '" + w[1] + "'");
        }
        else
            fail("unknown command '" + s.command + "'");
        script._steps.push_back(s);
    }
    return script;
}

bool EventScript::step(osgGA::EventQueue& queue, int windowHeight,
                       const std::function<void(const std::string&)>& screenshot)
{
    if (_quit) return false;
    // Events already split into frames (a drag's moves) go first.
    if (!_pending.empty())
    {
        auto f = _pending.front();
        _pending.erase(_pending.begin());
        f(queue, windowHeight);
        return true;
    }
    if (_next >= _steps.size()) return false;
    const Step s = _steps[_next++];
    // Script points are from the top left; the window's queue takes them so (X11 windows count
    // y downwards), one pixel's centre at +0.5.
    auto at = [](double v) { return float(v + 0.5); };
    if (s.command == "key")
    {
        const unsigned mods = s.mods;
        const int key = s.key;
        queue.getCurrentEventState()->setModKeyMask(mods);
        queue.keyPress(key);
        _pending.push_back(
            [mods, key](osgGA::EventQueue& q, int)
            {
                q.getCurrentEventState()->setModKeyMask(mods);
                q.keyRelease(key);
                q.getCurrentEventState()->setModKeyMask(0);
            });
    }
    else if (s.command == "move")
        queue.mouseMotion(at(s.numbers[0]), at(s.numbers[1]));
    else if (s.command == "click")
    {
        const float x = at(s.numbers[0]), y = at(s.numbers[1]);
        const unsigned b = buttonNumber(s.button);
        queue.mouseMotion(x, y);
        _pending.push_back([x, y, b](osgGA::EventQueue& q, int) { q.mouseButtonPress(x, y, b); });
        _pending.push_back([x, y, b](osgGA::EventQueue& q, int) { q.mouseButtonRelease(x, y, b); });
    }
    else if (s.command == "drag")
    {
        const float x0 = at(s.numbers[0]), y0 = at(s.numbers[1]), x1 = at(s.numbers[2]),
                    y1 = at(s.numbers[3]);
        const unsigned b = buttonNumber(s.button);
        queue.mouseMotion(x0, y0);
        _pending.push_back([x0, y0, b](osgGA::EventQueue& q, int) { q.mouseButtonPress(x0, y0, b); });
        for (unsigned i = 1; i <= s.steps; ++i)
        {
            const float t = float(i) / float(s.steps);
            const float x = x0 + (x1 - x0) * t, y = y0 + (y1 - y0) * t;
            _pending.push_back([x, y](osgGA::EventQueue& q, int) { q.mouseMotion(x, y); });
        }
        _pending.push_back([x1, y1, b](osgGA::EventQueue& q, int) { q.mouseButtonRelease(x1, y1, b); });
    }
    else if (s.command == "wait")
        for (unsigned i = 1; i < unsigned(s.numbers[0]); ++i)
            _pending.push_back([](osgGA::EventQueue&, int) {});
    else if (s.command == "screenshot")
        screenshot(s.text);
    else if (s.command == "quit")
    {
        _quit = true;
        return false;
    }
    return true;
}

} // namespace loa
