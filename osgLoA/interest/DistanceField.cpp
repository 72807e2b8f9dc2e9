// DistanceField: grid sizing, seed rasterization, the exact EDT, jump flooding on the CPU and as
// OSG render-to-texture passes (shaders/loa_jfa_pass.{vert,frag}.glsl).
#include <osgLoA/interest/DistanceField>

#include "../compositing/RenderTarget.h"
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>

#include <osg/GL>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Notify>
#include <osg/Texture>
#include <osg/Uniform>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace osgLoA
{

namespace
{
const double kInf = std::numeric_limits<double>::infinity();
const float kInfF = std::numeric_limits<float>::infinity();

std::string num(double v)
{
    std::ostringstream o;
    o << v;
    return o.str();
}

// --- seed rasterization helpers; segmentDistance and the even-odd crossing are computed with
// the very expressions of RegionOfInterest.cpp, so rule (a) decides exactly as
// RegionOfInterest::distance() == 0 does.

double segmentDistance(const osg::Vec2d& p, const osg::Vec2d& a, const osg::Vec2d& b)
{
    const osg::Vec2d ab = b - a;
    const double len2 = ab.length2();
    double t = len2 > 0.0 ? ((p - a) * ab) / len2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    return (p - (a + ab * t)).length();
}

/** Liang-Barsky: does segment a-b meet the closed box [lo, hi]? */
bool segmentMeetsBox(const osg::Vec2d& a, const osg::Vec2d& b, const osg::Vec2d& lo, const osg::Vec2d& hi)
{
    double t0 = 0.0, t1 = 1.0;
    const double d[2] = {b.x() - a.x(), b.y() - a.y()};
    const double p0[2] = {a.x(), a.y()};
    const double l[2] = {lo.x(), lo.y()};
    const double h[2] = {hi.x(), hi.y()};
    for (int axis = 0; axis < 2; ++axis)
    {
        const double ps[2] = {-d[axis], d[axis]};
        const double qs[2] = {p0[axis] - l[axis], h[axis] - p0[axis]};
        for (int s = 0; s < 2; ++s)
        {
            const double pp = ps[s], q = qs[s];
            if (pp == 0.0)
            {
                if (q < 0.0) return false;
                continue;
            }
            const double r = q / pp;
            if (pp < 0.0)
            {
                if (r > t1) return false;
                t0 = std::max(t0, r);
            }
            else
            {
                if (r < t0) return false;
                t1 = std::min(t1, r);
            }
        }
    }
    return t0 <= t1;
}

struct TexelRange
{
    int i0, i1, j0, j1; // inclusive; empty when i0 > i1 or j0 > j1
};

/** The texels whose squares may meet the world box [lo, hi], one texel of margin against
 *  rounding, clamped to the grid. */
TexelRange texelsOf(const DistanceField::Grid& g, const osg::Vec2d& lo, const osg::Vec2d& hi)
{
    const osg::Vec2d a = g.worldToTexel(lo), b = g.worldToTexel(hi);
    auto clampi = [](double v, int n) { return int(std::max(-1.0, std::min(double(n), v))); };
    TexelRange r;
    r.i0 = std::max(0, clampi(std::floor(a.x()), g.width) - 1);
    r.i1 = std::min(g.width - 1, clampi(std::floor(b.x()), g.width) + 1);
    r.j0 = std::max(0, clampi(std::floor(a.y()), g.height) - 1);
    r.j1 = std::min(g.height - 1, clampi(std::floor(b.y()), g.height) + 1);
    return r;
}

void texelSquare(const DistanceField::Grid& g, int i, int j, osg::Vec2d& lo, osg::Vec2d& hi)
{
    lo.set(g.origin.x() + i * g.texelSize, g.origin.y() + j * g.texelSize);
    hi.set(g.origin.x() + (i + 1) * g.texelSize, g.origin.y() + (j + 1) * g.texelSize);
}

/** Seeds of one segment grown by radius: rule (a) (within radius) or (b) (meets the square). */
void rasterizeSegment(const DistanceField::Grid& g, const osg::Vec2d& a, const osg::Vec2d& b, double radius,
                      DistanceField::Seeds& seeds)
{
    const osg::Vec2d lo(std::min(a.x(), b.x()) - radius, std::min(a.y(), b.y()) - radius);
    const osg::Vec2d hi(std::max(a.x(), b.x()) + radius, std::max(a.y(), b.y()) + radius);
    const TexelRange r = texelsOf(g, lo, hi);
    osg::Vec2d sqLo, sqHi;
    for (int j = r.j0; j <= r.j1; ++j)
        for (int i = r.i0; i <= r.i1; ++i)
        {
            if (seeds.isSeed(i, j)) continue;
            texelSquare(g, i, j, sqLo, sqHi);
            if (segmentDistance(g.texelCenter(i, j), a, b) <= radius || segmentMeetsBox(a, b, sqLo, sqHi))
                seeds.set(i, j);
        }
}

void rasterizeCircle(const DistanceField::Grid& g, const osg::Vec2d& c, double radius,
                     DistanceField::Seeds& seeds)
{
    const TexelRange r = texelsOf(g, c - osg::Vec2d(radius, radius), c + osg::Vec2d(radius, radius));
    osg::Vec2d sqLo, sqHi;
    for (int j = r.j0; j <= r.j1; ++j)
        for (int i = r.i0; i <= r.i1; ++i)
        {
            if (seeds.isSeed(i, j)) continue;
            texelSquare(g, i, j, sqLo, sqHi);
            const bool inSquare =
                c.x() >= sqLo.x() && c.x() <= sqHi.x() && c.y() >= sqLo.y() && c.y() <= sqHi.y();
            if ((g.texelCenter(i, j) - c).length() <= radius || inSquare) seeds.set(i, j);
        }
}

/** Texel centres inside the ring by the even-odd rule of RegionOfInterest (insideRing), one row
 *  at a time: a centre is inside when an odd number of crossings lie to its right. */
void rasterizePolygonInside(const DistanceField::Grid& g, const RegionOfInterest::Vertices& v,
                            DistanceField::Seeds& seeds)
{
    osg::Vec2d lo(kInf, kInf), hi(-kInf, -kInf);
    for (const osg::Vec2d& p : v)
    {
        lo.set(std::min(lo.x(), p.x()), std::min(lo.y(), p.y()));
        hi.set(std::max(hi.x(), p.x()), std::max(hi.y(), p.y()));
    }
    const TexelRange r = texelsOf(g, lo, hi);
    std::vector<double> xs;
    for (int j = r.j0; j <= r.j1; ++j)
    {
        const double py = g.texelCenter(0, j).y();
        xs.clear();
        for (std::size_t i = 0, k = v.size() - 1; i < v.size(); k = i++)
            if ((v[i].y() > py) != (v[k].y() > py))
                xs.push_back(v[k].x() + (py - v[k].y()) * (v[i].x() - v[k].x()) / (v[i].y() - v[k].y()));
        if (xs.empty()) continue;
        std::sort(xs.begin(), xs.end());
        for (int i = r.i0; i <= r.i1; ++i)
        {
            const double px = g.texelCenter(i, j).x();
            // crossings with px < x: all from the first x > px on
            const std::size_t right = std::size_t(xs.end() - std::upper_bound(xs.begin(), xs.end(), px));
            if (right % 2 == 1) seeds.set(i, j);
        }
    }
}

bool finiteRegion(const RegionOfInterest& region)
{
    const osg::BoundingBoxd b = region.bound();
    return b.valid() && std::isfinite(b.xMin()) && std::isfinite(b.xMax()) && std::isfinite(b.yMin()) &&
           std::isfinite(b.yMax());
}

// --- exact EDT: the lower envelope of parabolas f(q) + (p - q)^2 over the sites q with finite
// f, in exact integer arithmetic (intersections are compared as fractions).

struct Envelope
{
    std::vector<int> v;             // parabola sites
    std::vector<std::int64_t> zNum; // boundary k: zNum[k] / zDen[k]; k = 0 is -inf
    std::vector<std::int64_t> zDen;
    std::vector<unsigned char> zInf; // 1: -inf (k = 0) or +inf (one past the last)
};

/** f: n values, negative = no site. Writes d[p] = min_q f(q) + (p-q)^2 (or -1 without any
 *  site) and arg[p] = the minimizing q. */
void envelope1D(const std::int64_t* f, int n, std::int64_t* d, int* arg, Envelope& e)
{
    e.v.resize(std::size_t(n));
    e.zNum.resize(std::size_t(n) + 1);
    e.zDen.resize(std::size_t(n) + 1);
    e.zInf.resize(std::size_t(n) + 1);
    int k = -1;
    for (int q = 0; q < n; ++q)
    {
        if (f[q] < 0) continue;
        if (k < 0)
        {
            k = 0;
            e.v[0] = q;
            e.zInf[0] = 1;
            e.zInf[1] = 1;
            continue;
        }
        for (;;)
        {
            const int r = e.v[std::size_t(k)];
            // s = ((f[q] + q^2) - (f[r] + r^2)) / (2q - 2r), q > r
            const std::int64_t num = (f[q] + std::int64_t(q) * q) - (f[r] + std::int64_t(r) * r);
            const std::int64_t den = 2 * std::int64_t(q - r);
            // s <= z[k]? z[0] is -inf: never.
            const bool below = k > 0 && num * e.zDen[std::size_t(k)] <= e.zNum[std::size_t(k)] * den;
            if (below)
            {
                --k;
                continue;
            }
            ++k;
            e.v[std::size_t(k)] = q;
            e.zNum[std::size_t(k)] = num;
            e.zDen[std::size_t(k)] = den;
            e.zInf[std::size_t(k)] = 0;
            e.zInf[std::size_t(k) + 1] = 1;
            break;
        }
    }
    if (k < 0)
    {
        for (int p = 0; p < n; ++p)
        {
            d[p] = -1;
            arg[p] = -1;
        }
        return;
    }
    k = 0;
    for (int p = 0; p < n; ++p)
    {
        // advance while z[k+1] < p (z[k+1] finite)
        while (!e.zInf[std::size_t(k) + 1] &&
               e.zNum[std::size_t(k) + 1] < std::int64_t(p) * e.zDen[std::size_t(k) + 1])
            ++k;
        const int r = e.v[std::size_t(k)];
        d[p] = std::int64_t(p - r) * (p - r) + f[r];
        arg[p] = r;
    }
}

std::string joinAnd(const std::vector<std::string>& parts)
{
    std::string s;
    for (std::size_t i = 0; i < parts.size(); ++i)
        s += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
    return s;
}

} // namespace

// ------------------------------------------------------------------------------------------
// Grid

DistanceField::Grid::Grid(const osg::Vec2d& o, double t, int w, int h)
    : origin(o), texelSize(t), width(w), height(h)
{
}

bool DistanceField::Grid::valid() const
{
    return width >= 1 && height >= 1 && width <= kMaxResolution && height <= kMaxResolution &&
           std::isfinite(texelSize) && texelSize > 0.0 && std::isfinite(origin.x()) &&
           std::isfinite(origin.y());
}

osg::Vec2d DistanceField::Grid::texelCenter(int i, int j) const
{
    return osg::Vec2d(origin.x() + (i + 0.5) * texelSize, origin.y() + (j + 0.5) * texelSize);
}

osg::Vec2d DistanceField::Grid::worldToTexel(const osg::Vec2d& world) const
{
    return osg::Vec2d((world.x() - origin.x()) / texelSize, (world.y() - origin.y()) / texelSize);
}

osg::Vec2d DistanceField::Grid::worldToTexCoord(const osg::Vec2d& world) const
{
    const osg::Vec2d t = worldToTexel(world);
    return osg::Vec2d(t.x() / width, t.y() / height);
}

osg::Vec4f DistanceField::Grid::textureTransform() const
{
    const double sx = 1.0 / (texelSize * width), sy = 1.0 / (texelSize * height);
    return osg::Vec4f(float(sx), float(sy), float(-origin.x() * sx), float(-origin.y() * sy));
}

osg::BoundingBoxd DistanceField::Grid::bound() const
{
    return osg::BoundingBoxd(origin.x(), origin.y(), 0.0, origin.x() + width * texelSize,
                             origin.y() + height * texelSize, 0.0);
}

bool DistanceField::Grid::operator==(const Grid& o) const
{
    return origin == o.origin && texelSize == o.texelSize && width == o.width && height == o.height;
}

DistanceField::Grid DistanceField::Grid::cover(const osg::BoundingBoxd& area, double texelSize,
                                               int maxResolution)
{
    if (!area.valid()) throw std::invalid_argument("the area a distance field must cover is empty");
    if (!std::isfinite(area.xMin()) || !std::isfinite(area.xMax()) || !std::isfinite(area.yMin()) ||
        !std::isfinite(area.yMax()))
        throw std::invalid_argument("the area a distance field must cover is not finite");
    if (!std::isfinite(texelSize) || texelSize <= 0.0)
        throw std::invalid_argument("distance field texel size " + num(texelSize) +
                                    " must be finite and positive");
    if (maxResolution < 1 || maxResolution > kMaxResolution)
        throw std::invalid_argument("distance field maximum resolution " + std::to_string(maxResolution) +
                                    " is outside 1.." + std::to_string(kMaxResolution));
    const double ex = area.xMax() - area.xMin(), ey = area.yMax() - area.yMin();
    // Whole numbers of texels within 1e-9 are not rounded up (100 / 0.1 is 1000, not 1001).
    auto texels = [](double extent, double t) { return std::max(1.0, std::ceil(extent / t - 1e-9)); };
    double t = texelSize;
    double w = texels(ex, t), h = texels(ey, t);
    if (std::max(w, h) > maxResolution)
    {
        t = std::max(ex, ey) / maxResolution;
        w = texels(ex, t);
        h = texels(ey, t);
        while (std::max(w, h) > maxResolution) // rounding
        {
            t = std::nextafter(t, kInf);
            w = texels(ex, t);
            h = texels(ey, t);
        }
    }
    return Grid(osg::Vec2d(area.xMin(), area.yMin()), t, int(w), int(h));
}

osg::BoundingBoxd DistanceField::Grid::clipToRange(const osg::BoundingBoxd& area, const osg::Vec2d& centre,
                                                   double range)
{
    if (!std::isfinite(range) || range <= 0.0)
        throw std::invalid_argument("distance field range " + num(range) + " must be finite and positive");
    osg::BoundingBoxd b;
    if (!area.valid()) return b;
    const double x0 = std::max(area.xMin(), centre.x() - range),
                 x1 = std::min(area.xMax(), centre.x() + range);
    const double y0 = std::max(area.yMin(), centre.y() - range),
                 y1 = std::min(area.yMax(), centre.y() + range);
    if (x0 > x1 || y0 > y1) return b;
    return osg::BoundingBoxd(x0, y0, area.zMin(), x1, y1, area.zMax());
}

// ------------------------------------------------------------------------------------------
// Seeds and maps

DistanceField::Seeds::Seeds(int w, int h) : width(w), height(h)
{
    if (w < 0 || h < 0 || w > kMaxResolution || h > kMaxResolution)
        throw std::invalid_argument("seed image " + std::to_string(w) + "x" + std::to_string(h) +
                                    " is outside 0..." + std::to_string(kMaxResolution) + " per side");
    mask.assign(std::size_t(w) * std::size_t(h), 0);
}

std::size_t DistanceField::Seeds::count() const
{
    return std::size_t(std::count_if(mask.begin(), mask.end(), [](unsigned char m) { return m != 0; }));
}

DistanceField::Seeds DistanceField::rasterize(const Grid& grid, const RegionList& regions)
{
    if (!grid.valid())
        throw std::invalid_argument("cannot rasterize regions of interest into an invalid grid");
    Seeds seeds(grid.width, grid.height);
    for (const osg::ref_ptr<RegionOfInterest>& region : regions)
    {
        if (!region.valid() || !finiteRegion(*region)) continue;
        const RegionOfInterest::Vertices& v = region->getVertices();
        const double radius = region->getRadius();
        switch (region->getShape())
        {
        case RegionOfInterest::CIRCLES:
            for (const osg::Vec2d& c : v)
                rasterizeCircle(grid, c, radius, seeds);
            break;
        case RegionOfInterest::POLYLINE:
            for (std::size_t i = 0; i + 1 < v.size(); ++i)
                rasterizeSegment(grid, v[i], v[i + 1], radius, seeds);
            break;
        case RegionOfInterest::POLYGON:
            rasterizePolygonInside(grid, v, seeds);
            for (std::size_t i = 0; i < v.size(); ++i)
                rasterizeSegment(grid, v[i], v[(i + 1) % v.size()], radius, seeds);
            break;
        }
    }
    return seeds;
}

DistanceField::Map DistanceField::computeExact(const Seeds& seeds)
{
    const int w = seeds.width, h = seeds.height;
    Map m;
    m.width = w;
    m.height = h;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    m.distance.assign(n, kInfF);
    m.nearest.assign(n, Map::kNoSeed);
    if (n == 0) return m;

    Envelope env;
    // Pass 1, columns: squared distance to the nearest seed in the same column, and its row.
    std::vector<std::int64_t> colD(n);
    std::vector<int> colArg(n);
    {
        std::vector<std::int64_t> f(static_cast<std::size_t>(h)), d(static_cast<std::size_t>(h));
        std::vector<int> arg(static_cast<std::size_t>(h));
        for (int x = 0; x < w; ++x)
        {
            for (int y = 0; y < h; ++y)
                f[std::size_t(y)] = seeds.isSeed(x, y) ? 0 : -1;
            envelope1D(f.data(), h, d.data(), arg.data(), env);
            for (int y = 0; y < h; ++y)
            {
                colD[std::size_t(y) * std::size_t(w) + std::size_t(x)] = d[std::size_t(y)];
                colArg[std::size_t(y) * std::size_t(w) + std::size_t(x)] = arg[std::size_t(y)];
            }
        }
    }
    // Pass 2, rows: the envelope over the column results.
    std::vector<std::int64_t> d(static_cast<std::size_t>(w));
    std::vector<int> arg(static_cast<std::size_t>(w));
    for (int y = 0; y < h; ++y)
    {
        const std::size_t row = std::size_t(y) * std::size_t(w);
        envelope1D(&colD[row], w, d.data(), arg.data(), env);
        for (int x = 0; x < w; ++x)
        {
            if (d[std::size_t(x)] < 0) continue;
            m.distance[row + std::size_t(x)] = float(std::sqrt(double(d[std::size_t(x)])));
            const int sx = arg[std::size_t(x)];
            m.nearest[row + std::size_t(x)] = Map::pack(sx, colArg[row + std::size_t(sx)]);
        }
    }
    return m;
}

std::vector<int> DistanceField::steps(Variant variant, int width, int height, int maxDistanceTexels)
{
    const int n = std::max(width, height);
    int k = 0;
    if (n >= 2)
    {
        k = 1;
        while (k * 2 < n)
            k *= 2;
    }
    if (maxDistanceTexels > 0)
    {
        int kr = 1;
        while (kr < maxDistanceTexels && kr < kMaxResolution)
            kr *= 2;
        k = std::min(k, kr);
    }
    std::vector<int> out;
    if (variant == ONE_PLUS_JFA) out.push_back(1);
    for (int s = k; s >= 1; s /= 2)
        out.push_back(s);
    if (variant == JFA_PLUS_2)
    {
        out.push_back(2);
        out.push_back(1);
    }
    return out;
}

DistanceField::Map DistanceField::computeJFA(const Seeds& seeds, Variant variant, int maxDistanceTexels)
{
    const int w = seeds.width, h = seeds.height;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    std::vector<std::uint32_t> cur(n, Map::kNoSeed), next(n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (seeds.isSeed(x, y)) cur[std::size_t(y) * std::size_t(w) + std::size_t(x)] = Map::pack(x, y);

    auto squared = [](std::uint32_t s, int x, int y)
    {
        const int ex = Map::unpackX(s) - x, ey = Map::unpackY(s) - y;
        return ex * ex + ey * ey;
    };
    for (int k : steps(variant, w, h, maxDistanceTexels))
    {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
            {
                std::uint32_t best = Map::kNoSeed;
                int bestD = 0x7FFFFFFF;
                for (int dy = -1; dy <= 1; ++dy)
                {
                    const int qy = y + dy * k;
                    if (qy < 0 || qy >= h) continue;
                    for (int dx = -1; dx <= 1; ++dx)
                    {
                        const int qx = x + dx * k;
                        if (qx < 0 || qx >= w) continue;
                        const std::uint32_t s = cur[std::size_t(qy) * std::size_t(w) + std::size_t(qx)];
                        if (s == Map::kNoSeed) continue;
                        const int d2 = squared(s, x, y);
                        if (d2 < bestD)
                        {
                            bestD = d2;
                            best = s;
                        }
                    }
                }
                next[std::size_t(y) * std::size_t(w) + std::size_t(x)] = best;
            }
        cur.swap(next);
    }
    Map m;
    m.width = w;
    m.height = h;
    m.distance.resize(n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            m.distance[i] = cur[i] == Map::kNoSeed ? kInfF : std::sqrt(float(squared(cur[i], x, y)));
        }
    m.nearest = std::move(cur);
    return m;
}

DistanceField::Error DistanceField::compare(const Map& approx, const Map& reference, double maxDistance)
{
    if (approx.width != reference.width || approx.height != reference.height ||
        approx.distance.size() != reference.distance.size())
        throw std::invalid_argument("distance maps of different sizes cannot be compared");
    Error e;
    double sum = 0.0;
    std::size_t reached = 0;
    for (std::size_t i = 0; i < reference.distance.size(); ++i)
    {
        const double r = reference.distance[i];
        if (!std::isfinite(r) || r > maxDistance) continue;
        ++e.texels;
        const double a = approx.distance[i];
        if (!std::isfinite(a))
        {
            ++e.unreached;
            ++e.overOne;
            ++e.wrong;
            continue;
        }
        const double err = std::fabs(a - r);
        ++reached;
        sum += err;
        e.maxAbs = std::max(e.maxAbs, err);
        if (err > 1e-4) ++e.wrong;
        if (err > 1.0) ++e.overOne;
    }
    e.meanAbs = reached ? sum / double(reached) : 0.0;
    return e;
}

const char* DistanceField::toString(Variant variant)
{
    switch (variant)
    {
    case JFA:
        return "JFA";
    case ONE_PLUS_JFA:
        return "1+JFA";
    case JFA_PLUS_2:
        return "JFA+2";
    }
    return "JFA";
}

void DistanceField::checkCapabilities(const GLCapabilities& caps, int width, int height)
{
    std::vector<std::string> missing;
    if (!caps.versionAtLeast(3, 3))
        missing.push_back("OpenGL 3.3 with GLSL 3.30 (texelFetch, integer outputs)");
    if (!caps.compatibilityProfile)
        missing.push_back("a compatibility profile (the passes draw with gl_Vertex)");
    if (!caps.versionAtLeast(3, 0) && !caps.hasExtension("GL_EXT_texture_integer"))
        missing.push_back("integer textures as render targets (RGBA32UI; GL_EXT_texture_integer)");
    if (!caps.versionAtLeast(3, 0) &&
        !(caps.hasExtension("GL_ARB_texture_float") && caps.hasExtension("GL_ARB_color_buffer_float")))
        missing.push_back("float render targets (R32F; GL_ARB_texture_float, GL_ARB_color_buffer_float)");
    if (caps.maxTextureSize < std::max(width, height))
        missing.push_back("textures of " + std::to_string(std::max(width, height)) +
                          " texels a side (GL_MAX_TEXTURE_SIZE is " + std::to_string(caps.maxTextureSize) +
                          ")");
    if (!missing.empty())
        throw DistanceFieldError("the GPU distance field needs " + joinAnd(missing) +
                                 ", which the context (" + caps.summary() + ") lacks.");
}

// ------------------------------------------------------------------------------------------
// The node

/** Counts pass draws; on the last pass also counts a computation and reads back. */
struct DistanceFieldDrawCallback : public osg::Camera::DrawCallback
{
    DistanceFieldDrawCallback(DistanceField* field, bool last) : _field(field), _last(last) {}
    void operator()(osg::RenderInfo& renderInfo) const override
    {
        if (_field) _field->onPassDrawn(renderInfo, _last);
    }
    DistanceField* _field; // the node owns the cameras that own this callback
    bool _last;
};

DistanceField::DistanceField()
{
    setCullingActive(false);
    setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() + 1);
    _distanceTexture = new osg::Texture2D;
    _distanceTexture->setName("loa_jfaDistance");
    _distanceTexture->setInternalFormat(GL_R32F);
    _distanceTexture->setSourceFormat(GL_RED);
    _distanceTexture->setSourceType(GL_FLOAT);
    _distanceTexture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR);
    _distanceTexture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    _distanceTexture->setWrap(osg::Texture::WRAP_S, osg::Texture::CLAMP_TO_EDGE);
    _distanceTexture->setWrap(osg::Texture::WRAP_T, osg::Texture::CLAMP_TO_EDGE);
    _distanceTexture->setResizeNonPowerOfTwoHint(false);
    _distanceTexture->setDataVariance(osg::Object::DYNAMIC);
    _scaleUniform = new osg::Uniform("loa_jfaDistanceScale", 1.0f);
}

