// The relief presentation drawn through the LoA pipeline (paper 004 Figure 8D; osgLoA::
// ReliefPresentation): on planes of known gradient the hachures run along the analytic direction
// of steepest descent and the form lines across it (structure tensor of the ink), shaded slopes
// carry more ink, flat ground none; at 1920x1080, an odd size and in an offset viewport. On the
// demo city's hills the style differs from flat cartographic on terrain only; on a real terrain
// tile (San Francisco's Telegraph Hill, a GeoTIFF DEM from Debian's python-osmnx-doc) the
// hachures follow the DEM's slopes.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ReliefPresentation>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageFile>

#include <osg/ComputeBoundsVisitor>
#include <osg/Geometry>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

using namespace osgLoA;

namespace
{
using loatest::Viewport;

/** The plane z = a x + b y over [x0, x1] x [y0, y1] as a terrain feature. */
osg::ref_ptr<osg::Node> plane(double a, double b, double x0, double y0, double x1, double y1)
{
    return loatest::asFeature(loatest::planeQuad(x0, y0, x1, y1, a, b).get(), 1, FeatureType::Terrain);
}

/** Registers relief variants once: hachures only, form lines only. */
void registerVariants()
{
    static bool done = false;
    if (done) return;
    done = true;
    osg::ref_ptr<GraphicStyle> hachures = ReliefPresentation::create();
    hachures->setName("test-relief-hachures");
    hachures->getParameter("loa_relief_contourInterval")->set(0.0f);
    GraphicStyleCatalog::instance().add(*hachures);
    osg::ref_ptr<GraphicStyle> forms = ReliefPresentation::create();
    forms->setName("test-relief-forms");
    forms->getParameter("loa_relief_minSlope")->set(10.0f);
    forms->getParameter("loa_relief_maxSlope")->set(20.0f);
    GraphicStyleCatalog::instance().add(*forms);
}

void keep(const osg::Image& image, const std::string& name)
{
    loatest::keepFrame("relief", image, name);
}

double luma(const osg::Image& img, int x, int y)
{
    const unsigned char* p = img.data(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

struct Ink
{
    double share = 0.0;       ///< pixels with ink (darker than the flat frame by > 8/255), of those compared
    double strokeAngle = 0.0; ///< degrees in [0, 180): the dominant direction the ink runs along
    double coherence = 0.0;   ///< (l1 - l2) / (l1 + l2) of the ink's structure tensor
};

/** Ink = the flat frame's luma minus the styled frame's, over the viewport's inner pixels. Its
 *  orientation comes from the structure tensor of the ink smoothed by a Gaussian of sigma 2 px:
 *  central differences of 1-2 px wide lines straight on the pixel grid read their staircase
 *  (form lines at 108.4 degrees measured 119.4 unsmoothed). */
Ink inkOf(const osg::Image& styled, const osg::Image& flat, const Viewport& vp)
{
    Ink ink;
    const int w = vp.w, h = vp.h, r = 6;
    std::vector<double> raw(std::size_t(w) * h), tmp(raw.size()), smooth(raw.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            raw[std::size_t(y) * w + x] = luma(flat, vp.x + x, vp.y + y) - luma(styled, vp.x + x, vp.y + y);
    double kernel[2 * r + 1], sum = 0.0;
    for (int i = -r; i <= r; ++i)
        sum += kernel[i + r] = std::exp(-0.5 * i * i / 4.0);
    for (double& k : kernel)
        k /= sum;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            double v = 0.0;
            for (int i = -r; i <= r; ++i)
                v += kernel[i + r] * raw[std::size_t(y) * w + std::clamp(x + i, 0, w - 1)];
            tmp[std::size_t(y) * w + x] = v;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            double v = 0.0;
            for (int i = -r; i <= r; ++i)
                v += kernel[i + r] * tmp[std::size_t(std::clamp(y + i, 0, h - 1)) * w + x];
            smooth[std::size_t(y) * w + x] = v;
        }
    auto at = [&](int x, int y) { return smooth[std::size_t(y) * w + x]; };
    double jxx = 0, jyy = 0, jxy = 0;
    long inked = 0, total = 0;
    for (int y = r; y < h - r; ++y)
        for (int x = r; x < w - r; ++x)
        {
            ++total;
            if (raw[std::size_t(y) * w + x] > 8.0) ++inked;
            const double gx = at(x + 1, y) - at(x - 1, y), gy = at(x, y + 1) - at(x, y - 1);
            jxx += gx * gx;
            jyy += gy * gy;
            jxy += gx * gy;
        }
    ink.share = total ? double(inked) / total : 0.0;
    // The ink's gradients are across its strokes: the strokes run perpendicular to the tensor's
    // major eigenvector.
    const double gradient = 0.5 * std::atan2(2.0 * jxy, jxx - jyy);
    double stroke = (gradient + 0.5 * M_PI) * 180.0 / M_PI;
    stroke = std::fmod(std::fmod(stroke, 180.0) + 180.0, 180.0);
    ink.strokeAngle = stroke;
    const double root = std::sqrt((jxx - jyy) * (jxx - jyy) + 4.0 * jxy * jxy);
    ink.coherence = (jxx + jyy) > 0 ? root / (jxx + jyy) : 0.0;
    return ink;
}

/** |a - b| between undirected angles in degrees. */
double angleBetween(double a, double b)
{
    double d = std::fabs(std::fmod(a - b, 180.0));
    return std::min(d, 180.0 - d);
}

void expectStrokesAlongTheGradient(int width, int height, const Viewport& vp)
{
    registerVariants();
    const std::string label =
        std::to_string(width) + "x" + std::to_string(height) + (vp.x || vp.y ? " (viewport offset)" : "");
    const double a = 0.3, b = 0.1; // z = 0.3 x + 0.1 y: descent towards -(0.3, 0.1), 198.4 degrees
    const double aspect = double(vp.w) / vp.h;
    const osg::BoundingBoxd view(-40 * aspect, -40, 0, 40 * aspect, 40, 0);
    const double extent = 60 * aspect;
    osg::ref_ptr<osg::Node> slope = plane(a, b, -extent, -60, extent, 60);
    const osg::Vec2d down = ReliefPresentation::downhill(osg::Vec3d(-a, -b, 1));
    const double descent = std::fmod(std::atan2(down.y(), down.x()) * 180.0 / M_PI + 360.0, 180.0);

    osg::ref_ptr<osg::Image> flat = loatest::topDown(slope.get(), "cartographic", width, height, vp, view);
    osg::ref_ptr<osg::Image> hachures =
        loatest::topDown(slope.get(), "test-relief-hachures", width, height, vp, view);
    osg::ref_ptr<osg::Image> forms =
        loatest::topDown(slope.get(), "test-relief-forms", width, height, vp, view);
    osg::ref_ptr<osg::Image> relief = loatest::topDown(slope.get(), "relief", width, height, vp, view);
    const Ink h = inkOf(*hachures, *flat, vp), f = inkOf(*forms, *flat, vp);
    std::cout << "relief " << label << ": descent " << descent << " deg; hachures along " << h.strokeAngle
              << " deg (coherence " << h.coherence << ", ink " << 100 * h.share << " %); form lines along "
              << f.strokeAngle << " deg (coherence " << f.coherence << ", ink " << 100 * f.share << " %)\n";
    if (width == 1920)
    {
        keep(*relief, "plane-1920x1080");
        keep(*forms, "plane-forms-1920x1080");
        keep(*flat, "plane-flat-1920x1080");
    }
    // Hachures run along the direction of steepest descent, form lines across it.
    EXPECT_LT(angleBetween(h.strokeAngle, descent), 5.0) << label;
    EXPECT_GT(h.coherence, 0.3) << label;
    EXPECT_LT(angleBetween(f.strokeAngle, descent + 90.0), 3.0) << label;
    EXPECT_GT(f.coherence, 0.8) << label;
    // Slope 0.316 (density 0.73 of the cells): strokes of 1-2.5 px every ~14 px.
    EXPECT_GT(h.share, 0.02) << label;
    EXPECT_LT(h.share, 0.3) << label;
    EXPECT_GT(f.share, 0.005) << label;
}

/** A real terrain tile: a GeoTIFF DEM read through OSG's gdal plugin ("FILE.gdal"), its valid
 *  samples (the border of no-data, -32768, left out) as a grid mesh in metres (x east, y north,
 *  z the height; 1 arc second = 30.9 m north, 30.9 cos(latitude) m east), one terrain feature.
 *  `height(x, y)` samples it bilinearly (NaN outside). */
struct DemTile
{
    osg::ref_ptr<osg::Node> node;
    int columns = 0, rows = 0;
    double dx = 0.0, dy = 0.0;
    std::vector<double> z; ///< rows x columns, row 0 south
    double height(double x, double y) const
    {
        const double u = x / dx, v = y / dy;
        if (!(u >= 0.0 && v >= 0.0 && u <= columns - 1 && v <= rows - 1)) return std::nan("");
        const int i = std::min(int(u), columns - 2), j = std::min(int(v), rows - 2);
        const double fu = u - i, fv = v - j;
        auto at = [&](int c, int r) { return z[std::size_t(r) * columns + c]; };
        return (1 - fv) * ((1 - fu) * at(i, j) + fu * at(i + 1, j)) +
               fv * ((1 - fu) * at(i, j + 1) + fu * at(i + 1, j + 1));
    }
};

DemTile demTile(const std::string& path)
{
    DemTile t;
    osg::ref_ptr<osg::HeightField> hf = osgDB::readRefHeightFieldFile(path + ".gdal");
    if (!hf) return t;
    // The largest inner rectangle without no-data: the tile's one-sample border.
    int c0 = 0, c1 = int(hf->getNumColumns()) - 1, r0 = 0, r1 = int(hf->getNumRows()) - 1;
    auto valid = [&](int c, int r) { return hf->getHeight(unsigned(c), unsigned(r)) > -1000.0f; };
    auto colValid = [&](int c)
    {
        for (int r = r0; r <= r1; ++r)
            if (!valid(c, r)) return false;
        return true;
    };
    auto rowValid = [&](int r)
    {
        for (int c = c0; c <= c1; ++c)
            if (!valid(c, r)) return false;
        return true;
    };
    for (bool changed = true; changed && c0 < c1 && r0 < r1;)
    {
        changed = false;
        if (!colValid(c0)) ++c0, changed = true;
        if (!colValid(c1)) --c1, changed = true;
        if (!rowValid(r0)) ++r0, changed = true;
        if (!rowValid(r1)) --r1, changed = true;
    }
    t.columns = c1 - c0 + 1;
    t.rows = r1 - r0 + 1;
    const double lat = hf->getOrigin().y() + 0.5 * hf->getNumRows() * hf->getYInterval();
    t.dy = hf->getYInterval() * 111132.0;
    t.dx = hf->getXInterval() * 111320.0 * std::cos(lat * M_PI / 180.0);
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
            t.z.push_back(hf->getHeight(unsigned(c), unsigned(r)));
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.columns; ++c)
        {
            auto at = [&](int cc, int rr) {
                return t.z[std::size_t(std::clamp(rr, 0, t.rows - 1)) * t.columns +
                           std::clamp(cc, 0, t.columns - 1)];
            };
            v->push_back(osg::Vec3(float(c * t.dx), float(r * t.dy), float(at(c, r))));
            osg::Vec3 normal(float(-(at(c + 1, r) - at(c - 1, r)) / (2.0 * t.dx)),
                             float(-(at(c, r + 1) - at(c, r - 1)) / (2.0 * t.dy)), 1.0f);
            normal.normalize();
            n->push_back(normal);
        }
    g->setVertexArray(v.get());
    g->setNormalArray(n.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::Vec4Array> col = new osg::Vec4Array;
    col->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(col.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::DrawElementsUInt> tris = new osg::DrawElementsUInt(GL_TRIANGLES);
    for (int r = 0; r + 1 < t.rows; ++r)
        for (int c = 0; c + 1 < t.columns; ++c)
        {
            const unsigned a = unsigned(r * t.columns + c), b = a + 1, d = a + unsigned(t.columns), e = d + 1;
            for (unsigned i : {a, b, e, a, e, d})
                tris->push_back(i);
        }
    g->addPrimitiveSet(tris.get());
    t.node = loatest::asFeature(g.get(), 1, FeatureType::Terrain);
    return t;
}

/** Differing pixels lie on terrain only (the mask style's magenta, grown by 2 px), and more than
 *  minShare of the terrain pixels get ink. */
void expectDifferenceOnTerrainOnly(const std::string& name, osg::Node* model, int width, int height,
                                   double minShare)
{
    registerVariants();
    const loatest::MaskedDifference d = loatest::differenceInMask(
        model, "relief", "cartographic", loatest::typeMaskStyle(FeatureType::Terrain), width, height,
        "relief", name);
    EXPECT_EQ(d.outside, 0) << name;
    ASSERT_GT(d.inside, 0) << name << ": no terrain in view";
    EXPECT_GT(double(d.changed), minShare * d.inside) << name;
}
} // namespace

TEST(ReliefPresentationGLTest, StrokesFollowTheGradientAt1920x1080)
{
    expectStrokesAlongTheGradient(1920, 1080, Viewport{0, 0, 1920, 1080});
}

TEST(ReliefPresentationGLTest, StrokesFollowTheGradientAtAnOddSizeAndInAnOffsetViewport)
{
    expectStrokesAlongTheGradient(641, 359, Viewport{0, 0, 641, 359});
    expectStrokesAlongTheGradient(577, 343, Viewport{37, 21, 500, 300});
}

// Shadowed hachures (Buchin et al. 2004): of two slopes equally steep, the one facing away from
// the north-western light carries more ink; flat ground carries none.
TEST(ReliefPresentationGLTest, SlopesFacingAwayFromTheLightCarryMoreInkAndFlatGroundNone)
{
    registerVariants();
    const int w = 641, h = 359;
    const Viewport vp{0, 0, w, h};
    const osg::BoundingBoxd view(-40.0 * w / h, -40, 0, 40.0 * w / h, 40, 0);
    const double s = 0.5 / std::sqrt(2.0); // slope 0.5 towards the north-west or the south-east
    auto inkOn = [&](double a, double b)
    {
        osg::ref_ptr<osg::Node> p = plane(a, b, -100, -100, 100, 100);
        osg::ref_ptr<osg::Image> flat = loatest::topDown(p.get(), "cartographic", w, h, vp, view);
        osg::ref_ptr<osg::Image> hach = loatest::topDown(p.get(), "test-relief-hachures", w, h, vp, view);
        return inkOf(*hach, *flat, vp).share;
    };
    // z = s x - s y falls towards the north-west (-x, +y): faces the light.
    const double lit = inkOn(s, -s), shaded = inkOn(-s, s), flatInk = inkOn(0.0, 0.0);
    std::cout << "relief: ink on a slope facing the light " << 100 * lit << " %, facing away " << 100 * shaded
              << " %, flat " << 100 * flatInk << " %\n";
    // Normals (-+0.316, +-0.316, 0.894): n.l = 0.949 (lit) and 0.316 (away), shades 0.051 and
    // 0.684, stroke widths 1 + 1.5 shade = 1.08 and 2.03 px.
    EXPECT_GT(shaded, 1.2 * lit);
    EXPECT_GT(lit, 0.02);
    EXPECT_EQ(flatInk, 0.0);
}

TEST(ReliefPresentationGLTest, DiffersFromCartographicOnTerrainOnlyInTheDemoCity)
{
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    expectDifferenceOnTerrainOnly("demo-city", city.get(), 960, 540, 0.01);
}

// A real terrain tile: San Francisco's Telegraph Hill and North Beach, the GeoTIFF DEM shipped in
// Debian's python-osmnx-doc (elevation1.tif, 1 arc second, 10-98 m), drawn top-down at 1920x1080.
// In 96 px tiles where the ground slopes (over 5 %) and the hachures have a clear direction
// (coherence > 0.3, ink > 2 %), their direction is the DEM's direction of steepest descent at the
// tile's centre (bilinear, central differences over 10 m) within 20 degrees in at least 75 % of
// the tiles; flat cartographic and relief differ on the terrain.
TEST(ReliefPresentationGLTest, HachuresFollowTheSlopesOfARealTerrainTile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/elevation1.tif";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    registerVariants();
    const DemTile dem = demTile(file);
    ASSERT_TRUE(dem.node.valid()) << "OSG's gdal plugin did not read " << file;
    EXPECT_EQ(dem.columns, 22);
    EXPECT_EQ(dem.rows, 36); // no-data: the first and last columns and the northern row
    const int w = 1920, h = 1080;
    const Viewport vp{0, 0, w, h};
    // The tile's middle, 540 m x 304 m, north up.
    const double cx = 0.5 * (dem.columns - 1) * dem.dx, cy = 0.5 * (dem.rows - 1) * dem.dy;
    const double halfW = 270.0, halfH = halfW * h / w;
    const osg::BoundingBoxd view(cx - halfW, cy - halfH, 0.0, cx + halfW, cy + halfH, 120.0);
    osg::ref_ptr<osg::Image> flat = loatest::topDown(dem.node.get(), "cartographic", w, h, vp, view);
    osg::ref_ptr<osg::Image> hachures =
        loatest::topDown(dem.node.get(), "test-relief-hachures", w, h, vp, view);
    osg::ref_ptr<osg::Image> relief = loatest::topDown(dem.node.get(), "relief", w, h, vp, view);
    keep(*relief, "telegraph-hill-1920x1080");
    const int tile = 96;
    int qualifying = 0, along = 0;
    for (int ty = 0; ty + tile <= h; ty += tile)
        for (int tx = 0; tx + tile <= w; tx += tile)
        {
            const double x = view.xMin() + (tx + 0.5 * tile) * (view.xMax() - view.xMin()) / w;
            const double y = view.yMin() + (ty + 0.5 * tile) * (view.yMax() - view.yMin()) / h;
            const double gx = (dem.height(x + 5.0, y) - dem.height(x - 5.0, y)) / 10.0;
            const double gy = (dem.height(x, y + 5.0) - dem.height(x, y - 5.0)) / 10.0;
            if (!(std::hypot(gx, gy) > 0.05)) continue;
            const Ink ink = inkOf(*hachures, *flat, Viewport{tx, ty, tile, tile});
            if (ink.coherence < 0.3 || ink.share < 0.02) continue;
            ++qualifying;
            const double descent = std::fmod(std::atan2(-gy, -gx) * 180.0 / M_PI + 360.0, 180.0);
            along += angleBetween(ink.strokeAngle, descent) < 20.0;
        }
    std::cout << "telegraph hill: " << along << " of " << qualifying
              << " sloping tiles have hachures along the descent\n";
    EXPECT_GE(qualifying, 20);
    EXPECT_GE(along, 0.75 * qualifying);
    // Relief against flat cartographic: the terrain gets ink.
    long inked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            inked += luma(*flat, x, y) - luma(*relief, x, y) > 8.0;
    EXPECT_GT(double(inked), 0.01 * w * h);
}
