#include <osgLoA/city/CityGenerator>
#include <osgLoA/city/CityTextures>
#include <osgLoA/semantics/Feature>

#include "MeshBuilder.h"

#include <osg/CullFace>
#include <osg/Geode>
#include <osg/Material>
#include <osg/PolygonOffset>
#include <osg/ValueObject>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

namespace osgLoA
{
using detail::MeshBuilder;

namespace
{
constexpr double kStorey = 3.2;
constexpr double kPi = 3.14159265358979323846;

/** SplitMix64: a tiny, well-mixed, fully specified generator (identical everywhere). */
class Random
{
public:
    explicit Random(std::uint64_t seed) : _state(seed) {}
    std::uint64_t next()
    {
        std::uint64_t z = (_state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /** Uniform in [0, 1) with 53 bits. */
    double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    int integer(int lo, int hi)
    {
        return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1));
    }

private:
    std::uint64_t _state;
};

std::uint64_t streamSeed(unsigned seed, std::uint64_t a, std::uint64_t b)
{
    Random r(seed * 0x100000001b3ull ^ (a << 32) ^ b);
    return r.next();
}

double smoothstep(double e0, double e1, double x)
{
    if (e1 <= e0) return x < e0 ? 0.0 : 1.0;
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/** Value noise in [0, 1] on an integer lattice, smoothly interpolated. */
double lattice(unsigned seed, long long ix, long long iy)
{
    Random r(
        streamSeed(seed, static_cast<std::uint64_t>(ix) & 0xffffffffull, static_cast<std::uint64_t>(iy)));
    return r.uniform();
}
double valueNoise(unsigned seed, double x, double y)
{
    const double fx = std::floor(x), fy = std::floor(y);
    const long long ix = static_cast<long long>(fx), iy = static_cast<long long>(fy);
    const double tx = smoothstep(0, 1, x - fx), ty = smoothstep(0, 1, y - fy);
    const double a = lattice(seed, ix, iy), b = lattice(seed, ix + 1, iy);
    const double c = lattice(seed, ix, iy + 1), d = lattice(seed, ix + 1, iy + 1);
    return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}
double fbm(unsigned seed, double x, double y)
{
    double sum = 0, amp = 0.5, norm = 0;
    for (int o = 0; o < 4; ++o)
    {
        sum += amp * valueNoise(seed + static_cast<unsigned>(o) * 7919u, x, y);
        norm += amp;
        x *= 2.03;
        y *= 2.03;
        amp *= 0.5;
    }
    return sum / norm;
}

struct Rect
{
    double x0, y0, x1, y1;
    double w() const { return x1 - x0; }
    double h() const { return y1 - y0; }
    double cx() const { return 0.5 * (x0 + x1); }
    double cy() const { return 0.5 * (y0 + y1); }
};

enum class BlockKind
{
    Riverside,
    Buildings,
    Park,
    Forest,
    Landmark
};

/** Shared state sets, one per texture, so the scene has few state changes. */
class StateSets
{
public:
    osg::StateSet* textured(const std::string& kind)
    {
        auto it = _sets.find(kind);
        if (it != _sets.end()) return it->second.get();
        osg::ref_ptr<osg::Image> image;
        for (const FacadeStyle& s : CityTextures::facadeStyles())
            if (s.name == kind) image = CityTextures::facade(s);
        if (!image) image = CityTextures::surface(kind);
        osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
        ss->setName(kind);
        ss->setTextureAttributeAndModes(0, CityTextures::makeTexture(image.get()).get(),
                                        osg::StateAttribute::ON);
        _sets[kind] = ss;
        return ss.get();
    }
    osg::StateSet* draped(const std::string& kind)
    {
        const std::string key = kind + "#draped";
        auto it = _sets.find(key);
        if (it != _sets.end()) return it->second.get();
        osg::ref_ptr<osg::StateSet> ss = new osg::StateSet(*textured(kind), osg::CopyOp::SHALLOW_COPY);
        ss->setAttributeAndModes(new osg::PolygonOffset(-1.0f, -4.0f), osg::StateAttribute::ON);
        _sets[key] = ss;
        return ss.get();
    }

private:
    std::map<std::string, osg::ref_ptr<osg::StateSet>> _sets;
};

osg::ref_ptr<osg::Geode> geodeWith(osg::ref_ptr<osg::Geometry> g, osg::StateSet* ss)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    if (ss) g->setStateSet(ss);
    geode->addDrawable(g.get());
    return geode;
}
} // namespace

CityGenerator::CityGenerator(const CityParameters& parameters) : _p(parameters)
{
    _p.validate();
    computeLayout();
}

void CityGenerator::computeLayout()
{
    auto lines = [&](int blocks, std::vector<double>& pos, std::vector<bool>& major)
    {
        pos.assign(static_cast<size_t>(blocks) + 1, 0.0);
        major.assign(static_cast<size_t>(blocks) + 1, false);
        for (int i = 0; i <= blocks; ++i)
            major[static_cast<size_t>(i)] = i % _p.majorRoadEvery == 0;
        auto width = [&](int i)
        { return major[static_cast<size_t>(i)] ? _p.majorRoadWidth : _p.minorRoadWidth; };
        for (int i = 1; i <= blocks; ++i)
            pos[static_cast<size_t>(i)] =
                pos[static_cast<size_t>(i) - 1] + width(i - 1) / 2 + _p.blockSize + width(i) / 2;
        const double shift = pos.back() / 2;
        for (double& x : pos)
            x -= shift;
        return width(blocks);
    };
    const double wLastX = lines(_p.blocksX, _layout.roadLinesX, _layout.roadLineXMajor);
    const double wLastY = lines(_p.blocksY, _layout.roadLinesY, _layout.roadLineYMajor);
    const double w0 = _p.majorRoadWidth; // line 0 is always major
    const double cx0 = _layout.roadLinesX.front() - w0 / 2, cx1 = _layout.roadLinesX.back() + wLastX / 2;
    const double cy0 = _layout.roadLinesY.front() - w0 / 2, cy1 = _layout.roadLinesY.back() + wLastY / 2;

    Random rng(streamSeed(_p.seed, 1, 0));
    _riverX0 = cx0 + (cx1 - cx0) * rng.uniform(0.3, 0.4);
    _riverAmplitude = 0.6 * _p.blockSize;
    _riverPeriod = 2.5 * std::max(cy1 - cy0, 4.0 * _p.blockSize);
    _riverPhase = rng.uniform(0.0, 2.0 * kPi);
    _layout.waterLevel = 1.0;

    const double m = _p.terrainMargin;
    _layout.terrainBounds.set(cx0 - m, cy0 - m, -10.0, cx1 + m, cy1 + m, 10.0);
    const int n = _p.terrainResolution;
    _terrainStepX = (_layout.terrainBounds.xMax() - _layout.terrainBounds.xMin()) / (n - 1);
    _terrainStepY = (_layout.terrainBounds.yMax() - _layout.terrainBounds.yMin()) / (n - 1);
    _heights.resize(static_cast<size_t>(n) * static_cast<size_t>(n));
    float zmin = 1e30f, zmax = -1e30f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            const double x = _layout.terrainBounds.xMin() + i * _terrainStepX;
            const double y = _layout.terrainBounds.yMin() + j * _terrainStepY;
            const float h = static_cast<float>(terrainHeight(x, y));
            _heights[static_cast<size_t>(j) * static_cast<size_t>(n) + static_cast<size_t>(i)] = h;
            zmin = std::min(zmin, h);
            zmax = std::max(zmax, h);
        }
    _layout.terrainBounds.zMin() = zmin;
    _layout.terrainBounds.zMax() = zmax;
    float czmin = 1e30f, czmax = -1e30f;
    for (double y = cy0; y <= cy1; y += 10.0)
        for (double x = cx0; x <= cx1; x += 10.0)
        {
            const float h = static_cast<float>(meshHeight(x, y));
            czmin = std::min(czmin, h);
            czmax = std::max(czmax, h);
        }
    _layout.cityBounds.set(cx0, cy0, czmin, cx1, cy1, czmax);
}

