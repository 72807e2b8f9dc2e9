// OITAutoSelection: the order-independent transparency method picked by measured cost.
#include <osgLoA/compositing/OITAutoSelection>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace osgLoA
{

OITAutoSelection::OITAutoSelection(std::vector<Method> candidates, int framesPerTrial, int holdFrames)
    : _candidates(std::move(candidates)), _framesPerTrial(framesPerTrial), _holdFrames(holdFrames)
{
    if (_candidates.empty()) throw std::invalid_argument("OITAutoSelection: no candidate method");
    if (_framesPerTrial < 1 || _holdFrames < 1)
        throw std::invalid_argument("OITAutoSelection: frames per trial (" + std::to_string(framesPerTrial) +
                                    ") and hold frames (" + std::to_string(holdFrames) +
                                    ") must be at least 1");
    _medians.assign(_candidates.size(), -1.0);
}

void OITAutoSelection::startTrial()
{
    _trial = true;
    _index = 0;
    _samples.clear();
    _drop = 1;
    _medians.assign(_candidates.size(), -1.0);
}

OrderIndependentTransparency::Method OITAutoSelection::record(double milliseconds, int width, int height)
{
    if (!(milliseconds >= 0.0))
        throw std::invalid_argument("OITAutoSelection: frame time " + std::to_string(milliseconds) + " ms");
    if (width != _width || height != _height)
    {
        const bool first = _width < 0;
        _width = width;
        _height = height;
        if (!first)
        {
            // Costs depend on the size: measure again from this frame on.
            // This frame (new storage) is dropped, and the next one too where the method changes.
            const Method was = current();
            startTrial();
            _drop = current() != was ? 2 : 1;
        }
    }
    if (!_trial)
    {
        if (++_held >= _holdFrames) startTrial();
        return current();
    }
    if (_drop > 0)
    {
        --_drop;
        return current();
    }
    _samples.push_back(milliseconds);
    if (int(_samples.size()) < _framesPerTrial) return current();
    std::nth_element(_samples.begin(), _samples.begin() + _samples.size() / 2, _samples.end());
    _medians[_index] = _samples[_samples.size() / 2];
    _samples.clear();
    if (_index + 1 < _candidates.size())
    {
        ++_index;
        _drop = 1;
        return current();
    }
    // The trial is over: the cheapest (the first listed on a tie).
    const std::size_t best =
        std::size_t(std::min_element(_medians.begin(), _medians.end()) - _medians.begin());
    _index = best;
    _trial = false;
    _chosen = true;
    _held = 0;
    return current();
}

} // namespace osgLoA
