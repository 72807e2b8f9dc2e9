// loa-viewer --script FILE: a sequence of osgGA events (keys, clicks, drags) replayed into the
// viewer's window, one step a frame, for demos and the tests. Points are window pixels from the
// top left (as in a screenshot). The format, one command a line ('#' starts a comment):
//   key K [ctrl] [shift]          K: a character, or tab, return, escape, delete, f1..f12
//   click X Y [left|middle|right]
//   drag X0 Y0 X1 Y1 [left|middle|right] [steps N]    (default: left, 8 steps)
//   move X Y
//   wait N                        N frames
//   screenshot FILE               the next frame, panels included
//   quit
#ifndef OSGLOA_APPS_EVENTSCRIPT_H
#define OSGLOA_APPS_EVENTSCRIPT_H 1

#include <osgGA/EventQueue>

#include <functional>
#include <string>
#include <vector>

namespace loa
{

class EventScript
{
public:
    /** Parses a script; throws std::runtime_error naming the line of the first error. */
    static EventScript read(const std::string& path);
    static EventScript parse(const std::string& text, const std::string& label);

    /** Queues the events of the next step into queue (the window's). screenshot is called for a
     *  screenshot command. Returns false when the script asks to quit or has ended. */
    bool step(osgGA::EventQueue& queue, int windowHeight,
              const std::function<void(const std::string&)>& screenshot);
    bool finished() const { return _next >= _steps.size() && _pending.empty(); }
    std::size_t size() const { return _steps.size(); }

private:
    struct Step
    {
        std::string command;
        std::vector<double> numbers;
        std::string text;
        int button = 1;
        unsigned mods = 0;
        int key = 0;
        unsigned steps = 8;
        int line = 0;
    };
    std::vector<Step> _steps;
    std::size_t _next = 0;
    std::vector<std::function<void(osgGA::EventQueue&, int)>> _pending; ///< one per frame
    bool _quit = false;
};

} // namespace loa

#endif
