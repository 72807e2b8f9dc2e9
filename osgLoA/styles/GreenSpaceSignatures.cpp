/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/GreenSpaceSignatures>

#include "../util/FeatureGroundRaster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace osgLoA
{

namespace
{
struct SignaturesRegistrar
{
    SignaturesRegistrar() { GreenSpaceSignatures::registerStyle(); }
} s_signaturesRegistrar;

std::uint32_t pcg(std::uint32_t x)
{
    x = x * 747796405u + 2891336453u;
    const std::uint32_t w = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (w >> 22u) ^ w;
}

double circle(const osg::Vec2d& q, const osg::Vec2d& c, double r)
{
    return (q - c).length() - r;
}

double segment(const osg::Vec2d& q, const osg::Vec2d& a, const osg::Vec2d& b)
{
    const osg::Vec2d pa = q - a, ba = b - a;
    const double h = std::clamp((pa * ba) / (ba * ba), 0.0, 1.0);
    return (pa - ba * h).length();
}

double capsule(const osg::Vec2d& q, const osg::Vec2d& a, const osg::Vec2d& b, double r)
{
    return segment(q, a, b) - r;
}

/** Exact signed distance to a counter-clockwise triangle. */
double triangle(const osg::Vec2d& q, const osg::Vec2d& a, const osg::Vec2d& b, const osg::Vec2d& c)
{
    const double d = std::min({segment(q, a, b), segment(q, b, c), segment(q, c, a)});
    auto side = [&](const osg::Vec2d& p0, const osg::Vec2d& p1)
    { return (p1.x() - p0.x()) * (q.y() - p0.y()) - (p1.y() - p0.y()) * (q.x() - p0.x()); };
    const bool inside = side(a, b) >= 0.0 && side(b, c) >= 0.0 && side(c, a) >= 0.0;
    return inside ? -d : d;
}
} // namespace

osg::ref_ptr<GraphicStyle> GreenSpaceSignatures::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with map symbols of the vegetation kind bombed over green spaces, "
                      "upright and of constant size on screen (green-space signatures, paper 004 "
                      "Figure 8B)");
    s->setFragmentShader("loa_style_signatures.frag.glsl");
    osg::StateSet* ss = s->getParameters();
    ss->setName(std::string(name()) + " parameters");
    const Parameters p;
    ss->addUniform(new osg::Uniform("loa_signatures_cellPixels", p.cellPixels));
    ss->addUniform(new osg::Uniform("loa_signatures_symbolPixels", p.symbolPixels));
    ss->addUniform(new osg::Uniform("loa_signatures_jitter", p.jitter));
    ss->addUniform(new osg::Uniform("loa_signatures_minUp", p.minUp));
    ss->addUniform(new osg::Uniform("loa_signatures_vegetationHeight", p.vegetationHeight));
    // ColorBrewer Greens: the darkest for ink, lighter fills per symbol.
    ss->addUniform(new osg::Uniform("loa_signatures_ink", osg::Vec3f(0, 68, 27) / 255.0f));
    osg::ref_ptr<osg::Uniform> fill =
        new osg::Uniform(osg::Uniform::FLOAT_VEC3, "loa_signatures_fill", SYMBOL_COUNT);
    const osg::Vec3f fills[SYMBOL_COUNT] = {osg::Vec3f(0, 0, 0),      osg::Vec3f(116, 196, 118),
                                            osg::Vec3f(35, 139, 69),  osg::Vec3f(116, 196, 118),
                                            osg::Vec3f(65, 171, 93),  osg::Vec3f(161, 217, 155),
                                            osg::Vec3f(116, 196, 118)};
    for (unsigned i = 0; i < SYMBOL_COUNT; ++i)
        fill->setElement(i, fills[i] / 255.0f);
    ss->addUniform(fill.get());
    osg::ref_ptr<osg::Uniform> symbols =
        new osg::Uniform(osg::Uniform::INT, "loa_signatures_symbols", FeatureSubType::kCount);
    const std::vector<std::string>& names = FeatureSubType::names();
    for (unsigned i = 0; i < unsigned(FeatureSubType::kCount); ++i)
        symbols->setElement(i, int(symbolOf(names[i])));
    ss->addUniform(symbols.get());
    return s;
}

void GreenSpaceSignatures::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

GreenSpaceSignatures::Symbol GreenSpaceSignatures::symbolOf(const std::string& subType)
{
    const int code = FeatureSubType::code(subType);
    const std::string& s = FeatureSubType::names()[std::size_t(code)];
    // "" and words the table does not know share code 0 in the shader: a green space nobody
    // described (or described in other words) gets grass.
    if (code == 0) return GRASS;
    if (s == "deciduous") return DECIDUOUS;
    if (s == "coniferous") return CONIFEROUS;
    if (s == "mixed" || s == "forest" || s == "wood" || s == "nature_reserve") return MIXED;
    if (s == "orchard" || s == "vineyard") return ORCHARD;
    if (s == "scrub" || s == "heath") return SCRUB;
    for (const char* g : {"park", "grass", "meadow", "garden", "village_green", "recreation_ground",
                          "cemetery", "allotments", "grassland", "pitch", "golf_course", "playground"})
        if (s == g) return GRASS;
    return NONE;
}