DistanceField::DistanceField(const DistanceField& other, const osg::CopyOp& copyop)
    : osg::Group(other, copyop), _grid(other._grid), _regions(other._regions), _variant(other._variant),
      _maxDistance(other._maxDistance), _units(other._units), _method(other._method),
      _readBack(other._readBack), _seeds(other._seeds), _seedsFromRegions(other._seedsFromRegions)
{
    // The copied children are the other node's passes: build our own.
    removeChildren(0, getNumChildren());
    setCullingActive(false);
    setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() + 1);
    _distanceTexture = new osg::Texture2D(*other._distanceTexture, osg::CopyOp::SHALLOW_COPY);
    _scaleUniform = new osg::Uniform("loa_jfaDistanceScale", 1.0f);
    _rasterizePending = _seedsFromRegions;
    rebuildPasses();
}

DistanceField::~DistanceField()
{
    // Callbacks point back here; cameras may outlive the node in render caches.
    for (auto& c : _cameras)
    {
        c->setInitialDrawCallback(nullptr);
        c->setPostDrawCallback(nullptr);
    }
}

void DistanceField::setGrid(const Grid& grid)
{
    if (grid.width > kMaxResolution || grid.height > kMaxResolution)
        throw std::invalid_argument("distance field grid " + std::to_string(grid.width) + "x" +
                                    std::to_string(grid.height) + " exceeds " +
                                    std::to_string(kMaxResolution) + " texels a side");
    if (grid == _grid && !_cameras.empty()) return;
    // Same size and steps (a grid that moved with the camera): keep the passes and textures.
    const bool keepPasses = !_cameras.empty() && grid.valid() && grid.width == _grid.width &&
                            grid.height == _grid.height && stepsFor(grid) == _passSteps;
    _grid = grid;
    if (_seedsFromRegions)
        _rasterizePending = true;
    else
    {
        _seeds = _grid.valid() ? Seeds(_grid.width, _grid.height) : Seeds();
        ++_seedRevision;
    }
    if (keepPasses)
    {
        _scaleUniform->set(_units == WORLD ? float(_grid.texelSize) : 1.0f);
        ++_computeRevision;
    }
    else
        rebuildPasses();
}

