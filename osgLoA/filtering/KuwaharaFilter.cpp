/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/KuwaharaFilter>

#include <algorithm>
#include <vector>

namespace osgLoA
{

static FilterRegistry::Entry<KuwaharaFilter>
    s_registeredKuwaharaFilter("kuwahara",
                 "classic Kuwahara filter: mean of the least-variance of 4 square sectors (radius texels)");

namespace
{
int clampedRadius(int r)
{
    return std::clamp(r, KuwaharaFilter::minimumRadius(), KuwaharaFilter::maximumRadius());
}
} // namespace

FilterImage KuwaharaFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    const int w = input.width(), h = input.height();
    FilterImage out(w, h);
    if (input.empty()) return out;
    const int r = clampedRadius(_radius);
    // Summed-area table over the image padded by r texels on each side (padding read with the
    // wrap modes): S(X, Y) = sum of (R, G, B, R^2 + G^2 + B^2) over padded [0, X) x [0, Y).
    const int pw = w + 2 * r, ph = h + 2 * r;
    const std::size_t stride = std::size_t(pw) + 1;
    std::vector<double> sat(stride * (std::size_t(ph) + 1) * 4, 0.0);
    auto at = [&](int X, int Y) { return &sat[(std::size_t(Y) * stride + std::size_t(X)) * 4]; };
    for (int Y = 0; Y < ph; ++Y)
    {
        double row[4] = {0, 0, 0, 0};
        for (int X = 0; X < pw; ++X)
        {
            const osg::Vec4f c = input.fetch(X - r, Y - r, border);
            row[0] += c[0];
            row[1] += c[1];
            row[2] += c[2];
            row[3] += double(c[0]) * c[0] + double(c[1]) * c[1] + double(c[2]) * c[2];
            const double* above = at(X + 1, Y);
            double* s = at(X + 1, Y + 1);
            for (int k = 0; k < 4; ++k)
                s[k] = above[k] + row[k];
        }
    }
    const double n = double(r + 1) * double(r + 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const int X = x + r, Y = y + r; // the texel in padded coordinates
            // Sector k covers padded columns [x0, x0 + r] and rows [y0, y0 + r].
            const int x0s[4] = {X - r, X, X - r, X}, y0s[4] = {Y - r, Y - r, Y, Y};
            double best = 0.0, mean[3] = {0, 0, 0};
            for (int k = 0; k < 4; ++k)
            {
                const double *a = at(x0s[k], y0s[k]), *b = at(x0s[k] + r + 1, y0s[k]),
                             *c = at(x0s[k], y0s[k] + r + 1), *d = at(x0s[k] + r + 1, y0s[k] + r + 1);
                double m[4];
                for (int i = 0; i < 4; ++i)
                    m[i] = (d[i] - b[i] - c[i] + a[i]) / n;
                const double var = m[3] - (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
                if (k == 0 || var < best)
                {
                    best = var;
                    mean[0] = m[0];
                    mean[1] = m[1];
                    mean[2] = m[2];
                }
            }
            out.set(x, y, osg::Vec4f(float(mean[0]), float(mean[1]), float(mean[2]), input.get(x, y)[3]));
        }
    return out;
}

std::vector<GpuFilterPass> KuwaharaFilter::gpuPasses() const
{
    const int r = clampedRadius(_radius);
    std::vector<GpuFilterPass> passes(3);
    for (int stage = 0; stage < 3; ++stage)
    {
        GpuFilterPass& p = passes[std::size_t(stage)];
        p.shader = "loa_filter_kuwahara.comp.glsl";
        p.defines = {{"LOA_KUWAHARA_STAGE", std::to_string(stage)}, {"LOA_RADIUS", std::to_string(r)}};
        p.radius = r;
    }
    passes[0].inputs = {-1}; // row sums over [x-r, x]
    passes[1].inputs = {-1}; // row sums over [x, x+r]
    passes[2].inputs = {0, 1, -1};
    return passes;
}

std::vector<FilterParameter> KuwaharaFilter::parameters()
{
    FilterParameter r;
    r.name = "radius";
    r.description = "sector size r, texels: 4 sectors of (r+1)^2 texels";
    r.minimum = minimumRadius();
    r.maximum = maximumRadius();
    r.integer = true;
    r.get = [this] { return double(_radius); };
    r.set = [this](double v) { _radius = int(v); };
    return {r};
}

} // namespace osgLoA