double CityGenerator::riverCenterX(double y) const
{
    return _riverX0 + _riverAmplitude * std::sin(2.0 * kPi * y / _riverPeriod + _riverPhase);
}

double CityGenerator::terrainHeight(double x, double y) const
{
    const osg::BoundingBox& t = _layout.terrainBounds;
    const double m = std::max(_p.terrainMargin, 1.0);
    // 0 inside the city, rising to 1 at the terrain's edge.
    const double dx = std::max({0.0, (t.xMin() + m) - x, x - (t.xMax() - m)}) / m;
    const double dy = std::max({0.0, (t.yMin() + m) - y, y - (t.yMax() - m)}) / m;
    const double outside = std::clamp(std::max(dx, dy), 0.0, 1.0);
    double h = 3.0 + 4.0 * fbm(_p.seed * 3u + 1u, x / 300.0 + 17.0, y / 300.0 + 5.0);
    h += _p.reliefAmplitude * smoothstep(0.0, 1.0, outside) * fbm(_p.seed * 3u + 2u, x / 350.0, y / 350.0) *
         1.6;
    if (_p.river)
    {
        const double d = std::fabs(x - riverCenterX(y));
        const double bank = smoothstep(_p.riverWidth / 2 - 3.0, _p.riverWidth / 2 + 30.0, d);
        h = -2.5 + (h + 2.5) * bank;
    }
    return h;
}

double CityGenerator::meshHeight(double x, double y) const
{
    const int n = _p.terrainResolution;
    const double gx = std::clamp((x - _layout.terrainBounds.xMin()) / _terrainStepX, 0.0, n - 1.0);
    const double gy = std::clamp((y - _layout.terrainBounds.yMin()) / _terrainStepY, 0.0, n - 1.0);
    const int i = std::min(static_cast<int>(gx), n - 2), j = std::min(static_cast<int>(gy), n - 2);
    const double fx = gx - i, fy = gy - j;
    auto H = [&](int a, int b)
    {
        return static_cast<double>(
            _heights[static_cast<size_t>(b) * static_cast<size_t>(n) + static_cast<size_t>(a)]);
    };
    const double h00 = H(i, j), h10 = H(i + 1, j), h01 = H(i, j + 1), h11 = H(i + 1, j + 1);
    // The mesh splits each cell along (i,j)-(i+1,j+1).
    if (fx >= fy) return h00 + fx * (h10 - h00) + fy * (h11 - h10);
    return h00 + fy * (h01 - h00) + fx * (h11 - h01);
}

namespace
{
/** The pieces the generator builds; kept out of the header. */
class Builder
{
public:
    Builder(const CityGenerator& gen, const CityParameters& p, const CityLayout& l) : g(gen), p(p), L(l) {}

    const CityGenerator& g;
    const CityParameters& p;
    const CityLayout& L;
    StateSets states;
    unsigned nextId = 1;

    osg::ref_ptr<osg::Group> feature(FeatureType type, const std::string& subtype, bool landmark = false)
    {
        osg::ref_ptr<osg::Group> group = new osg::Group;
        osg::ref_ptr<Feature> f = new Feature(nextId++, type, subtype, Feature::MODEL_DATA);
        f->setLandmark(landmark);
        if (landmark) f->setInterest(1.0f); // the generator builds landmarks on purpose
        f->setSourceType("loacity");
        Feature::attach(*group, f.get());
        return group;
    }

    osg::ref_ptr<osg::Node> terrain()
    {
        const int n = p.terrainResolution;
        const osg::BoundingBox& t = L.terrainBounds;
        const double sx = (t.xMax() - t.xMin()) / (n - 1), sy = (t.yMax() - t.yMin()) / (n - 1);
        MeshBuilder mb;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
            {
                const double x = t.xMin() + i * sx, y = t.yMin() + j * sy;
                const double hx = g.meshHeight(x + sx, y) - g.meshHeight(x - sx, y);
                const double hy = g.meshHeight(x, y + sy) - g.meshHeight(x, y - sy);
                osg::Vec3 nrm(static_cast<float>(-hx / (2 * sx)), static_cast<float>(-hy / (2 * sy)), 1.0f);
                nrm.normalize();
                mb.vertex(osg::Vec3(static_cast<float>(x), static_cast<float>(y),
                                    static_cast<float>(g.meshHeight(x, y))),
                          nrm, osg::Vec2(static_cast<float>(x / 25.0), static_cast<float>(y / 25.0)));
            }
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i)
            {
                const unsigned a = static_cast<unsigned>(j * n + i), b = a + 1,
                               c = a + static_cast<unsigned>(n) + 1, d = a + static_cast<unsigned>(n);
                mb.triangleIndices(a, b, c);
                mb.triangleIndices(a, c, d);
            }
        osg::ref_ptr<osg::Group> f = feature(FeatureType::Terrain, "relief");
        f->addChild(geodeWith(mb.build("TINRelief"), states.textured("terrain")).get());
        return f;
    }