std::vector<int> DistanceField::stepsFor(const Grid& grid) const
{
    if (!grid.valid()) return std::vector<int>();
    const double maxTexels = _maxDistance > 0.0 ? std::ceil(_maxDistance / grid.texelSize) : 0.0;
    return steps(_variant, grid.width, grid.height, int(std::min(maxTexels, double(kMaxResolution))));
}

void DistanceField::setRegions(const RegionList& regions)
{
    _regions = regions;
    dirtyRegions();
}

void DistanceField::addRegion(RegionOfInterest* region)
{
    _regions.push_back(region);
    dirtyRegions();
}

void DistanceField::dirtyRegions()
{
    _seedsFromRegions = true;
    _rasterizePending = true;
}

void DistanceField::setSeeds(const Seeds& seeds)
{
    if (seeds.width != _grid.width || seeds.height != _grid.height ||
        seeds.mask.size() != std::size_t(seeds.width) * std::size_t(seeds.height))
        throw std::invalid_argument("seed image " + std::to_string(seeds.width) + "x" +
                                    std::to_string(seeds.height) +
                                    " does not match the distance field grid " + std::to_string(_grid.width) +
                                    "x" + std::to_string(_grid.height));
    _seeds = seeds;
    _seedsFromRegions = false;
    _rasterizePending = false;
    ++_seedRevision;
}