std::uint32_t GreenSpaceSignatures::hash(int cx, int cy, int level, std::uint32_t salt)
{
    const std::uint32_t l = pcg(std::uint32_t(level + 64) * 83492791u ^ salt);
    const std::uint32_t y = pcg(std::uint32_t(cy) * 19349663u ^ l);
    return pcg(std::uint32_t(cx) * 73856093u ^ y);
}

double GreenSpaceSignatures::unit(std::uint32_t h)
{
    return double(h >> 8u) / 16777216.0;
}

osg::Vec2d GreenSpaceSignatures::anchor(int cx, int cy, int level, double jitter)
{
    const double s = std::ldexp(1.0, level);
    const double u = unit(hash(cx, cy, level, 1u)), v = unit(hash(cx, cy, level, 2u));
    return osg::Vec2d((cx + 0.5 + jitter * (u - 0.5)) * s, (cy + 0.5 + jitter * (v - 0.5)) * s);
}

GreenSpaceSignatures::Symbol GreenSpaceSignatures::cellSymbol(Symbol featureSymbol, int cx, int cy, int level)
{
    if (featureSymbol == MIXED) return unit(hash(cx, cy, level, 4u)) < 0.5 ? DECIDUOUS : CONIFEROUS;
    if (featureSymbol == ORCHARD) return DECIDUOUS;
    return featureSymbol;
}

int GreenSpaceSignatures::level(double sigma, const Parameters& p)
{
    const double l = std::ceil(std::log2(std::max(double(p.cellPixels) * sigma, 1e-30)));
    return int(std::clamp(l, -40.0, 40.0));
}

double GreenSpaceSignatures::visibleFraction(double cellOnScreen, const Parameters& p)
{
    const double c = p.cellPixels, s = cellOnScreen;
    if (!(c > 0.0) || !(s > c) || s >= 4.0 * c) return 0.0;
    return s <= 2.0 * c ? (s - c) / c : (4.0 * c - s) / (2.0 * c);
}

double GreenSpaceSignatures::symbolSize(const Parameters& p)
{
    return std::max(1.0, std::min(double(p.symbolPixels), 2.0 * double(p.cellPixels) - 1.5));
}

int GreenSpaceSignatures::reachCells(double cellOnScreen, const Parameters& p)
{
    return int(std::ceil((symbolSize(p) + 1.5) / cellOnScreen));
}

double GreenSpaceSignatures::presence(double f, double u)
{
    return std::clamp((1.1 * f - u) / 0.1, 0.0, 1.0);
}

double GreenSpaceSignatures::symbolDistance(Symbol symbol, const osg::Vec2d& q, bool& inkOnly)
{
    const double inf = std::numeric_limits<double>::infinity();
    double fill = inf, ink = inf;
    switch (symbol)
    {
    case DECIDUOUS:
    case ORCHARD:
        fill = circle(q, osg::Vec2d(0.0, 0.64), 0.34);
        ink = capsule(q, osg::Vec2d(0.0, 0.02), osg::Vec2d(0.0, 0.34), 0.06);
        break;
    case CONIFEROUS:
        fill = triangle(q, osg::Vec2d(-0.3, 0.22), osg::Vec2d(0.3, 0.22), osg::Vec2d(0.0, 0.98));
        ink = capsule(q, osg::Vec2d(0.0, 0.02), osg::Vec2d(0.0, 0.24), 0.06);
        break;
    case GRASS:
        for (const osg::Vec2d& tip : {osg::Vec2d(-0.28, 0.5), osg::Vec2d(0.0, 0.62), osg::Vec2d(0.28, 0.5)})
            ink = std::min(ink, capsule(q, osg::Vec2d(0.0, 0.04), tip, 0.05));
        break;
    case SCRUB:
        fill = std::min({circle(q, osg::Vec2d(-0.2, 0.24), 0.2), circle(q, osg::Vec2d(0.2, 0.24), 0.2),
                         circle(q, osg::Vec2d(0.0, 0.42), 0.22)});
        break;
    default:
        break;
    }
    inkOnly = ink < fill;
    return std::min(fill, ink);
}

