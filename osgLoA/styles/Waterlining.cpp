/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/Waterlining>

#include "../util/FeatureGroundRaster.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Image>
#include <osg/Transform>
#include <osg/TriangleFunctor>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace osgLoA
{

namespace
{
// Registers the style when the library is loaded, so that scenarios read before any water code
// runs can name it.
struct WaterliningRegistrar
{
    WaterliningRegistrar() { Waterlining::registerStyle(); }
} s_waterliningRegistrar;

} // namespace

osg::ref_ptr<GraphicStyle> Waterlining::create()
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName(name());
    s->setDescription("cartographic, with lines parallel to the shore inside water at widening intervals "
                      "(waterlining, paper 004 Figure 8A)");
    s->setFragmentShader("loa_style_waterlining.frag.glsl");
    osg::StateSet* p = s->getParameters();
    p->setName(std::string(name()) + " parameters");
    const Lines l;
    p->addUniform(new osg::Uniform("loa_waterlining_lineColor", osg::Vec3f(31, 120, 180) / 255.0f));
    p->addUniform(new osg::Uniform("loa_waterlining_spacing", l.spacing));
    p->addUniform(new osg::Uniform("loa_waterlining_exponent", l.exponent));
    p->addUniform(new osg::Uniform("loa_waterlining_count", l.count));
    p->addUniform(new osg::Uniform("loa_waterlining_width", l.width));
    p->addUniform(new osg::Uniform("loa_waterlining_fade", l.fade));
    p->addUniform(new osg::Uniform("loa_waterlining_shoreline", l.shoreline));
    return s;
}

void Waterlining::registerStyle()
{
    GraphicStyleCatalog::instance().add(*create());
}

double Waterlining::lineDistance(int k, const Lines& lines)
{
    return double(lines.spacing) * std::pow(double(k), double(std::max(lines.exponent, 1e-3f)));
}

double Waterlining::lineCoverage(double d, double pixelSize, const Lines& lines)
{
    if (!(d >= 0.0) || !(pixelSize > 0.0) || !(lines.spacing > 0.0f)) return 0.0;
    const double e = std::max(double(lines.exponent), 1e-3);
    const int count = std::max(lines.count, 0);
    const int k0 = int(std::lround(std::pow(d / lines.spacing, 1.0 / e)));
    double best = 0.0;
    for (int k = k0 - 1; k <= k0 + 1; ++k)
    {
        if (k < (lines.shoreline ? 0 : 1) || k > count) continue;
        const double dk = lineDistance(k, lines);
        const double strength =
            k == 0 ? 1.0 : 1.0 - double(lines.fade) * double(k - 1) / double(std::max(count - 1, 1));
        const double c = std::clamp(0.5 * lines.width + 0.5 - std::fabs(d - dk) / pixelSize, 0.0, 1.0);
        best = std::max(best, std::clamp(strength, 0.0, 1.0) * c);
    }
    return best;
}

float Waterlining::ShoreMap::sample(double x, double y) const
{
    if (!valid()) return std::numeric_limits<float>::infinity();
    return sampleBilinear(grid, distance, x, y);
}

Waterlining::ShoreMap Waterlining::computeShoreMap(osg::Node& model, int resolution, double minTexelSize)
{
    checkGridParameters("waterlining", resolution, minTexelSize);
    ShoreMap map;
    // The water features' triangles, and the terrain's: where the terrain lies above the water
    // surface the water is hidden, and the shore is where it emerges (a river's polygon reaches
    // under its banks).
    const FeatureTriangles waterTriangles = collectFeatureTriangles(model, FeatureType::Water);
    const std::vector<osg::Vec3d>& corners = waterTriangles.corners;
    const std::vector<osg::Vec3d> terrain = collectFeatureTriangles(model, FeatureType::Terrain).corners;
    map.waterFeatures = waterTriangles.features;
    map.triangles = unsigned(corners.size() / 3);
    if (corners.empty()) return map;
    // resolution - 2 texels across the footprint (no finer than minTexelSize), one land texel of
    // margin on each side.
    double extent = 0.0;
    map.grid = footprintGrid(corners, resolution, minTexelSize, &extent);
    if (!map.grid.valid()) return map;
    const DistanceField::Grid& g = map.grid;
    // The highest water and terrain surface at each texel centre (closed triangles: edges count),
    // interpolated in the triangle; -infinity where there is none.
    const double none = -std::numeric_limits<double>::infinity();
    std::vector<double> waterTop(std::size_t(g.width) * std::size_t(g.height), none), terrainTop(waterTop);
    rasterizeHeights(g, corners, true, waterTop);
    rasterizeHeights(g, terrain, true, terrainTop);
    // Water where a water surface lies at the texel and no terrain above it (by more than a
    // thousandth of the footprint: coplanar ground does not hide it).
    const double above = 1e-3 * extent;
    std::vector<unsigned char> water(waterTop.size(), 0);
    for (std::size_t i = 0; i < water.size(); ++i)
        water[i] = waterTop[i] > none && !(terrainTop[i] > waterTop[i] + above) ? 1 : 0;
    DistanceField::Seeds land(g.width, g.height);
    for (std::size_t i = 0; i < water.size(); ++i)
    {
        land.mask[i] = water[i] ? 0 : 1;
        map.waterTexels += water[i];
    }
    const DistanceField::Map exact = DistanceField::computeExact(land);
    map.distance.resize(exact.distance.size());
    for (std::size_t i = 0; i < exact.distance.size(); ++i)
        map.distance[i] = float(double(exact.distance[i]) * g.texelSize);
    return map;
}

osg::ref_ptr<osg::Texture2D> Waterlining::createTexture(const ShoreMap& map)
{
    return createGridTexture(map.grid, map.distance, "osgLoA waterlining shore distance", true);
}

Waterlining::ShoreMap Waterlining::attach(osg::Node& model, int resolution)
{
    ShoreMap map = computeShoreMap(model, resolution);
    if (!map.valid()) return map;
    osg::StateSet* ss = model.getOrCreateStateSet();
    ss->setTextureAttribute(kUnit, createTexture(map).get());
    ss->addUniform(new osg::Uniform("loa_waterDistance", int(kUnit)));
    ss->addUniform(new osg::Uniform("loa_waterDistanceTransform", map.grid.textureTransform()));
    ss->addUniform(new osg::Uniform("loa_hasWaterDistance", true));
    return map;
}

} // namespace osgLoA