    osg::ref_ptr<osg::Node> water()
    {
        const osg::BoundingBox& t = L.terrainBounds;
        const double half = p.riverWidth / 2 + 22.0;
        MeshBuilder mb;
        const float z = static_cast<float>(L.waterLevel);
        const int steps = std::max(2, static_cast<int>((t.yMax() - t.yMin()) / 10.0));
        for (int k = 0; k <= steps; ++k)
        {
            const double y = t.yMin() + (t.yMax() - t.yMin()) * k / steps;
            const double xc = g.riverCenterX(y);
            const osg::Vec3 up(0, 0, 1);
            mb.vertex(osg::Vec3(static_cast<float>(xc - half), static_cast<float>(y), z), up,
                      osg::Vec2(static_cast<float>((xc - half) / 30.0), static_cast<float>(y / 30.0)));
            mb.vertex(osg::Vec3(static_cast<float>(xc + half), static_cast<float>(y), z), up,
                      osg::Vec2(static_cast<float>((xc + half) / 30.0), static_cast<float>(y / 30.0)));
            if (k > 0)
            {
                const unsigned b = static_cast<unsigned>(2 * k);
                mb.triangleIndices(b - 2, b - 1, b + 1);
                mb.triangleIndices(b - 2, b + 1, b);
            }
        }
        osg::ref_ptr<osg::Group> f = feature(FeatureType::Water, "river");
        f->addChild(geodeWith(mb.build("WaterSurface"), states.textured("water")).get());
        return f;
    }

    double roadZ(double x, double y, bool major, bool alongX) const
    {
        const double z = g.meshHeight(x, y) + (major ? 0.35 : 0.25) + (alongX ? 0.05 : 0.0);
        return p.river ? std::max(z, L.waterLevel + 1.8) : z; // bridges over the river
    }

    /** The demo city's street names, as an American grid names them: the east-west streets
     *  after trees ("Oak Street"; "Boulevard" for major ones), the north-south ones numbered
     *  ("3rd Avenue"). */
    static std::string streetName(bool alongX, size_t line, bool major)
    {
        if (alongX)
        {
            static const char* const trees[] = {"Oak",    "Elm",   "Maple", "Cedar",  "Pine",   "Birch",
                                                "Walnut", "Aspen", "Alder", "Willow", "Poplar", "Laurel"};
            const size_t n = sizeof(trees) / sizeof(trees[0]);
            std::string name = trees[line % n];
            if (line >= n) name += " " + std::to_string(line / n + 1);
            return name + (major ? " Boulevard" : " Street");
        }
        const size_t k = line + 1;
        const char* suffix = (k % 100 >= 11 && k % 100 <= 13) ? "th"
                             : k % 10 == 1                    ? "st"
                             : k % 10 == 2                    ? "nd"
                             : k % 10 == 3                    ? "rd"
                                                              : "th";
        return std::to_string(k) + suffix + (major ? " Parkway" : " Avenue");
    }

    osg::ref_ptr<osg::Node> street(bool alongX, size_t line)
    {
        const bool major = alongX ? L.roadLineYMajor[line] : L.roadLineXMajor[line];
        const double w = major ? p.majorRoadWidth : p.minorRoadWidth;
        const double c = alongX ? L.roadLinesY[line] : L.roadLinesX[line];
        const double a0 = alongX ? L.cityBounds.xMin() : L.cityBounds.yMin();
        const double a1 = alongX ? L.cityBounds.xMax() : L.cityBounds.yMax();
        const int steps = std::max(1, static_cast<int>(std::ceil((a1 - a0) / 5.0)));
        MeshBuilder mb;
        for (int k = 0; k <= steps; ++k)
        {
            const double a = a0 + (a1 - a0) * k / steps;
            const float v = static_cast<float>((a - a0) / (w * 1.5));
            for (int side = 0; side < 2; ++side)
            {
                const double off = c + (side ? w / 2 : -w / 2);
                const double x = alongX ? a : off, y = alongX ? off : a;
                // u runs across the road: 0 on the left of the direction of travel.
                const float u = alongX ? static_cast<float>(1 - side) : static_cast<float>(side);
                mb.vertex(osg::Vec3(static_cast<float>(x), static_cast<float>(y),
                                    static_cast<float>(roadZ(x, y, major, alongX))),
                          osg::Vec3(0, 0, 1), osg::Vec2(u, v));
            }
            if (k > 0)
            {
                const unsigned b = static_cast<unsigned>(2 * k);
                if (alongX) // vertices: side 0 = south edge, side 1 = north edge
                {
                    mb.triangleIndices(b - 2, b, b + 1);
                    mb.triangleIndices(b - 2, b + 1, b - 1);
                }
                else // side 0 = west edge, side 1 = east edge
                {
                    mb.triangleIndices(b - 2, b - 1, b + 1);
                    mb.triangleIndices(b - 2, b + 1, b);
                }
            }
        }
        osg::ref_ptr<osg::Group> f = feature(FeatureType::Street, major ? "major" : "minor");
        // The centre line, through every crossing with the other direction's roads (the same
        // coordinates there, so routes find the junctions: ScenarioFitting).
        Feature::Centreline centreline;
        const std::vector<double>& crossings = alongX ? L.roadLinesX : L.roadLinesY;
        std::vector<double> along = {a0, a1};
        for (double x : crossings)
            if (x > a0 && x < a1) along.push_back(x);
        std::sort(along.begin(), along.end());
        for (double a : along)
            centreline.push_back(alongX ? osg::Vec2d(a, c) : osg::Vec2d(c, a));
        Feature::get(*f)->setCentreline(centreline);
        Feature::get(*f)->setLabel(streetName(alongX, line, major));
        f->addChild(
            geodeWith(mb.build("TrafficArea"), states.draped(major ? "road-major" : "road-minor")).get());
        return f;
    }

