// Streets as on a map drawn through the LoA pipeline (osgLoA::StreetPresentation): top-down, a
// major and a minor street take their class's fill (times the flat shading computed by hand) and a
// casing of their class's width in pixels along their edges (4 and 3 px in the test's variant), at 1920x1080,
// an odd size and in an offset viewport; nothing off the streets changes; on West Oakland (OpenStreetMap) the
// style changes street pixels only.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StreetPresentation>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Node> road(unsigned id, const std::string& subType, double x0, double y0, double x1,
                             double y1)
{
    return loatest::featureQuad(id, FeatureType::Street, subType, x0, y0, x1, y1);
}

int diff(const unsigned char* p, const osg::Vec3f& c)
{
    return std::max({std::abs(int(p[0]) - int(std::lround(255.0 * c[0]))),
                     std::abs(int(p[1]) - int(std::lround(255.0 * c[1]))),
                     std::abs(int(p[2]) - int(std::lround(255.0 * c[2])))});
}

/** The streets style with casings of 4 px (major) and 3 px (minor): wide enough to count. */
void registerWide()
{
    static bool done = false;
    if (done) return;
    done = true;
    osg::ref_ptr<GraphicStyle> wide = GraphicStyleCatalog::instance().create("streets");
    wide->setName("test-streets-wide");
    wide->getParameter("loa_streets_casingPixels")->setElement(0, 4.0f);
    wide->getParameter("loa_streets_casingPixels")->setElement(1, 3.0f);
    GraphicStyleCatalog::instance().add(*wide);
}

void expectFillsAndCasings(int w, int h, const loatest::Viewport& vp)
{
    registerWide();
    // Streets running north-south: a major one 14 m wide, a minor one 8 m wide.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(road(1, "major", 10, 0, 24, 100).get());
    scene->addChild(road(2, "minor", 50, 0, 58, 100).get());
    const osg::BoundingBoxd view(0, 20, 0, 70, 80, 0);
    osg::ref_ptr<osg::Image> img = loatest::topDown(scene.get(), "test-streets-wide", w, h, vp, view);
    osg::ref_ptr<osg::Image> flat = loatest::topDown(scene.get(), "cartographic", w, h, vp, view);
    const std::string label =
        std::to_string(w) + "x" + std::to_string(h) + " viewport " + std::to_string(vp.x);
    loatest::keepFrame("streets", *img,
                       "quads-" + std::to_string(w) + "x" + std::to_string(h) + "-" + std::to_string(vp.x));
    const double light = 0.6 + 0.4 * 0.8 / std::sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.8 * 0.8);
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("test-streets-wide");
    auto element = [&](const char* name, unsigned i)
    {
        osg::Vec3f v;
        style->getParameter(name)->getElement(i, v);
        return v * float(light);
    };
    struct Street
    {
        double x0, x1;
        int cls;
        double casingPixels;
    };
    const Street streets[] = {{10, 24, 0, 4.0}, {50, 58, 1, 3.0}};
    const double pixelWorld = 70.0 / vp.w; // world units per pixel across
    for (const Street& s : streets)
    {
        const osg::Vec3f fill = element("loa_streets_fill", unsigned(s.cls)),
                         casing = element("loa_streets_casing", unsigned(s.cls));
        long fillPixels = 0, casingPixels = 0, other = 0, rows = 0;
        for (int y = vp.y + vp.h / 4; y < vp.y + 3 * vp.h / 4; y += 7, ++rows)
            for (int x = vp.x + int(s.x0 / pixelWorld) - 3; x <= vp.x + int(s.x1 / pixelWorld) + 3; ++x)
            {
                const double wx = (x + 0.5 - vp.x) * pixelWorld;
                if (wx < s.x0 || wx > s.x1) continue;
                const unsigned char* p = img->data(x, y);
                if (diff(p, fill) <= 2)
                    ++fillPixels;
                else if (diff(p, casing) <= 2)
                    ++casingPixels;
                else
                    ++other; // anti-aliased casing rims
            }
        const double perRowCasing = double(casingPixels) / double(rows);
        std::cout << "streets " << label << " class " << s.cls << ": " << perRowCasing
                  << " full casing pixels a row (casing " << s.casingPixels << " px each side), "
                  << double(other) / double(rows) << " rim pixels, " << double(fillPixels) / double(rows)
                  << " fill\n";
        // Both sides: casingPixels each, of which the street's outermost pixel carries the
        // compositor's silhouette edge and the innermost may be partly covered (a rim).
        EXPECT_GE(perRowCasing, 2.0 * (s.casingPixels - 2.0)) << label;
        EXPECT_LE(perRowCasing, 2.0 * s.casingPixels + 1.0) << label;
        EXPECT_LE(double(other) / double(rows), 5.0) << label;
        EXPECT_GT(double(fillPixels) / double(rows), (s.x1 - s.x0) / pixelWorld - 2.0 * s.casingPixels - 4.0)
            << label;
    }
    // Off the streets: as cartographic.
    long changed = 0;
    for (int y = vp.y; y < vp.y + vp.h; ++y)
        for (int x = vp.x; x < vp.x + vp.w; ++x)
        {
            const double wx = (x + 0.5 - vp.x) * pixelWorld;
            const bool near = (wx > 9.0 && wx < 25.0) || (wx > 49.0 && wx < 59.0);
            if (near) continue;
            const unsigned char *p = img->data(x, y), *q = flat->data(x, y);
            changed += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
        }
    EXPECT_EQ(changed, 0) << label;
}
} // namespace

TEST(StreetPresentationGLTest, FillsAndCasingsAt1920x1080)
{
    expectFillsAndCasings(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
}

TEST(StreetPresentationGLTest, FillsAndCasingsAtAnOddSizeAndInAnOffsetViewport)
{
    expectFillsAndCasings(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectFillsAndCasings(577, 343, loatest::Viewport{37, 21, 500, 300});
}

TEST(StreetPresentationGLTest, DiffersFromCartographicOnStreetsOnlyInARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    const loatest::MaskedDifference d = loatest::differenceInMask(model.get(), "streets", "cartographic",
                                                                  loatest::typeMaskStyle(FeatureType::Street),
                                                                  1920, 1080, "streets", "west-oakland");
    EXPECT_EQ(d.outside, 0);
    ASSERT_GT(d.inside, 0);
    // Major roads change fill; every street gets casings.
    EXPECT_GT(double(d.changed), 0.1 * d.inside);
}