void DistanceField::setVariant(Variant variant)
{
    if (variant == _variant) return;
    _variant = variant;
    rebuildPasses();
}

void DistanceField::setMaxDistance(double worldUnits)
{
    if (!std::isfinite(worldUnits) || worldUnits < 0.0)
        throw std::invalid_argument("distance field maximum distance " + num(worldUnits) +
                                    " must be finite and not negative");
    if (worldUnits == _maxDistance) return;
    _maxDistance = worldUnits;
    rebuildPasses();
}

void DistanceField::setMethod(Method method)
{
    if (method == _method) return;
    _method = method;
    rebuildPasses();
}

DistanceField::Method DistanceField::preferredMethod(const GLCapabilities& caps)
{
    return caps.isSoftwareRenderer() ? CPU_EXACT : GPU_JUMP_FLOODING;
}

void DistanceField::setUnits(Units units)
{
    if (units == _units) return;
    _units = units;
    _scaleUniform->set(_units == WORLD ? float(_grid.texelSize) : 1.0f);
    ++_computeRevision;
}

osg::Texture2D* DistanceField::getNearestSeedTexture()
{
    if (_cameras.empty()) return nullptr;
    if (_passSteps.empty()) return _seedTexture.get();
    return _pingPong[(_passSteps.size() - 1) % 2].get();
}

