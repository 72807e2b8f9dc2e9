/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GuidedFilter>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<GuidedFilter>
    s_registeredGuidedFilter("guided", "guided filter, self-guided with the colour image (He et al. 2013; radius, eps)");

namespace
{
/** Box means over (2r+1)^2 windows of `fields` planes of w x h doubles (plane-major), wrapped by the border:
 *  separable running sums. */
void boxMean(std::vector<double>& data, int fields, int w, int h, int r, const ImageBorder& border)
{
    const double norm = 1.0 / double(2 * r + 1);
    std::vector<double> line(std::size_t(std::max(w, h)));
    for (int f = 0; f < fields; ++f)
    {
        double* plane = &data[std::size_t(f) * w * h];
        for (int y = 0; y < h; ++y)
        {
            double* row = plane + std::size_t(y) * w;
            double s = 0;
            for (int i = -r; i <= r; ++i)
                s += row[wrapIndex(i, w, border.s)];
            for (int x = 0; x < w; ++x)
            {
                line[std::size_t(x)] = s * norm;
                s += row[wrapIndex(x + r + 1, w, border.s)] - row[wrapIndex(x - r, w, border.s)];
            }
            std::copy(line.begin(), line.begin() + w, row);
        }
        for (int x = 0; x < w; ++x)
        {
            double s = 0;
            for (int i = -r; i <= r; ++i)
                s += plane[std::size_t(wrapIndex(i, h, border.t)) * w + x];
            for (int y = 0; y < h; ++y)
            {
                line[std::size_t(y)] = s * norm;
                s += plane[std::size_t(wrapIndex(y + r + 1, h, border.t)) * w + x] -
                     plane[std::size_t(wrapIndex(y - r, h, border.t)) * w + x];
            }
            for (int y = 0; y < h; ++y)
                plane[std::size_t(y) * w + x] = line[std::size_t(y)];
        }
    }
}
} // namespace

FilterImage GuidedFilter::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    if (input.empty()) return input;
    const int w = input.width(), h = input.height();
    const std::size_t n = std::size_t(w) * h;

    // The moments of the guide: I_0..2, then I_i I_j for (i, j) = 00 01 02 11 12 22.
    static const int kPair[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    std::vector<double> m(9 * n);
    for (std::size_t k = 0; k < n; ++k)
    {
        const float* p = &input.data()[k * 4];
        for (int c = 0; c < 3; ++c)
            m[c * n + k] = p[c];
        for (int q = 0; q < 6; ++q)
            m[(3 + q) * n + k] = double(p[kPair[q][0]]) * p[kPair[q][1]];
    }
    boxMean(m, 9, w, h, _radius, border);

    // Per window k and output channel c: a_c (3) and b_c: planes 4c .. 4c+3.
    std::vector<double> ab(12 * n);
    for (std::size_t k = 0; k < n; ++k)
    {
        const double mu[3] = {m[k], m[n + k], m[2 * n + k]};
        double s[3][3];
        for (int q = 0; q < 6; ++q)
        {
            const int i = kPair[q][0], j = kPair[q][1];
            s[i][j] = s[j][i] = m[(3 + q) * n + k] - mu[i] * mu[j];
        }
        // (Sigma + eps U)^-1 by cofactors (symmetric).
        double e[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                e[i][j] = s[i][j] + (i == j ? double(_eps) : 0.0);
        double inv[3][3];
        inv[0][0] = e[1][1] * e[2][2] - e[1][2] * e[2][1];
        inv[0][1] = e[0][2] * e[2][1] - e[0][1] * e[2][2];
        inv[0][2] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
        inv[1][1] = e[0][0] * e[2][2] - e[0][2] * e[2][0];
        inv[1][2] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
        inv[2][2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        inv[1][0] = inv[0][1], inv[2][0] = inv[0][2], inv[2][1] = inv[1][2];
        const double det = e[0][0] * inv[0][0] + e[0][1] * inv[1][0] + e[0][2] * inv[2][0];
        for (int c = 0; c < 3; ++c)
        {
            double a[3];
            for (int i = 0; i < 3; ++i)
                a[i] = (inv[i][0] * s[0][c] + inv[i][1] * s[1][c] + inv[i][2] * s[2][c]) / det;
            for (int i = 0; i < 3; ++i)
                ab[(4 * c + i) * n + k] = a[i];
            ab[(4 * c + 3) * n + k] = mu[c] - (a[0] * mu[0] + a[1] * mu[1] + a[2] * mu[2]);
        }
    }
    boxMean(ab, 12, w, h, _radius, border);

    FilterImage out(w, h);
    for (std::size_t k = 0; k < n; ++k)
    {
        const float* p = &input.data()[k * 4];
        float* o = &out.data()[k * 4];
        for (int c = 0; c < 3; ++c)
            o[c] = float(ab[(4 * c) * n + k] * p[0] + ab[(4 * c + 1) * n + k] * p[1] +
                         ab[(4 * c + 2) * n + k] * p[2] + ab[(4 * c + 3) * n + k]);
        o[3] = p[3];
    }
    return out;
}

std::vector<GpuFilterPass> GuidedFilter::gpuPasses() const
{
    checkParameters();
    const std::string r = std::to_string(_radius);
    std::vector<GpuFilterPass> passes;
    auto box = [&](int source, int axis, int input)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_guided_box.comp.glsl";
        p.defines = {
            {"LOA_SOURCE", std::to_string(source)}, {"LOA_AXIS", std::to_string(axis)}, {"LOA_RADIUS", r}};
        p.inputs = {input};
        p.radius = _radius;
        passes.push_back(p);
    };
    // 0..2: horizontal box sums of the moments (r, g, b, rr), (rg, rb, gg, gb), (bb); 3..5: vertical.
    for (int source = 1; source <= 3; ++source)
        box(source, 0, -1);
    for (int k = 0; k < 3; ++k)
        box(0, 1, k);
    // 6..8: (a_c, b_c) per output channel c.
    for (int c = 0; c < 3; ++c)
    {
        GpuFilterPass p;
        p.shader = "loa_filter_guided_coefficients.comp.glsl";
        p.defines = {{"LOA_CHANNEL", std::to_string(c)}};
        p.uniforms = {GpuUniform::scalar("loa_eps", _eps)};
        p.inputs = {3, 4, 5};
        p.radius = 0;
        passes.push_back(p);
    }
    // 9..11 horizontal, 12..14 vertical box means of the coefficients.
    for (int k = 0; k < 3; ++k)
        box(0, 0, 6 + k);
    for (int k = 0; k < 3; ++k)
        box(0, 1, 9 + k);
    // 15: the output.
    GpuFilterPass out;
    out.shader = "loa_filter_guided_output.comp.glsl";
    out.inputs = {-1, 12, 13, 14};
    out.radius = 0;
    passes.push_back(out);
    return passes;
}

std::vector<FilterParameter> GuidedFilter::parameters()
{
    FilterParameter radius;
    radius.name = "radius";
    radius.description = "window radius r, texels (box of (2r+1)^2)";
    radius.minimum = 0;
    radius.maximum = 32;
    radius.integer = true;
    radius.get = [this] { return double(_radius); };
    radius.set = [this](double v) { _radius = int(v); };

    FilterParameter eps;
    eps.name = "eps";
    eps.description = "regularization, in [0, 1]^2 units (0.01 = 0.1^2)";
    eps.minimum = 1e-6;
    eps.maximum = 1;
    eps.get = [this] { return double(_eps); };
    eps.set = [this](double v) { _eps = float(v); };
    return {radius, eps};
}

} // namespace osgLoA