    // --- green spaces -------------------------------------------------------------------
    void drapedPatch(MeshBuilder& mb, const Rect& r, double lift, double texScale) const
    {
        const int nx = std::max(1, static_cast<int>(std::ceil(r.w() / 10.0)));
        const int ny = std::max(1, static_cast<int>(std::ceil(r.h() / 10.0)));
        const unsigned base = mb.numVertices();
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
            {
                const double x = r.x0 + r.w() * i / nx, y = r.y0 + r.h() * j / ny;
                mb.vertex(osg::Vec3(static_cast<float>(x), static_cast<float>(y),
                                    static_cast<float>(g.meshHeight(x, y) + lift)),
                          osg::Vec3(0, 0, 1),
                          osg::Vec2(static_cast<float>(x / texScale), static_cast<float>(y / texScale)));
            }
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
            {
                const unsigned a = base + static_cast<unsigned>(j * (nx + 1) + i), b = a + 1,
                               c = a + static_cast<unsigned>(nx + 1) + 1,
                               d = a + static_cast<unsigned>(nx + 1);
                mb.triangleIndices(a, b, c);
                mb.triangleIndices(a, c, d);
            }
    }

    /** A square prism trunk of half-width r and height h standing on base. */
    static void squareTrunk(MeshBuilder& trunk, const osg::Vec3& base, float r, float h)
    {
        const osg::Vec3 axis = base + osg::Vec3(0, 0, h / 2);
        for (int k = 0; k < 4; ++k)
        {
            const double a0 = kPi / 2 * k, a1 = kPi / 2 * (k + 1);
            const osg::Vec3 d0(static_cast<float>(std::cos(a0)) * r, static_cast<float>(std::sin(a0)) * r, 0);
            const osg::Vec3 d1(static_cast<float>(std::cos(a1)) * r, static_cast<float>(std::sin(a1)) * r, 0);
            const osg::Vec3 q[4] = {base + d0, base + d1, base + d1 + osg::Vec3(0, 0, h),
                                    base + d0 + osg::Vec3(0, 0, h)};
            const osg::Vec2 t[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            trunk.quad(q, t, &axis);
        }
    }

    void coniferTree(MeshBuilder& crown, MeshBuilder& trunk, osg::Vec3 base, double h, Random& rng) const
    {
        const float H = static_cast<float>(h);
        const float tr = 0.025f * H, th = 0.22f * H, cr = 0.2f * H;
        const osg::Vec3 centre = base + osg::Vec3(0, 0, 0.5f * H);
        squareTrunk(trunk, base, tr, th);
        const float shade = static_cast<float>(rng.uniform(0.85, 1.1));
        crown.color = osg::Vec4(0.16f * shade, 0.36f * shade, 0.20f * shade, 1.0f);
        const osg::Vec3 apex = base + osg::Vec3(0, 0, H);
        const int seg = 8;
        for (int k = 0; k < seg; ++k)
        {
            const double a0 = 2 * kPi * k / seg, a1 = 2 * kPi * (k + 1) / seg;
            const osg::Vec3 b0 = base + osg::Vec3(static_cast<float>(std::cos(a0)) * cr,
                                                  static_cast<float>(std::sin(a0)) * cr, 0.18f * H);
            const osg::Vec3 b1 = base + osg::Vec3(static_cast<float>(std::cos(a1)) * cr,
                                                  static_cast<float>(std::sin(a1)) * cr, 0.18f * H);
            crown.triangle(b0, b1, apex, {0, 0}, {1, 0}, {0.5f, 1}, &centre);
        }
    }

    void deciduousTree(MeshBuilder& crown, MeshBuilder& trunk, osg::Vec3 base, double h, Random& rng) const
    {
        const float H = static_cast<float>(h);
        const float tr = 0.03f * H, th = 0.5f * H;
        squareTrunk(trunk, base, tr, th);
        // Icosahedral crown, squashed a little.
        const float shade = static_cast<float>(rng.uniform(0.85, 1.15));
        crown.color = osg::Vec4(0.30f * shade, 0.50f * shade, 0.18f * shade, 1.0f);
        const float r = 0.32f * H;
        const osg::Vec3 c = base + osg::Vec3(0, 0, 0.66f * H);
        const float t = 1.618034f;
        const osg::Vec3 v[12] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
        static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
        auto P = [&](int i)
        {
            osg::Vec3 q = v[i];
            q.normalize();
            return c + osg::Vec3(q.x() * r, q.y() * r, q.z() * r * 0.8f);
        };
        for (const auto& tri : f)
            crown.triangle(P(tri[0]), P(tri[1]), P(tri[2]), {0, 0}, {1, 0}, {0.5f, 1}, &c);
    }

    osg::ref_ptr<osg::Node> greenSpace(const Rect& block, bool forest, const std::string& subtype,
                                       Random& rng)
    {
        const Rect r{block.x0 + 1, block.y0 + 1, block.x1 - 1, block.y1 - 1};
        MeshBuilder ground, crown, trunk;
        drapedPatch(ground, r, 0.12, 15.0);
        trunk.color = osg::Vec4(0.36f, 0.26f, 0.17f, 1.0f);
        const double density = (forest ? p.forestTreesPerHectare : p.parkTreesPerHectare) / 10000.0;
        const double area = r.w() * r.h();
        const int count = static_cast<int>(std::floor(area * density));
        const Rect inner{r.x0 + 3, r.y0 + 3, r.x1 - 3, r.y1 - 3};
        // Forests: jittered grid, evenly covered; parks: scattered.
        const int cols = std::max(1, static_cast<int>(std::lround(std::sqrt(count * inner.w() / inner.h()))));
        for (int k = 0; k < count; ++k)
        {
            double x, y;
            if (forest)
            {
                const int rows = std::max(1, (count + cols - 1) / cols);
                const int ci = k % cols, ri = k / cols;
                x = inner.x0 + inner.w() * (ci + rng.uniform(0.1, 0.9)) / cols;
                y = inner.y0 + inner.h() * (ri + rng.uniform(0.1, 0.9)) / rows;
            }
            else
            {
                x = rng.uniform(inner.x0, inner.x1);
                y = rng.uniform(inner.y0, inner.y1);
            }
            const osg::Vec3 base(static_cast<float>(x), static_cast<float>(y),
                                 static_cast<float>(g.meshHeight(x, y)));
            const bool conifer = subtype == "coniferous" || (subtype == "mixed" && rng.uniform() < 0.5);
            const double h = conifer ? rng.uniform(12.0, 22.0) : rng.uniform(8.0, 16.0);
            if (conifer)
                coniferTree(crown, trunk, base, h, rng);
            else
                deciduousTree(crown, trunk, base, h, rng);
        }
        osg::ref_ptr<osg::Group> f = feature(FeatureType::Green, subtype);
        f->addChild(
            geodeWith(ground.build("PlantCover"), states.draped(forest ? "forest-floor" : "park-grass"))
                .get());
        if (!crown.empty())
        {
            osg::ref_ptr<osg::Geode> trees = new osg::Geode;
            trees->setName("SolitaryVegetationObjects");
            trees->addDrawable(crown.build("TreeCrown").get());
            trees->addDrawable(trunk.build("TreeTrunk").get());
            f->addChild(trees.get());
        }
        return f;
    }

    // --- buildings ------------------------------------------------------------------------
    struct Footprint
    {
        double groundMin, groundMax;
    };
    Footprint ground(const Rect& r) const
    {
        Footprint fp{1e30, -1e30};
        for (double fx : {0.0, 0.5, 1.0})
            for (double fy : {0.0, 0.5, 1.0})
            {
                const double h = g.meshHeight(r.x0 + fx * r.w(), r.y0 + fy * r.h());
                fp.groundMin = std::min(fp.groundMin, h);
                fp.groundMax = std::max(fp.groundMax, h);
            }
        return fp;
    }

    /** Four textured walls of an axis-aligned box; v = 0 at ground level (zGround). */
    static void boxWalls(MeshBuilder& walls, const Rect& r, double zb, double zt, double zGround,
                         const FacadeStyle& s)
    {
        const osg::Vec3 centre(static_cast<float>(r.cx()), static_cast<float>(r.cy()),
                               static_cast<float>((zb + zt) / 2));
        const double cs[5][2] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}, {r.x0, r.y0}};
        const float v0 = static_cast<float>((zb - zGround) / (kStorey * s.floors));
        const float v1 = static_cast<float>((zt - zGround) / (kStorey * s.floors));
        for (int e = 0; e < 4; ++e)
        {
            const double len = std::hypot(cs[e + 1][0] - cs[e][0], cs[e + 1][1] - cs[e][1]);
            const float u1 = static_cast<float>(std::max(1.0, std::round(len / s.bayWidth)) / s.bays);
            const osg::Vec3 a(static_cast<float>(cs[e][0]), static_cast<float>(cs[e][1]), 0);
            const osg::Vec3 b(static_cast<float>(cs[e + 1][0]), static_cast<float>(cs[e + 1][1]), 0);
            const osg::Vec3 q[4] = {
                a + osg::Vec3(0, 0, static_cast<float>(zb)), b + osg::Vec3(0, 0, static_cast<float>(zb)),
                b + osg::Vec3(0, 0, static_cast<float>(zt)), a + osg::Vec3(0, 0, static_cast<float>(zt))};
            const osg::Vec2 t[4] = {{0, v0}, {u1, v0}, {u1, v1}, {0, v1}};
            walls.quad(q, t, &centre);
        }
    }

    static void flatRoof(MeshBuilder& roof, const Rect& r, double z)
    {
        const float fz = static_cast<float>(z);
        const osg::Vec3 q[4] = {{static_cast<float>(r.x0), static_cast<float>(r.y0), fz},
                                {static_cast<float>(r.x1), static_cast<float>(r.y0), fz},
                                {static_cast<float>(r.x1), static_cast<float>(r.y1), fz},
                                {static_cast<float>(r.x0), static_cast<float>(r.y1), fz}};
        osg::Vec2 t[4];
        for (int k = 0; k < 4; ++k)
            t[k] = osg::Vec2(q[k].x() / 8.0f, q[k].y() / 8.0f);
        const osg::Vec3 below(static_cast<float>(r.cx()), static_cast<float>(r.cy()), fz - 1.0f);
        roof.quad(q, t, &below);
    }

    /** A gable roof with its ridge along the longer side; gable ends go to the walls. */
    static void gableRoof(MeshBuilder& roof, MeshBuilder& walls, const Rect& r, double eave, double zGround,
                          const FacadeStyle& s)
    {
        const bool alongX = r.w() >= r.h();
        const double span = alongX ? r.h() : r.w();
        const float rise = static_cast<float>(0.4 * span);
        const float ze = static_cast<float>(eave), zr = ze + rise;
        const osg::Vec3 centre(static_cast<float>(r.cx()), static_cast<float>(r.cy()), ze);
        auto V = [](double x, double y, float z)
        { return osg::Vec3(static_cast<float>(x), static_cast<float>(y), z); };
        const float slope = static_cast<float>(std::hypot(span / 2, rise) / 4.0);
        if (alongX)
        {
            const double ym = r.cy();
            const float L = static_cast<float>(r.w() / 4.0);
            const osg::Vec3 s1[4] = {V(r.x0, r.y0, ze), V(r.x1, r.y0, ze), V(r.x1, ym, zr), V(r.x0, ym, zr)};
            const osg::Vec3 s2[4] = {V(r.x1, r.y1, ze), V(r.x0, r.y1, ze), V(r.x0, ym, zr), V(r.x1, ym, zr)};
            const osg::Vec2 t[4] = {{0, 0}, {L, 0}, {L, slope}, {0, slope}};
            roof.quad(s1, t, &centre);
            roof.quad(s2, t, &centre);
            const float vE = static_cast<float>((eave - zGround) / (kStorey * s.floors));
            const float vR = static_cast<float>((eave + rise - zGround) / (kStorey * s.floors));
            const float u = static_cast<float>(std::max(1.0, std::round(r.h() / s.bayWidth)) / s.bays);
            walls.triangle(V(r.x0, r.y0, ze), V(r.x0, r.y1, ze), V(r.x0, ym, zr), {0, vE}, {u, vE},
                           {u / 2, vR}, &centre);
            walls.triangle(V(r.x1, r.y0, ze), V(r.x1, r.y1, ze), V(r.x1, ym, zr), {0, vE}, {u, vE},
                           {u / 2, vR}, &centre);
        }
        else
        {
            const double xm = r.cx();
            const float L = static_cast<float>(r.h() / 4.0);
            const osg::Vec3 s1[4] = {V(r.x0, r.y1, ze), V(r.x0, r.y0, ze), V(xm, r.y0, zr), V(xm, r.y1, zr)};
            const osg::Vec3 s2[4] = {V(r.x1, r.y0, ze), V(r.x1, r.y1, ze), V(xm, r.y1, zr), V(xm, r.y0, zr)};
            const osg::Vec2 t[4] = {{0, 0}, {L, 0}, {L, slope}, {0, slope}};
            roof.quad(s1, t, &centre);
            roof.quad(s2, t, &centre);
            const float vE = static_cast<float>((eave - zGround) / (kStorey * s.floors));
            const float vR = static_cast<float>((eave + rise - zGround) / (kStorey * s.floors));
            const float u = static_cast<float>(std::max(1.0, std::round(r.w() / s.bayWidth)) / s.bays);
            walls.triangle(V(r.x0, r.y0, ze), V(r.x1, r.y0, ze), V(xm, r.y0, zr), {0, vE}, {u, vE},
                           {u / 2, vR}, &centre);
            walls.triangle(V(r.x0, r.y1, ze), V(r.x1, r.y1, ze), V(xm, r.y1, zr), {0, vE}, {u, vE},
                           {u / 2, vR}, &centre);
        }
    }

    osg::ref_ptr<osg::Node> building(const Rect& r, int floors, const FacadeStyle& style, bool gable)
    {
        const Footprint fp = ground(r);
        const double zb = fp.groundMin - 1.0, zg = fp.groundMax, eave = zg + floors * kStorey;
        MeshBuilder walls, roof;
        boxWalls(walls, r, zb, eave, zg, style);
        if (gable)
            gableRoof(roof, walls, r, eave, zg, style);
        else
            flatRoof(roof, r, eave);
        osg::ref_ptr<osg::Group> f =
            feature(FeatureType::Building, floors >= 6 ? "commercial" : "residential");
        f->setUserValue("loa.building.floors", floors);
        f->setUserValue("loa.building.facade", style.name);
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        osg::ref_ptr<osg::Geometry> w = walls.build("WallSurface");
        w->setStateSet(states.textured(style.name));
        osg::ref_ptr<osg::Geometry> rf = roof.build("RoofSurface");
        rf->setStateSet(states.textured(gable ? "roof-tiles" : "roof-gravel"));
        geode->addDrawable(w.get());
        geode->addDrawable(rf.get());
        f->addChild(geode.get());
        return f;
    }

    void buildingBlock(osg::Group* parent, const Rect& block, double centrality, Random& rng)
    {
        const auto& styles = CityTextures::facadeStyles();
        for (int row = 0; row < 2; ++row)
        {
            const double depth = std::min(24.0, block.h() / 2 - 4.0);
            const double ry0 = row == 0 ? block.y0 + 2.0 : block.y1 - 2.0 - depth;
            double x = block.x0 + 1.0;
            while (x < block.x1 - 10.0)
            {
                double w = rng.uniform(14.0, 30.0);
                if (block.x1 - 1.0 - (x + w) < 12.0) w = block.x1 - 1.0 - x; // the last lot takes the rest
                const Rect lot{x + 1.0, ry0, x + w - 1.0, ry0 + depth * rng.uniform(0.75, 1.0)};
                const Rect fpRect =
                    row == 0 ? lot : Rect{lot.x0, block.y1 - 2.0 - lot.h(), lot.x1, block.y1 - 2.0};
                x += w;
                if (rng.uniform() < 0.08 || fpRect.w() < 6.0) continue; // an empty lot: a courtyard or a gap
                const double tall = std::pow(rng.uniform(), 1.5) * (0.35 + 0.65 * centrality);
                const int floors = std::clamp(
                    p.minFloors + static_cast<int>(std::lround(tall * (p.maxFloors - p.minFloors))),
                    p.minFloors, p.maxFloors);
                int si = rng.integer(0, static_cast<int>(styles.size()) - 1);
                if (floors >= 7 && rng.uniform() < 0.6)
                    si = rng.uniform() < 0.5 ? 2 : 5; // tall buildings: glass or modern
                const bool gable = floors <= 3 && rng.uniform() < 0.5;
                parent->addChild(building(fpRect, floors, styles[static_cast<size_t>(si)], gable).get());
            }
        }
    }

    static void cylinder(MeshBuilder& mb, double cx, double cy, double r, double zb, double zt, int seg,
                         double zGround, const FacadeStyle& s)
    {
        const double circumference = 2 * kPi * r;
        const float uMax = static_cast<float>(std::max(1.0, std::round(circumference / s.bayWidth)) / s.bays);
        const float v0 = static_cast<float>((zb - zGround) / (kStorey * s.floors));
        const float v1 = static_cast<float>((zt - zGround) / (kStorey * s.floors));
        const unsigned base = mb.numVertices();
        for (int k = 0; k <= seg; ++k)
        {
            const double a = 2 * kPi * k / seg;
            const osg::Vec3 n(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0);
            const osg::Vec3 pb(static_cast<float>(cx + r * std::cos(a)),
                               static_cast<float>(cy + r * std::sin(a)), static_cast<float>(zb));
            const float u = uMax * static_cast<float>(k) / static_cast<float>(seg);
            mb.vertex(pb, n, {u, v0});
            mb.vertex(osg::Vec3(pb.x(), pb.y(), static_cast<float>(zt)), n, {u, v1});
        }
        for (int k = 0; k < seg; ++k)
        {
            const unsigned b = base + static_cast<unsigned>(2 * k);
            mb.triangleIndices(b, b + 2, b + 3);
            mb.triangleIndices(b, b + 3, b + 1);
        }
    }

    static void cone(MeshBuilder& mb, double cx, double cy, double r, double zb, double h, int seg)
    {
        const osg::Vec3 apex(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(zb + h));
        const osg::Vec3 centre(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(zb));
        for (int k = 0; k < seg; ++k)
        {
            const double a0 = 2 * kPi * k / seg, a1 = 2 * kPi * (k + 1) / seg;
            const osg::Vec3 b0(static_cast<float>(cx + r * std::cos(a0)),
                               static_cast<float>(cy + r * std::sin(a0)), static_cast<float>(zb));
            const osg::Vec3 b1(static_cast<float>(cx + r * std::cos(a1)),
                               static_cast<float>(cy + r * std::sin(a1)), static_cast<float>(zb));
            mb.triangle(b0, b1, apex, {static_cast<float>(k), 0}, {static_cast<float>(k + 1), 0},
                        {static_cast<float>(k) + 0.5f, static_cast<float>(h / 4.0)}, &centre);
        }
    }

    static void dome(MeshBuilder& mb, double cx, double cy, double r, double zb, int seg, int rings)
    {
        const osg::Vec3 c(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(zb));
        auto P = [&](int k, int i)
        {
            const double a = 2 * kPi * k / seg, e = 0.5 * kPi * i / rings;
            return osg::Vec3(static_cast<float>(cx + r * std::cos(e) * std::cos(a)),
                             static_cast<float>(cy + r * std::cos(e) * std::sin(a)),
                             static_cast<float>(zb + r * std::sin(e)));
        };
        for (int i = 0; i < rings; ++i)
            for (int k = 0; k < seg; ++k)
            {
                const osg::Vec2 t[4] = {{static_cast<float>(k), static_cast<float>(i)},
                                        {static_cast<float>(k + 1), static_cast<float>(i)},
                                        {static_cast<float>(k + 1), static_cast<float>(i + 1)},
                                        {static_cast<float>(k), static_cast<float>(i + 1)}};
                if (i == rings - 1)
                    mb.triangle(P(k, i), P(k + 1, i), P(k, i + 1), t[0], t[1], t[3], &c);
                else
                {
                    const osg::Vec3 q[4] = {P(k, i), P(k + 1, i), P(k + 1, i + 1), P(k, i + 1)};
                    mb.quad(q, t, &c);
                }
            }
    }

    static void pyramid(MeshBuilder& mb, const Rect& r, double zb, double h)
    {
        auto V = [](double x, double y, double z)
        { return osg::Vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)); };
        const osg::Vec3 apex = V(r.cx(), r.cy(), zb + h), c = V(r.cx(), r.cy(), zb);
        const osg::Vec3 cs[5] = {V(r.x0, r.y0, zb), V(r.x1, r.y0, zb), V(r.x1, r.y1, zb), V(r.x0, r.y1, zb),
                                 V(r.x0, r.y0, zb)};
        for (int e = 0; e < 4; ++e)
            mb.triangle(cs[e], cs[e + 1], apex, {0, 0}, {2, 0}, {1, static_cast<float>(h / 4)}, &c);
    }

    osg::ref_ptr<osg::Node> landmark(const Rect& block, int kind)
    {
        const auto& styles = CityTextures::facadeStyles();
        const double cx = block.cx(), cy = block.cy();
        const Rect site{cx - 30, cy - 30, cx + 30, cy + 30};
        const Footprint fp = ground(Rect{std::max(block.x0, site.x0), std::max(block.y0, site.y0),
                                         std::min(block.x1, site.x1), std::min(block.y1, site.y1)});
        const double zb = fp.groundMin - 1.0, zg = fp.groundMax;
        const double s = std::min(1.0, block.w() / 90.0) * std::min(1.0, block.h() / 90.0);
        MeshBuilder walls, roof, roof2;
        std::string wallTex, roofTex = "roof-gravel", roof2Tex, name;
        switch (kind % 4)
        {
        case 0: // a stepped high-rise with a spire
        {
            name = "tower";
            wallTex = styles[2].name;
            double half = 20 * s, z0 = zb, z1 = zg + 60;
            for (int step = 0; step < 3; ++step)
            {
                const Rect r{cx - half, cy - half, cx + half, cy + half};
                boxWalls(walls, r, z0, z1, zg, styles[2]);
                flatRoof(roof, r, z1);
                z0 = z1;
                z1 += 40 - 15 * step;
                half *= 0.72;
            }
            roof2Tex = "roof-gravel";
            cone(roof2, cx, cy, 3.0, z0, 35.0, 12);
            break;
        }
        case 1: // a cathedral: nave with gable roof and two front towers
        {
            name = "cathedral";
            wallTex = styles[4].name;
            roofTex = "roof-tiles";
            const Rect nave{cx - 12 * s, cy - 32 * s, cx + 12 * s, cy + 30 * s};
            boxWalls(walls, nave, zb, zg + 24, zg, styles[4]);
            gableRoof(roof, walls, nave, zg + 24, zg, styles[4]);
            roof2Tex = "roof-tiles";
            for (int side : {-1, 1})
            {
                const double tx = cx + side * 9 * s;
                const Rect tower{tx - 6 * s, cy - 42 * s, tx + 6 * s, cy - 30 * s};
                boxWalls(walls, tower, zb, zg + 48, zg, styles[4]);
                pyramid(roof2, tower, zg + 48, 22);
            }
            break;
        }
        case 2: // a rotunda with a copper dome and lantern
        {
            name = "rotunda";
            wallTex = styles[4].name;
            const double r = 26 * s;
            cylinder(walls, cx, cy, r, zb, zg + 18, 40, zg, styles[4]);
            roof.color = osg::Vec4(0.55f, 0.82f, 0.72f, 1.0f);
            dome(roof, cx, cy, r, zg + 18, 40, 10);
            cylinder(walls, cx, cy, 3.5, zg + 18 + r - 1, zg + 18 + r + 6, 12, zg, styles[4]);
            roof2Tex = "roof-gravel";
            roof2.color = osg::Vec4(0.55f, 0.82f, 0.72f, 1.0f);
            cone(roof2, cx, cy, 4.2, zg + 18 + r + 6, 6, 12);
            break;
        }
        default: // a round residential spire
        {
            name = "round-tower";
            wallTex = styles[5].name;
            const double r = 13 * s;
            cylinder(walls, cx, cy, r, zb, zg + 95, 32, zg, styles[5]);
            roof2Tex = "roof-tiles";
            cone(roof2, cx, cy, r + 1.0, zg + 95, 22, 32);
            break;
        }
        }
        osg::ref_ptr<osg::Group> f = feature(FeatureType::Building, "landmark", true);
        f->setUserValue("loa.landmark.kind", name);
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        osg::ref_ptr<osg::Geometry> w = walls.build("WallSurface");
        w->setStateSet(states.textured(wallTex));
        geode->addDrawable(w.get());
        if (!roof.empty())
        {
            osg::ref_ptr<osg::Geometry> rf = roof.build("RoofSurface");
            rf->setStateSet(states.textured(roofTex));
            geode->addDrawable(rf.get());
        }
        if (!roof2.empty())
        {
            osg::ref_ptr<osg::Geometry> rf = roof2.build("RoofSurface");
            rf->setStateSet(states.textured(roof2Tex));
            geode->addDrawable(rf.get());
        }
        f->addChild(geode.get());
        return f;
    }
};
} // namespace