namespace
{
/** A packed seed texture: RGBA32UI, texel (i, j) holds grid texels 4i..4i+3 of row j. */
osg::ref_ptr<osg::Texture2D> packedTexture(int packs, int h)
{
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D;
    t->setTextureSize(packs, h);
    t->setInternalFormat(GL_RGBA32UI_EXT);
    t->setSourceFormat(GL_RGBA_INTEGER_EXT);
    t->setSourceType(GL_UNSIGNED_INT);
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::CLAMP_TO_EDGE);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::CLAMP_TO_EDGE);
    t->setResizeNonPowerOfTwoHint(false);
    t->setUseHardwareMipMapGeneration(false);
    t->setDataVariance(osg::Object::DYNAMIC);
    return t;
}

/** One triangle covering the viewport, in clip space (loa_jfa_pass.vert.glsl passes it on). */
osg::ref_ptr<osg::Geode> fullScreenTriangle()
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(detail::createFullScreenTriangle().get());
    geode->setCullingActive(false);
    return geode;
}

int packsOf(int width)
{
    return (width + 3) / 4;
}
} // namespace

void DistanceField::rebuildPasses()
{
    for (auto& c : _cameras)
    {
        c->setInitialDrawCallback(nullptr);
        c->setPostDrawCallback(nullptr);
    }
    removeChildren(0, getNumChildren());
    _cameras.clear();
    _passSteps.clear();
    _scaleUniform->set(_units == WORLD ? float(_grid.texelSize) : 1.0f);
    ++_computeRevision;
    _uploadedRevision = 0;
    if (!_grid.valid())
    {
        _seedImage = nullptr;
        _seedTexture = nullptr;
        _pingPong[0] = _pingPong[1] = nullptr;
        return;
    }
    const int w = _grid.width, h = _grid.height, packs = packsOf(w);
    if (_method == CPU_EXACT)
    {
        _seedImage = nullptr;
        _seedTexture = nullptr;
        _pingPong[0] = _pingPong[1] = nullptr;
        _distanceImage = new osg::Image;
        _distanceImage->allocateImage(w, h, 1, GL_RED, GL_FLOAT);
        _distanceImage->setInternalTextureFormat(GL_R32F);
        _distanceImage->setDataVariance(osg::Object::DYNAMIC);
        std::fill_n(reinterpret_cast<float*>(_distanceImage->data()), std::size_t(w) * std::size_t(h), kInfF);
        _distanceTexture->setImage(_distanceImage.get());
        _distanceTexture->setUnRefImageDataAfterApply(false);
        _distanceTexture->dirtyTextureObject();
        return;
    }
    if (_distanceTexture->getImage())
    {
        _distanceTexture->setImage(nullptr);
        _distanceImage = nullptr;
        _distanceTexture->setTextureSize(0, 0); // forces the resize below
    }
    _passSteps = stepsFor(_grid);

    _seedImage = new osg::Image;
    _seedImage->allocateImage(packs, h, 1, GL_RGBA_INTEGER_EXT, GL_UNSIGNED_INT);
    _seedImage->setInternalTextureFormat(GL_RGBA32UI_EXT);
    _seedImage->setDataVariance(osg::Object::DYNAMIC);
    _seedTexture = packedTexture(packs, h);
    _seedTexture->setImage(_seedImage.get());
    _seedTexture->setUnRefImageDataAfterApply(false);
    _pingPong[0] = packedTexture(packs, h);
    _pingPong[1] = packedTexture(packs, h);
    if (_distanceTexture->getTextureWidth() != w || _distanceTexture->getTextureHeight() != h)
    {
        _distanceTexture->setTextureSize(w, h);
        _distanceTexture->dirtyTextureObject();
    }

    if (!_stepProgram.valid())
        _stepProgram =
            ShaderLibrary::createProgram("jfa step", {"loa_jfa_pass.vert.glsl", "loa_jfa_step.frag.glsl"});
    if (!_distanceProgram.valid())
        _distanceProgram = ShaderLibrary::createProgram(
            "jfa distance", {"loa_jfa_pass.vert.glsl", "loa_jfa_distance.frag.glsl"});
    osg::ref_ptr<osg::Geode> triangle = fullScreenTriangle();
    _drawCallback = new DistanceFieldDrawCallback(this, false);
    _lastDrawCallback = new DistanceFieldDrawCallback(this, true);
    osg::ref_ptr<osg::Uniform> sampler =
        new osg::Uniform(osg::Uniform::UNSIGNED_INT_SAMPLER_2D, "loa_jfaSeeds");
    sampler->set(0);
    osg::ref_ptr<osg::Uniform> width = new osg::Uniform("loa_jfaWidth", w);
    const unsigned prot = osg::StateAttribute::ON | osg::StateAttribute::PROTECTED;
    const unsigned off = osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED;

    // Passes 0..n-1 flood (packed, packs x h); pass n writes the distances (w x h).
    const std::size_t n = _passSteps.size();
    osg::Texture2D* source = _seedTexture.get();
    for (std::size_t i = 0; i <= n; ++i)
    {
        const bool last = i == n;
        osg::ref_ptr<osg::Camera> cam = new osg::Camera;
        cam->setName(last ? std::string("loa_jfa distance")
                          : "loa_jfa step " + std::to_string(_passSteps[i]));
        cam->setRenderOrder(osg::Camera::PRE_RENDER, int(i));
        cam->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
        cam->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
        cam->setImplicitBufferAttachmentMask(0, 0);
        cam->setViewport(0, 0, last ? w : packs, h);
        cam->setClearMask(0); // every texel is written
        cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        cam->setCullingMode(osg::CullSettings::NO_CULLING);
        cam->setProjectionMatrix(osg::Matrix::identity());
        cam->setViewMatrix(osg::Matrix::identity());
        osg::Texture2D* target = last ? _distanceTexture.get() : _pingPong[i % 2].get();
        cam->attach(osg::Camera::COLOR_BUFFER0, target);
        cam->setInitialDrawCallback(_drawCallback.get());
        if (last) cam->setPostDrawCallback(_lastDrawCallback.get());

        osg::StateSet* ss = cam->getOrCreateStateSet();
        ss->setAttributeAndModes(last ? _distanceProgram.get() : _stepProgram.get(), prot);
        ss->setTextureAttribute(0, source, prot);
        ss->addUniform(sampler.get(), prot);
        ss->addUniform(width.get(), prot);
        if (last)
            ss->addUniform(_scaleUniform.get(), prot);
        else
            ss->addUniform(new osg::Uniform("loa_jfaStep", _passSteps[i]), prot);
        ss->setMode(GL_DEPTH_TEST, off);
        ss->setMode(GL_BLEND, off);
        ss->setMode(GL_CULL_FACE, off);
        ss->setMode(GL_LIGHTING, off);
        cam->addChild(triangle.get());
        addChild(cam.get());
        _cameras.push_back(cam);
        source = target;
    }
}

