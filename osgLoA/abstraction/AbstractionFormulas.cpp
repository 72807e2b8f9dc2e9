/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionFormulas>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace osgLoA
{

namespace
{
float clamp01(float v)
{
    return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; // NaN -> 0
}

float mix(float a, float b, float t)
{
    return a * (1.0f - t) + b * t;
}
} // namespace

float AbstractionFormulas::celQuantize(float shade, int levels)
{
    if (levels < 1)
        throw std::invalid_argument("AbstractionFormulas::celQuantize: levels " + std::to_string(levels) +
                                    " must be >= 1");
    const float n = float(levels);
    const int k = std::min(int(std::floor(clamp01(shade) * n)), levels - 1);
    return float(k + 1) / n;
}

osg::Vec3f AbstractionFormulas::toon(const osg::Vec3f& P, float C, float E, float sigma)
{
    osg::Vec3f out;
    for (int i = 0; i < 3; ++i)
        out[i] = clamp01(P[i] * sigma * C * E);
    return out;
}

osg::Vec3f AbstractionFormulas::pencilSketch(const osg::Vec3f& P, float S, float gamma)
{
    const float s = std::pow(clamp01(S), gamma);
    osg::Vec3f out;
    for (int i = 0; i < 3; ++i)
        out[i] = clamp01(P[i] * s);
    return out;
}

osg::Vec3f AbstractionFormulas::overlay(const osg::Vec3f& c, float E, float edgeOpacity, float bleach)
{
    const float e = 1.0f - E;
    osg::Vec3f out;
    for (int i = 0; i < 3; ++i)
        out[i] = mix(mix(c[i], 1.0f, bleach), 0.0f, edgeOpacity * e);
    return out;
}

osg::Vec3f AbstractionFormulas::shadingShare(float C, float share)
{
    const float v = mix(1.0f, C, share);
    return osg::Vec3f(v, v, v);
}

FilterImage AbstractionFormulas::blendLevels(const std::vector<FilterImage>& levels,
                                             const FilterImage& lambda)
{
    if (levels.empty()) throw std::invalid_argument("AbstractionFormulas::blendLevels: levels is empty");
    const int w = lambda.width(), h = lambda.height();
    for (std::size_t i = 0; i < levels.size(); ++i)
        if (levels[i].width() != w || levels[i].height() != h)
            throw std::invalid_argument("AbstractionFormulas::blendLevels: levels[" + std::to_string(i) +
                                        "] is " + std::to_string(levels[i].width()) + "x" +
                                        std::to_string(levels[i].height()) + ", lambda " + std::to_string(w) +
                                        "x" + std::to_string(h));
    const int last = int(levels.size()) - 1;
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            float l = lambda.get(x, y)[0];
            l = l > 0.0f ? (l < float(last) ? l : float(last)) : 0.0f;
            const int i0 = int(std::floor(l));
            const int i1 = std::min(i0 + 1, last);
            const float f = l - float(i0);
            const float* a = levels[std::size_t(i0)].texel(x, y);
            const float* b = levels[std::size_t(i1)].texel(x, y);
            float* o = out.texel(x, y);
            for (int c = 0; c < 4; ++c)
                o[c] = mix(a[c], b[c], f);
        }
    return out;
}

FilterImage AbstractionFormulas::silhouettes(const FilterImage& ids)
{
    const int w = ids.width(), h = ids.height();
    FilterImage out(w, h, osg::Vec4f(1, 1, 1, 1));
    auto same = [&](const float* a, int x, int y)
    {
        const float* b = ids.texel(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1));
        return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float* c = ids.texel(x, y);
            if (!same(c, x - 1, y) || !same(c, x, y - 1)) out.set(x, y, osg::Vec4f(0, 0, 0, 1));
        }
    return out;
}

} // namespace osgLoA