osg::ref_ptr<osg::Group> CityGenerator::generate()
{
    Builder b(*this, _p, _layout);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->setName("DemoCity");
    root->setUserValue("loa.city.parameters", _p.toString());
    osg::StateSet* ss = root->getOrCreateStateSet();
    osg::ref_ptr<osg::Material> material = new osg::Material;
    material->setColorMode(osg::Material::AMBIENT_AND_DIFFUSE);
    material->setSpecular(osg::Material::FRONT_AND_BACK, osg::Vec4(0, 0, 0, 1));
    ss->setAttributeAndModes(material.get(), osg::StateAttribute::ON);
    ss->setAttributeAndModes(new osg::CullFace(osg::CullFace::BACK), osg::StateAttribute::ON);
    ss->setMode(GL_LIGHTING, osg::StateAttribute::ON);
    ss->setMode(GL_NORMALIZE, osg::StateAttribute::OFF);

    auto group = [&](const char* name)
    {
        osg::ref_ptr<osg::Group> g = new osg::Group;
        g->setName(name);
        root->addChild(g.get());
        return g;
    };
    osg::ref_ptr<osg::Group> terrainG = group("Terrain"), waterG = group("Water"),
                             streetsG = group("Streets"), greenG = group("GreenSpaces"),
                             buildingsG = group("Buildings");

    terrainG->addChild(b.terrain().get());
    if (_p.river) waterG->addChild(b.water().get());
    for (size_t i = 0; i < _layout.roadLinesX.size(); ++i)
        streetsG->addChild(b.street(false, i).get());
    for (size_t i = 0; i < _layout.roadLinesY.size(); ++i)
        streetsG->addChild(b.street(true, i).get());

    // Blocks: classify, then build row by row.
    const int nb = _p.blocksX * _p.blocksY;
    std::vector<Rect> rects(static_cast<size_t>(nb));
    std::vector<BlockKind> kinds(static_cast<size_t>(nb), BlockKind::Buildings);
    std::vector<int> available;
    const double corridor = _p.riverWidth / 2 + 22.0 + 4.0;
    for (int by = 0; by < _p.blocksY; ++by)
        for (int bx = 0; bx < _p.blocksX; ++bx)
        {
            const size_t i = static_cast<size_t>(by * _p.blocksX + bx);
            const auto X = static_cast<size_t>(bx), Y = static_cast<size_t>(by);
            const double wx0 = _layout.roadLineXMajor[X] ? _p.majorRoadWidth : _p.minorRoadWidth;
            const double wy0 = _layout.roadLineYMajor[Y] ? _p.majorRoadWidth : _p.minorRoadWidth;
            rects[i] = Rect{_layout.roadLinesX[X] + wx0 / 2, _layout.roadLinesY[Y] + wy0 / 2,
                            _layout.roadLinesX[X] + wx0 / 2 + _p.blockSize,
                            _layout.roadLinesY[Y] + wy0 / 2 + _p.blockSize};
            bool riverside = false;
            if (_p.river)
                for (double y = rects[i].y0; y <= rects[i].y1 + 1e-9 && !riverside; y += 5.0)
                {
                    const double rx = riverCenterX(y);
                    riverside = rx > rects[i].x0 - corridor && rx < rects[i].x1 + corridor;
                }
            if (riverside)
                kinds[i] = BlockKind::Riverside;
            else
                available.push_back(static_cast<int>(i));
        }
    // Landmarks: the most central free block first, the others at random; then quotas of
    // parks and forests (at least one each where the fraction is non-zero), at random.
    Random layoutRng(streamSeed(_p.seed, 2, 0));
    const double ccx = _layout.cityBounds.center().x(), ccy = _layout.cityBounds.center().y();
    auto centralityOf = [&](size_t i)
    {
        const double dx = (rects[i].cx() - ccx) / std::max(1.0, _layout.cityBounds.xMax() - ccx);
        const double dy = (rects[i].cy() - ccy) / std::max(1.0, _layout.cityBounds.yMax() - ccy);
        return std::clamp(1.0 - std::sqrt(dx * dx + dy * dy) / 1.4142, 0.0, 1.0);
    };
    std::stable_sort(available.begin(), available.end(),
                     [&](int a, int c)
                     { return centralityOf(static_cast<size_t>(a)) > centralityOf(static_cast<size_t>(c)); });
    for (size_t k = available.size(); k > 2; --k) // shuffle all but the most central
    {
        const size_t j = 1 + static_cast<size_t>(layoutRng.next() % (k - 1));
        std::swap(available[k - 1], available[j]);
    }
    size_t cursor = 0;
    auto take = [&](int count, BlockKind kind)
    {
        for (int k = 0; k < count && cursor < available.size(); ++k)
            kinds[static_cast<size_t>(available[cursor++])] = kind;
    };
    const int free = static_cast<int>(available.size());
    take(std::min(_p.landmarks, free), BlockKind::Landmark);
    auto quota = [&](double fraction)
    { return fraction <= 0.0 ? 0 : std::max(1, static_cast<int>(std::lround(fraction * free))); };
    take(quota(_p.parkFraction), BlockKind::Park);
    take(quota(_p.forestFraction), BlockKind::Forest);

    int landmarkIndex = 0, forestIndex = 0;
    static const char* forestTypes[3] = {"coniferous", "deciduous", "mixed"};
    for (int i = 0; i < nb; ++i)
    {
        const size_t k = static_cast<size_t>(i);
        Random rng(streamSeed(_p.seed, 3, k));
        switch (kinds[k])
        {
        case BlockKind::Riverside:
            break;
        case BlockKind::Park:
            greenG->addChild(b.greenSpace(rects[k], false, "park", rng).get());
            break;
        case BlockKind::Forest:
            greenG->addChild(b.greenSpace(rects[k], true, forestTypes[forestIndex++ % 3], rng).get());
            break;
        case BlockKind::Landmark:
            buildingsG->addChild(b.landmark(rects[k], landmarkIndex++).get());
            break;
        case BlockKind::Buildings:
            b.buildingBlock(buildingsG.get(), rects[k], centralityOf(k), rng);
            break;
        }
    }
    return root;
}

} // namespace osgLoA