void DistanceField::prepareSeeds()
{
    if (!_grid.valid() || !(_seedImage.valid() || _distanceImage.valid())) return;
    if (_rasterizePending && _seedsFromRegions)
    {
        _seeds = rasterize(_grid, _regions);
        ++_seedRevision;
    }
    _rasterizePending = false;
    const int w = _grid.width, h = _grid.height, packs = packsOf(w);
    const bool fits = _seeds.width == w && _seeds.height == h;
    if (_method == CPU_EXACT)
    {
        if (_uploadedRevision == _seedRevision && _computedRevision == _computeRevision) return;
        _uploadedRevision = _seedRevision;
        _computedRevision = _computeRevision;
        Map m = computeExact(fits ? _seeds : Seeds(w, h));
        const float scale = _units == WORLD ? float(_grid.texelSize) : 1.0f;
        auto* out = reinterpret_cast<float*>(_distanceImage->data());
        for (std::size_t i = 0; i < m.distance.size(); ++i)
            out[i] = m.distance[i] * scale;
        _distanceImage->dirty();
        ++_computations;
        if (_readBack)
        {
            std::copy(out, out + m.distance.size(), m.distance.begin());
            _readBackMap = std::move(m);
        }
        return;
    }
    if (_uploadedRevision == _seedRevision) return;
    auto* out = reinterpret_cast<std::uint32_t*>(_seedImage->data());
    std::fill(out, out + std::size_t(packs) * 4 * std::size_t(h), Map::kNoSeed);
    if (fits)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (_seeds.mask[std::size_t(y) * std::size_t(w) + std::size_t(x)])
                    out[std::size_t(y) * std::size_t(packs) * 4 + std::size_t(x)] = Map::pack(x, y);
    _seedImage->dirty();
    _uploadedRevision = _seedRevision;
    ++_computeRevision;
}

