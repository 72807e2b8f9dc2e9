// The relief presentation drawn through the LoA pipeline (paper 004 Figure 8D; osgLoA::
// ReliefPresentation): on planes of known gradient the hachures run along the analytic direction
// of steepest descent and the form lines across it (structure tensor of the ink), shaded slopes
// carry more ink, flat ground none; at 1920x1080, an odd size and in an offset viewport. On the
// demo city's hills and a real terrain (OpenStreetMap on a GeoTIFF DEM, both from Debian
// packages) the style differs from flat cartographic on terrain only.
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
