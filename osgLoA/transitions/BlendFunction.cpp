// BlendFunction: smoothstep fade-in and fade-out intervals with hard steps for zero widths.
#include <osgLoA/transitions/BlendFunction>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace osgLoA
{

float BlendFunction::smoothstep(float a, float b, float x)
{
    if (std::isnan(x)) return 0.0f;
    if (!(b > a)) return x >= a ? 1.0f : 0.0f;
    float t = (x - a) / (b - a);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

float BlendFunction::fadeIn(float interest) const
{
    return smoothstep(inBegin, inEnd, interest);
}

float BlendFunction::fadeOut(float interest) const
{
    if (std::isnan(interest)) return 0.0f;
    if (outBegin >= 1.0f && interest <= 1.0f) return 1.0f; // the top of the axis stays valid
    return 1.0f - smoothstep(outBegin, outEnd, interest);
}

bool BlendFunction::contributesThroughout(float lo, float hi, float margin) const
{
    if (std::isnan(lo) || std::isnan(hi) || hi < lo) return false;
    // The support (see mayContribute) is an interval: [inBegin or (inBegin, up to 1] or
    // up to outBegin / outEnd, open. Both ends of [lo, hi] must lie inside it, by the margin.
    // A hard fade-in at or below 0 lets every interest in (interests are never negative).
    const bool hardIn = !(inEnd > inBegin);
    if (!(hardIn && inBegin <= 0.0f) && !(lo > inBegin + margin)) return false;
    if (outBegin >= 1.0f) return true; // fadeOut is 1 for every interest <= 1
    const float end = outEnd > outBegin ? outEnd : outBegin;
    return hi < end - margin;
}

bool BlendFunction::mayContribute(float lo, float hi) const
{
    if (std::isnan(lo) || std::isnan(hi) || hi < lo) return false;
    // w > 0 exactly on the support S = {I : fadeIn(I) > 0 and fadeOut(I) > 0}, an interval:
    // fadeIn > 0 for I >= inBegin (hard) or I > inBegin (smooth); fadeOut > 0 for I <= 1 when
    // outBegin >= 1, else I < outBegin (hard) or I < outEnd (smooth). [lo, hi] meets S when the
    // intersection's lower end lies below its upper end (or equals it, both ends closed).
    const bool hardIn = !(inEnd > inBegin);
    const float low = std::max(lo, inBegin);
    const bool lowOpen = !hardIn && inBegin >= lo;
    float high;
    bool highOpen;
    if (outBegin >= 1.0f)
        high = std::min(hi, 1.0f), highOpen = false;
    else
    {
        const float end = outEnd > outBegin ? outEnd : outBegin;
        high = std::min(hi, end);
        highOpen = hi >= end;
    }
    return low < high || (low == high && !lowOpen && !highOpen);
}

std::string BlendFunction::validate() const
{
    std::ostringstream s;
    for (float v : {inBegin, inEnd, outBegin, outEnd})
        if (!std::isfinite(v)) return "a fade interval bound is not finite";
    if (inBegin < 0.0f || inBegin > 1.0f)
    {
        s << "fade-in begins at " << inBegin << ", outside the interest axis [0, 1]";
        return s.str();
    }
    if (inEnd < inBegin)
    {
        s << "fade-in interval [" << inBegin << ", " << inEnd << "] is inverted";
        return s.str();
    }
    if (outEnd < outBegin)
    {
        s << "fade-out interval [" << outBegin << ", " << outEnd << "] is inverted";
        return s.str();
    }
    if (outBegin < inEnd)
    {
        s << "fade-in interval [" << inBegin << ", " << inEnd << "] overlaps fade-out interval [" << outBegin
          << ", " << outEnd << "]";
        return s.str();
    }
    if (outBegin == inBegin && inEnd == inBegin && outEnd == outBegin && outBegin < 1.0f)
    {
        s << "validity range is empty: fade-in and fade-out are the same step at " << inBegin;
        return s.str();
    }
    return std::string();
}

} // namespace osgLoA