void DistanceField::traverse(osg::NodeVisitor& nv)
{
    switch (nv.getVisitorType())
    {
    case osg::NodeVisitor::UPDATE_VISITOR:
        prepareSeeds();
        osg::Group::traverse(nv);
        return;
    case osg::NodeVisitor::CULL_VISITOR:
        // The passes render only in a frame after a change; the textures keep their content.
        if (_cameras.empty() || _computedRevision == _computeRevision) return;
        _computedRevision = _computeRevision;
        osg::Group::traverse(nv);
        return;
    default:
        osg::Group::traverse(nv);
    }
}

void DistanceField::onPassDrawn(osg::RenderInfo& renderInfo, bool last)
{
    if (!last)
    {
        ++_passesDrawn; // every pass, the last included (its initial draw callback)
        return;
    }
    ++_computations;
    if (!_readBack) return;
    const int w = _grid.width, h = _grid.height, packs = packsOf(w);
    Map m;
    m.width = w;
    m.height = h;
    m.distance.resize(std::size_t(w) * std::size_t(h));
    m.nearest.resize(m.distance.size());
    std::vector<std::uint32_t> packed(std::size_t(packs) * 4 * std::size_t(h));
    osg::State& state = *renderInfo.getState();
    state.setActiveTextureUnit(0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    state.applyTextureAttribute(0, _distanceTexture.get());
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, m.distance.data());
    state.applyTextureAttribute(0, getNearestSeedTexture());
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA_INTEGER_EXT, GL_UNSIGNED_INT, packed.data());
    for (int y = 0; y < h; ++y)
        std::copy_n(packed.begin() + std::ptrdiff_t(std::size_t(y) * std::size_t(packs) * 4), w,
                    m.nearest.begin() + std::ptrdiff_t(std::size_t(y) * std::size_t(w)));
    _readBackMap = std::move(m);
}

