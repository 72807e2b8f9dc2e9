/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StreetLabels>
#include <osgLoA/styles/StreetPresentation>

#include "../util/FeatureGroundRaster.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace osgLoA
{

namespace
{
struct StreetsRegistrar
{
    StreetsRegistrar() { StreetPresentation::registerStyle(); }
} s_streetsRegistrar;

bool oneOf(const std::string& s, std::initializer_list<const char*> words)
{
    for (const char* w : words)
        if (s == w) return true;
    return false;
}
} // namespace

osg::ref_ptr<GraphicStyle> StreetPresentation::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with streets as on a road map: major, minor, path and rail classes "
                      "(from the model's sub-types, else the width) in their colours with casings along "
                      "their edges, wider for more important roads");
    s->setFragmentShader("loa_style_streets.frag.glsl");
    osg::StateSet* ss = s->getParameters();
    ss->setName(std::string(name()) + " parameters");
    const Parameters p;
    ss->addUniform(new osg::Uniform("loa_streets_majorWidth", p.majorWidth));
    ss->addUniform(new osg::Uniform("loa_streets_minorWidth", p.minorWidth));
    // Fills and casings per class (major, minor, path, rail): ColorBrewer Set3 orange and light
    // yellow, Set3 grey, greys; casings of OrRd / greys.
    const osg::Vec3f fill[CLASS_COUNT] = {osg::Vec3f(253, 180, 98), osg::Vec3f(255, 255, 179),
                                          osg::Vec3f(217, 217, 217), osg::Vec3f(150, 150, 150)};
    const osg::Vec3f casing[CLASS_COUNT] = {osg::Vec3f(179, 88, 6), osg::Vec3f(140, 140, 140),
                                            osg::Vec3f(140, 140, 140), osg::Vec3f(82, 82, 82)};
    const float casingPixels[CLASS_COUNT] = {2.0f, 1.0f, 0.0f, 1.0f};
    osg::ref_ptr<osg::Uniform> f =
        new osg::Uniform(osg::Uniform::FLOAT_VEC3, "loa_streets_fill", CLASS_COUNT);
    osg::ref_ptr<osg::Uniform> c =
        new osg::Uniform(osg::Uniform::FLOAT_VEC3, "loa_streets_casing", CLASS_COUNT);
    osg::ref_ptr<osg::Uniform> w =
        new osg::Uniform(osg::Uniform::FLOAT, "loa_streets_casingPixels", CLASS_COUNT);
    for (unsigned i = 0; i < CLASS_COUNT; ++i)
    {
        f->setElement(i, fill[i] / 255.0f);
        c->setElement(i, casing[i] / 255.0f);
        w->setElement(i, casingPixels[i]);
    }
    ss->addUniform(f.get());
    ss->addUniform(c.get());
    ss->addUniform(w.get());
    // The class each sub-type code names (classOf without a width; -1: by the width).
    osg::ref_ptr<osg::Uniform> classes =
        new osg::Uniform(osg::Uniform::INT, "loa_streets_classOf", FeatureSubType::kCount);
    const std::vector<std::string>& names = FeatureSubType::names();
    for (unsigned i = 0; i < unsigned(FeatureSubType::kCount); ++i)
        classes->setElement(i, int(classOf(names[i], 0.0)));
    ss->addUniform(classes.get());
    // The label layer: street names along the centre lines (StreetLabels).
    StreetLabels::addUniforms(*s);
    return s;
}

void StreetPresentation::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

StreetPresentation::RoadClass StreetPresentation::classOf(const std::string& subType, double width,
                                                          const Parameters& p)
{
    std::string s(subType);
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    if (oneOf(s, {"major", "motorway", "trunk", "primary", "secondary"})) return MAJOR;
    if (oneOf(s, {"minor", "tertiary", "residential", "unclassified", "service", "living_street"}))
        return MINOR;
    if (oneOf(s, {"path", "footway", "cycleway", "pedestrian", "steps", "bridleway", "track"})) return PATH;
    if (oneOf(s, {"rail", "railway", "tram", "light_rail"})) return RAIL;
    if (!(width > 0.0)) return UNKNOWN;
    return width >= p.majorWidth ? MAJOR : width >= p.minorWidth ? MINOR : PATH;
}

StreetPresentation::RoadClass StreetPresentation::classOf(const std::string& subType, double width)
{
    return classOf(subType, width, Parameters());
}

double StreetPresentation::casingCoverage(double d, double pixelSize, double casingPixels)
{
    if (!(casingPixels > 0.0) || !(pixelSize > 0.0) || std::isnan(d)) return 0.0;
    // A street fragment whose map value is below 0 lies on the edge, within the map's
    // interpolation: full casing.
    return std::clamp(casingPixels + 0.5 - std::max(d, 0.0) / pixelSize, 0.0, 1.0);
}

float StreetPresentation::StreetMap::sample(double x, double y) const
{
    if (!valid()) return 0.0f;
    return sampleBilinear(grid, distance, x, y);
}

