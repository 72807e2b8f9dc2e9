// BlendFunction: smoothstep fade-in and fade-out intervals with hard steps for zero widths.
#include <osgLoA/transitions/BlendFunction>

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

bool BlendFunction::mayContribute(float lo, float hi) const
{
    if (std::isnan(lo) || std::isnan(hi) || hi < lo) return false;
    // w > 0 exactly on the set S = {I : fadeIn(I) > 0 and fadeOut(I) > 0}, an interval:
    // fadeIn > 0 for I > inBegin (I >= inBegin when hard); fadeOut > 0 for I < outEnd
    // (I < outBegin when hard; everywhere up to 1 when outBegin >= 1).
    const bool hardIn = !(inEnd > inBegin);
    const bool lowOk = hardIn ? hi >= inBegin : hi > inBegin;
    bool highOk;
    if (outBegin >= 1.0f)
        highOk = lo <= 1.0f || lo < outEnd;
    else if (!(outEnd > outBegin))
        highOk = lo < outBegin;
    else
        highOk = lo < outEnd;
    return lowOk && highOk;
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