GreenSpaceSignatures::Sample GreenSpaceSignatures::sample(Symbol featureSymbol, const osg::Vec3d& p,
                                                          const osg::Vec3d& normal, const osg::Vec2d& pixel,
                                                          double sigma, const Projector& project,
                                                          const Parameters& params, const GroundMap* ground)
{
    Sample best;
    osg::Vec3d n = normal;
    if (!(n.normalize() > 0.0)) return best;
    if (n.z() < 0.0) n = -n;
    if (featureSymbol == NONE || n.z() < params.minUp || !(sigma > 0.0)) return best;
    if (ground && !(ground->at(p.x(), p.y()) > -1.0e29f)) return best; // no green ground here
    const double size = symbolSize(params);
    const double jitter = featureSymbol == ORCHARD ? 0.0 : std::clamp(double(params.jitter), 0.0, 1.0);
    const int l0 = level(sigma, params);
    double bestY = std::numeric_limits<double>::infinity();
    for (int l = l0; l <= l0 + 1; ++l)
    {
        const double s = std::ldexp(1.0, l);
        const double f = visibleFraction(s / sigma, params);
        if (f <= 0.0) continue;
        const int bx = int(std::floor(p.x() / s)), by = int(std::floor(p.y() / s));
        const int r = reachCells(s / sigma, params);
        for (int j = -r; j <= r; ++j)
            for (int i = -r; i <= r; ++i)
            {
                const int cx = bx + i, cy = by + j;
                const double pres = presence(f, unit(hash(cx, cy, l, 3u)));
                const Symbol sym = cellSymbol(featureSymbol, cx, cy, l);
                if (pres <= 0.0 || sym == NONE) continue;
                const osg::Vec2d a = anchor(cx, cy, l, jitter);
                const float g = ground ? ground->at(a.x(), a.y()) : GroundMap::kNoGround;
                const double z = g > -1.0e29f ? double(g) : p.z();
                const osg::Vec3d w = project(osg::Vec3d(a.x(), a.y(), z));
                bool inkOnly = false;
                const double d =
                    symbolDistance(sym, osg::Vec2d(pixel.x() - w.x(), pixel.y() - w.y()) / size, inkOnly) *
                    size;
                const double alpha = std::clamp(0.5 - d, 0.0, 1.0) * pres;
                if (alpha <= 0.0 || !(w.y() < bestY)) continue;
                bestY = w.y();
                best.alpha = alpha;
                best.ink = inkOnly ? 1.0 : std::clamp(d + 1.5, 0.0, 1.0);
                best.symbol = sym;
                best.anchor = a;
            }
    }
    return best;
}

float GreenSpaceSignatures::GroundMap::at(double x, double y) const
{
    if (!valid()) return kNoGround;
    const osg::Vec2d t = grid.worldToTexel(osg::Vec2d(x, y));
    const int i = std::clamp(int(std::floor(t.x())), 0, grid.width - 1);
    const int j = std::clamp(int(std::floor(t.y())), 0, grid.height - 1);
    return height[std::size_t(j) * std::size_t(grid.width) + std::size_t(i)];
}

GreenSpaceSignatures::GroundMap GreenSpaceSignatures::computeGroundMap(osg::Node& model, int resolution,
                                                                       double minTexelSize)
{
    checkGridParameters("signatures", resolution, minTexelSize);
    GroundMap map;
    FeatureTriangles green = collectFeatureTriangles(model, FeatureType::Green);
    // Ground faces up: only triangles whose (winding) normal rises at most 45 degrees from the
    // vertical make the map, so a crown's underside is not taken for ground, and a green feature
    // that is a tree alone (no ground geometry) keeps its crown top as its "ground" and is drawn.
    {
        std::vector<osg::Vec3d> up;
        for (std::size_t t = 0; t + 2 < green.corners.size(); t += 3)
        {
            const osg::Vec3d n =
                (green.corners[t + 1] - green.corners[t]) ^ (green.corners[t + 2] - green.corners[t]);
            if (n.z() >= 0.7071 * n.length())
                up.insert(up.end(), green.corners.begin() + std::ptrdiff_t(t),
                          green.corners.begin() + std::ptrdiff_t(t + 3));
        }
        green.corners.swap(up);
    }
    map.greenFeatures = green.features;
    map.triangles = unsigned(green.corners.size() / 3);
    if (green.corners.empty()) return map;
    map.grid = footprintGrid(green.corners, resolution, minTexelSize);
    if (!map.grid.valid()) return map;
    const double none = std::numeric_limits<double>::infinity();
    std::vector<double> lowest(std::size_t(map.grid.width) * std::size_t(map.grid.height), none);
    rasterizeHeights(map.grid, green.corners, false, lowest);
    map.height.resize(lowest.size());
    for (std::size_t i = 0; i < lowest.size(); ++i)
    {
        const bool covered = lowest[i] < none;
        map.height[i] = covered ? float(lowest[i]) : GroundMap::kNoGround;
        map.groundTexels += covered ? 1u : 0u;
    }
    return map;
}

GreenSpaceSignatures::GroundMap GreenSpaceSignatures::attach(osg::Node& model, int resolution)
{
    GroundMap map = computeGroundMap(model, resolution);
    if (!map.valid()) return map;
    osg::StateSet* ss = model.getOrCreateStateSet();
    ss->setTextureAttribute(
        kUnit, createGridTexture(map.grid, map.height, "osgLoA green-space ground", false).get());
    ss->addUniform(new osg::Uniform("loa_greenGround", int(kUnit)));
    ss->addUniform(new osg::Uniform("loa_greenGroundTransform", map.grid.textureTransform()));
    ss->addUniform(new osg::Uniform("loa_hasGreenGround", true));
    ss->addUniform(new osg::Uniform("loa_greenGroundTexel", float(map.grid.texelSize)));
    return map;
}

} // namespace osgLoA
