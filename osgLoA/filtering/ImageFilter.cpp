/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/ImageFilter>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

int ImageFilter::dependencyRadius() const
{
    const std::vector<GpuFilterPass> passes = gpuPasses();
    if (passes.empty()) return -1;
    // The radius of pass k's output as seen from the filter's input: its own radius plus the
    // largest radius of the passes it reads.
    std::vector<int> reach(passes.size(), 0);
    for (std::size_t k = 0; k < passes.size(); ++k)
    {
        if (passes[k].radius < 0) return -1;
        int upstream = 0;
        for (int in : passes[k].inputs)
            if (in >= 0) upstream = std::max(upstream, reach[std::size_t(in)]);
        reach[k] = passes[k].radius + upstream;
    }
    return reach.back();
}

namespace
{
std::string formatValue(const FilterParameter& p, double v)
{
    if (!p.choices.empty())
    {
        const long i = std::lround(v);
        if (i >= 0 && i < long(p.choices.size())) return p.choices[std::size_t(i)];
    }
    if (p.integer && std::fabs(v - std::round(v)) < 1e-9) return std::to_string(std::lround(v));
    // The shortest text that reads back as the same value: as a float when the value is one
    // (parameters are stored as floats: 0.1f prints as 0.1, not 0.100000001), else as a double
    // (ranges: 1e-06, not 9.9999999999999995e-07). Canonical strings stay readable and exact.
    char b[40];
    const bool isFloat = double(float(v)) == v;
    for (int digits = 6; digits <= 17; ++digits)
    {
        std::snprintf(b, sizeof b, "%.*g", digits, v);
        const double back = std::strtod(b, nullptr);
        if (isFloat ? float(back) == float(v) : back == v) break;
    }
    return b;
}

std::string rangeText(const FilterParameter& p)
{
    if (!p.choices.empty())
    {
        std::string s = "one of";
        for (const std::string& c : p.choices)
            s += " " + c;
        return s;
    }
    return (p.integer ? "an integer in [" : "a number in [") + formatValue(p, p.minimum) + ", " +
           formatValue(p, p.maximum) + "]";
}
} // namespace

void ImageFilter::setParameter(const std::string& name, double value)
{
    for (FilterParameter& p : parameters())
    {
        if (p.name != name) continue;
        if (!std::isfinite(value) || value < p.minimum || value > p.maximum ||
            (p.integer && std::fabs(value - std::round(value)) > 1e-9))
            throw std::invalid_argument(filterName() + ": parameter " + name + " = " + formatValue(p, value) +
                                        " is not " + rangeText(p));
        p.set(p.integer ? std::round(value) : value);
        return;
    }
    std::string known;
    for (const FilterParameter& p : const_cast<ImageFilter*>(this)->parameters())
        known += (known.empty() ? "" : ", ") + p.name;
    throw std::invalid_argument(filterName() + ": unknown parameter '" + name +
                                "' (known: " + (known.empty() ? "none" : known) + ")");
}

void ImageFilter::setParameter(const std::string& name, const std::string& value)
{
    for (FilterParameter& p : parameters())
    {
        if (p.name != name) continue;
        for (std::size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == value)
            {
                setParameter(name, double(i));
                return;
            }
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || end == value.c_str() || *end != '\0')
            throw std::invalid_argument(filterName() + ": parameter " + name + " = '" + value + "' is not " +
                                        rangeText(p));
        setParameter(name, v);
        return;
    }
    setParameter(name, 0.0); // throws the unknown-parameter error
}

void ImageFilter::checkParameters() const
{
    for (const FilterParameter& p : const_cast<ImageFilter*>(this)->parameters())
    {
        const double v = p.get();
        if (!std::isfinite(v) || v < p.minimum || v > p.maximum)
            throw std::invalid_argument(filterName() + ": parameter " + p.name + " = " + formatValue(p, v) +
                                        " is not " + rangeText(p));
    }
}

std::string ImageFilter::getParameterString() const
{
    std::ostringstream s;
    s << filterName();
    const std::vector<FilterParameter> ps = const_cast<ImageFilter*>(this)->parameters();
    for (std::size_t i = 0; i < ps.size(); ++i)
        s << (i == 0 ? ":" : ",") << ps[i].name << "=" << formatValue(ps[i], ps[i].get());
    return s.str();
}

} // namespace osgLoA