DistanceField::Map DistanceField::computeGPU(OffscreenRenderer& renderer, const Seeds& seeds, Variant variant,
                                             int maxDistanceTexels)
{
    if (seeds.width < 1 || seeds.height < 1)
        throw std::invalid_argument("a GPU distance field needs at least one texel");
    checkCapabilities(renderer.getCapabilities(), seeds.width, seeds.height);
    osg::ref_ptr<DistanceField> field = new DistanceField;
    field->setGrid(Grid(osg::Vec2d(0.0, 0.0), 1.0, seeds.width, seeds.height));
    field->setVariant(variant);
    field->setMaxDistance(std::max(0, maxDistanceTexels));
    field->setUnits(TEXELS);
    field->setSeeds(seeds);
    field->setReadBack(true);
    // Work-around: OffscreenRenderer re-checks the programs of new scene data with its context
    // made current and then released, while osgViewer still believes the context current from
    // the last frame and does not make it current again. Making it current in the update
    // traversal (before rendering) restores what the viewer believes.
    struct MakeCurrent : public osg::NodeCallback
    {
        explicit MakeCurrent(osg::GraphicsContext* gc) : _gc(gc) {}
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            if (_gc.valid()) _gc->makeCurrent();
            traverse(node, nv);
        }
        osg::observer_ptr<osg::GraphicsContext> _gc;
    };
    field->setUpdateCallback(new MakeCurrent(renderer.getContext()));
    renderer.setSceneData(field.get());
    renderer.renderImage();
    renderer.setSceneData(nullptr);
    Map m = field->getReadBackMap();
    if (m.width != seeds.width || m.height != seeds.height)
        throw std::runtime_error("the distance field passes did not run in the rendered frame");
    return m;
}

} // namespace osgLoA