StreetPresentation::StreetMap StreetPresentation::computeStreetMap(osg::Node& model, int resolution,
                                                                   double minTexelSize)
{
    checkGridParameters("streets", resolution, minTexelSize);
    StreetMap map;
    const FeatureTriangles streets = collectFeatureTriangles(model, FeatureType::Street);
    map.streetFeatures = streets.features;
    map.triangles = unsigned(streets.corners.size() / 3);
    if (streets.corners.empty()) return map;
    map.grid = footprintGrid(streets.corners, resolution, minTexelSize);
    if (!map.grid.valid()) return map;
    const DistanceField::Grid& g = map.grid;
    const double none = -std::numeric_limits<double>::infinity();
    const std::size_t texels = std::size_t(g.width) * std::size_t(g.height);
    std::vector<double> top(texels, none);
    rasterizeHeights(g, streets.corners, true, top);
    DistanceField::Seeds outside(g.width, g.height);
    for (std::size_t i = 0; i < texels; ++i)
    {
        const bool street = top[i] > none;
        outside.mask[i] = street ? 0 : 1;
        map.streetTexels += street ? 1u : 0u;
    }
    // Signed: street texels the distance to the nearest outside texel, outside texels minus the
    // distance to the nearest street texel, each less half a texel, so that the edge lies at 0
    // between the two texel centres and a GL_LINEAR fetch finds it (an unsigned map measured from
    // texel centres put the edge half a texel out, wider than a 1-pixel casing when zoomed in).
    DistanceField::Seeds inside(g.width, g.height);
    for (std::size_t i = 0; i < texels; ++i)
        inside.mask[i] = outside.mask[i] ? 0 : 1;
    const DistanceField::Map toOutside = DistanceField::computeExact(outside);
    const DistanceField::Map toInside = DistanceField::computeExact(inside);
    map.distance.resize(texels);
    for (std::size_t i = 0; i < texels; ++i)
        map.distance[i] = float(outside.mask[i] ? -(double(toInside.distance[i]) - 0.5) * g.texelSize
                                                : (double(toOutside.distance[i]) - 0.5) * g.texelSize);
    // Each street's width: its own texels' 90th-percentile distance, / 0.9, times 2 (one
    // coverage grid, scanned and reset in each street's texel window only).
    std::vector<double> mine(texels, none);
    for (std::size_t k = 0; k < streets.parts.size(); ++k)
    {
        const std::size_t end =
            k + 1 < streets.parts.size() ? streets.parts[k + 1].begin : streets.corners.size();
        const std::vector<osg::Vec3d> own(streets.corners.begin() + std::ptrdiff_t(streets.parts[k].begin),
                                          streets.corners.begin() + std::ptrdiff_t(end));
        int i0 = g.width, i1 = -1, j0 = g.height, j1 = -1;
        for (const osg::Vec3d& c : own)
        {
            const osg::Vec2d t = g.worldToTexel(osg::Vec2d(c.x(), c.y()));
            i0 = std::min(i0, std::max(0, int(std::floor(t.x())) - 1));
            i1 = std::max(i1, std::min(g.width - 1, int(std::ceil(t.x())) + 1));
            j0 = std::min(j0, std::max(0, int(std::floor(t.y())) - 1));
            j1 = std::max(j1, std::min(g.height - 1, int(std::ceil(t.y())) + 1));
        }
        rasterizeHeights(g, own, true, mine);
        std::vector<float> d;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
            {
                double& cell = mine[std::size_t(j) * std::size_t(g.width) + std::size_t(i)];
                if (cell > none)
                    d.push_back(map.distance[std::size_t(j) * std::size_t(g.width) + std::size_t(i)]);
                cell = none;
            }
        float width = 0.0f;
        if (!d.empty())
        {
            const std::size_t q = std::min(d.size() - 1, std::size_t(0.9 * double(d.size())));
            std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(q), d.end());
            width = float(2.0 * double(d[q]) / 0.9);
        }
        map.widths.emplace_back(streets.parts[k].node, width);
    }
    return map;
}

StreetPresentation::StreetMap StreetPresentation::attach(osg::Node& model, int resolution)
{
    StreetMap map = computeStreetMap(model, resolution);
    if (!map.valid()) return map;
    osg::StateSet* ss = model.getOrCreateStateSet();
    ss->setTextureAttribute(
        kUnit, createGridTexture(map.grid, map.distance, "osgLoA street edge distance", true).get());
    ss->addUniform(new osg::Uniform("loa_streetDistance", int(kUnit)));
    ss->addUniform(new osg::Uniform("loa_streetDistanceTransform", map.grid.textureTransform()));
    ss->addUniform(new osg::Uniform("loa_hasStreetDistance", true));
    for (const auto& w : map.widths)
        if (w.first.valid())
            w.first->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_streetWidth", w.second));
    return map;
}

} // namespace osgLoA
