/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/PencilTextures>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace osgLoA
{

namespace
{
constexpr double kPi = 3.14159265358979323846;

/** A float in [0, 1) from the top 24 bits of one draw (the same on every platform). */
float uniform(std::mt19937& rng)
{
    return float(rng() >> 8) * (1.0f / 16777216.0f);
}

/** The toroidal canvas (1 paper, 0 black) and the running sum of its values. */
struct Canvas
{
    int size;
    std::vector<float> v;
    double sum;

    explicit Canvas(int s) : size(s), v(std::size_t(s) * std::size_t(s), 1.0f), sum(double(s) * double(s)) {}
    double mean() const { return sum / (double(size) * double(size)); }

    /** One stroke from (ax, ay) to (bx, by), width w, darkness a (pixel coordinates on the torus). */
    void stroke(double ax, double ay, double bx, double by, double w, double a)
    {
        const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
        const double reach = w * 0.5 + 0.5;
        int x0 = int(std::floor(std::min(ax, bx) - reach)), x1 = int(std::ceil(std::max(ax, bx) + reach));
        int y0 = int(std::floor(std::min(ay, by) - reach)), y1 = int(std::ceil(std::max(ay, by) + reach));
        x1 = std::min(x1, x0 + size - 1); // never visit a pixel twice through the wrap
        y1 = std::min(y1, y0 + size - 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
            {
                const double px = x + 0.5 - ax, py = y + 0.5 - ay;
                double t = len2 > 0.0 ? (px * dx + py * dy) / len2 : 0.0;
                t = std::clamp(t, 0.0, 1.0);
                const double ex = px - t * dx, ey = py - t * dy;
                const double coverage = std::clamp(reach - std::sqrt(ex * ex + ey * ey), 0.0, 1.0);
                if (coverage <= 0.0) continue;
                const double pressure = std::min(1.0, std::min(t, 1.0 - t) * 5.0);
                const int wx = ((x % size) + size) % size, wy = ((y % size) + size) % size;
                float& p = v[std::size_t(wy) * std::size_t(size) + std::size_t(wx)];
                const float old = p;
                p = float(double(p) * (1.0 - a * pressure * coverage));
                sum += double(p) - double(old);
            }
    }
};

void checkStack(const osg::Image& stack, int k, const char* what)
{
    if (stack.getPixelFormat() != GL_RGBA || stack.getDataType() != GL_UNSIGNED_BYTE || !stack.data())
        throw std::invalid_argument(std::string("PencilTextures::") + what +
                                    ": stack must be a GL_RGBA 8-bit image");
    if (k < 0 || k >= stack.r())
        throw std::invalid_argument(std::string("PencilTextures::") + what + ": k " + std::to_string(k) +
                                    " is outside [0, " + std::to_string(stack.r() - 1) + "]");
}
} // namespace

float PencilTextures::targetTone(int k, int levels)
{
    if (levels < 2)
        throw std::invalid_argument("PencilTextures::targetTone: levels " + std::to_string(levels) +
                                    " must be >= 2");
    if (k < 0 || k >= levels)
        throw std::invalid_argument("PencilTextures::targetTone: k " + std::to_string(k) +
                                    " is outside [0, " + std::to_string(levels - 1) + "]");
    return 0.25f + 0.75f * float(k) / float(levels - 1);
}

osg::ref_ptr<osg::Image> PencilTextures::create(int levels, int size, unsigned seed)
{
    if (levels < 2 || levels > 16)
        throw std::invalid_argument("PencilTextures::create: levels " + std::to_string(levels) +
                                    " is outside [2, 16]");
    if (size < 16 || size > 4096)
        throw std::invalid_argument("PencilTextures::create: size " + std::to_string(size) +
                                    " is outside [16, 4096]");
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(size, size, levels, GL_RGBA, GL_UNSIGNED_BYTE);
    image->setInternalTextureFormat(GL_RGBA8);

    std::mt19937 rng(seed);
    Canvas canvas(size);
    const double baseWidth = std::max(1.0, size / 200.0);
    const double hatch = kPi / 4.0, cross = -kPi / 4.0;
    unsigned strokeCount = 0;
    for (int k = levels - 1; k >= 0; --k)
    {
        const double target = targetTone(k, levels);
        const bool crossHatching = target < 0.7;
        while (canvas.mean() > target)
        {
            const double cx = uniform(rng) * size, cy = uniform(rng) * size;
            const double length = size * (0.15 + 0.25 * uniform(rng));
            const double jitter = (uniform(rng) - 0.5) * 0.2;
            const double width = baseWidth * (0.9 + 0.5 * uniform(rng));
            const double darkness = 0.3 + 0.3 * uniform(rng);
            const double angle = (crossHatching && (strokeCount % 2 == 1) ? cross : hatch) + jitter;
            const double hx = 0.5 * length * std::cos(angle), hy = 0.5 * length * std::sin(angle);
            canvas.stroke(cx - hx, cy - hy, cx + hx, cy + hy, width, darkness);
            ++strokeCount;
        }
        unsigned char* out = image->data(0, 0, k);
        for (std::size_t i = 0; i < canvas.v.size(); ++i)
        {
            const unsigned char g = (unsigned char)std::lround(std::clamp(canvas.v[i], 0.0f, 1.0f) * 255.0f);
            out[4 * i + 0] = g;
            out[4 * i + 1] = g;
            out[4 * i + 2] = g;
            out[4 * i + 3] = 255;
        }
    }
    image->dirty();
    return image;
}

osg::ref_ptr<osg::Image> PencilTextures::layer(const osg::Image& stack, int k)
{
    checkStack(stack, k, "layer");
    osg::ref_ptr<osg::Image> out = new osg::Image;
    out->allocateImage(stack.s(), stack.t(), 1, GL_RGBA, GL_UNSIGNED_BYTE);
    out->setInternalTextureFormat(GL_RGBA8);
    std::memcpy(out->data(), stack.data(0, 0, k), std::size_t(out->getImageSizeInBytes()));
    return out;
}

double PencilTextures::meanTone(const osg::Image& stack, int k)
{
    checkStack(stack, k, "meanTone");
    const unsigned char* p = stack.data(0, 0, k);
    const std::size_t n = std::size_t(stack.s()) * std::size_t(stack.t());
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        sum += double(p[4 * i]) + double(p[4 * i + 1]) + double(p[4 * i + 2]);
    return sum / (3.0 * 255.0 * double(n));
}

} // namespace osgLoA
