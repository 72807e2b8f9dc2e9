// Streets as on a map drawn through the LoA pipeline (osgLoA::StreetPresentation): top-down, a
// major and a minor street take their class's fill (times the flat shading computed by hand) and a
// casing of their class's width in pixels along their edges (4 and 3 px in the test's variant), at 1920x1080,
// an odd size and in an offset viewport; nothing off the streets changes; on West Oakland (OpenStreetMap) the
// style changes street pixels only.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/StreetLabels>
#include <osgLoA/styles/StreetPresentation>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <set>

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

/** The streets style without its label layer (labels size 0). */
std::string unlabelled()
{
    const std::string name = "test-streets-unlabelled";
    if (!GraphicStyleCatalog::instance().prototype(name))
    {
        osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create("streets");
        s->setName(name);
        s->getParameter("loa_labels_size")->set(0.0f);
        GraphicStyleCatalog::instance().add(*s);
    }
    return name;
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
    // Fills and casings (the label layer is StreetLabelsGLTest's).
    const loatest::MaskedDifference d = loatest::differenceInMask(model.get(), unlabelled(), "cartographic",
                                                                  loatest::typeMaskStyle(FeatureType::Street),
                                                                  1920, 1080, "streets", "west-oakland");
    EXPECT_EQ(d.outside, 0);
    ASSERT_GT(d.inside, 0);
    // Major roads change fill; every street gets casings.
    EXPECT_GT(double(d.changed), 0.1 * d.inside);
}

// --- street labels (osgLoA::StreetLabels) ---------------------------------------------------------

namespace
{
/** A street quad carrying a name and its centre line along the quad's long axis. */
osg::ref_ptr<osg::Node> namedRoad(unsigned id, const std::string& name, double x0, double y0, double x1,
                                  double y1)
{
    osg::ref_ptr<osg::Node> n = road(id, "major", x0, y0, x1, y1);
    Feature* f = Feature::get(*n);
    f->setLabel(name);
    if (x1 - x0 >= y1 - y0)
        f->setCentreline({osg::Vec2d(x0, 0.5 * (y0 + y1)), osg::Vec2d(x1, 0.5 * (y0 + y1))});
    else
        f->setCentreline({osg::Vec2d(0.5 * (x0 + x1), y0), osg::Vec2d(0.5 * (x0 + x1), y1)});
    return n;
}

/** The labels the renderer lays out for a top-down view of `model` over `view` in a w x h
 *  viewport (the layout is deterministic: the test repeats it on the CPU). */
std::vector<StreetLabels::Label> topDownLabels(osg::Node* model, const osg::BoundingBoxd& view, int w, int h,
                                               std::vector<StreetLabels::Street>& streets,
                                               SignedDistanceFont*& font, osg::ref_ptr<StreetLabels>& holder)
{
    FeatureIndex index(*model);
    streets = StreetLabels::collect(index);
    holder = new StreetLabels(streets);
    font = &holder->getFont();
    StreetLabels::Parameters p;
    StreetLabels::parametersOf(*GraphicStyleCatalog::instance().create("streets"), p);
    StreetLabels::View v;
    v.width = w;
    v.height = h;
    const double top = view.zMax() + 500.0;
    v.sceneToClip = osg::Matrixd::lookAt(osg::Vec3d(0, 0, top), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0)) *
                    osg::Matrixd::ortho(view.xMin(), view.xMax(), view.yMin(), view.yMax(), 1.0,
                                        top - view.zMin() + 10.0);
    return StreetLabels::layout(streets, v, *font, p);
}

/** Whether window pixel (x, y) (viewport-relative) lies in a glyph quad of the labels, grown by
 *  `grow` pixels. */
bool inQuads(const std::vector<StreetLabels::Label>& labels, const SignedDistanceFont& font, double x,
             double y, double grow)
{
    for (const auto& l : labels)
        for (const auto& g : l.glyphs)
        {
            osg::Vec2d q[4];
            StreetLabels::glyphQuad(g, l.size, font, q);
            bool inside = true;
            for (int i = 0; i < 4 && inside; ++i)
            {
                const osg::Vec2d e = q[(i + 1) % 4] - q[i];
                const osg::Vec2d n = osg::Vec2d(-e.y(), e.x()) / e.length();
                inside = (osg::Vec2d(x, y) - q[i]) * n >= -grow;
            }
            if (inside) return true;
        }
    return false;
}

void expectLabelsWhereLaidOut(int w, int h, const loatest::Viewport& vp)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(namedRoad(1, "Adeline Street", 0, 40, 200, 54).get());
    scene->addChild(namedRoad(2, "Market Street", 120, 0, 134, 100).get());
    const double aspect = double(vp.w) / vp.h;
    const osg::BoundingBoxd view(100 - 50 * aspect, 0, 0, 100 + 50 * aspect, 100, 0);
    osg::ref_ptr<osg::Image> labelled = loatest::topDown(scene.get(), "streets", w, h, vp, view);
    osg::ref_ptr<osg::Image> plain = loatest::topDown(scene.get(), unlabelled(), w, h, vp, view);
    const std::string name = std::to_string(w) + "x" + std::to_string(h) + "-" + std::to_string(vp.x);
    loatest::keepFrame("street-labels", *labelled, "quads-" + name);
    std::vector<StreetLabels::Street> streets;
    SignedDistanceFont* font = nullptr;
    osg::ref_ptr<StreetLabels> holder;
    const auto labels = topDownLabels(scene.get(), view, vp.w, vp.h, streets, font, holder);
    // Both streets labelled (at 1920x1080 the 200 m street repeats its name every 300 px or more).
    ASSERT_GE(labels.size(), 2u) << name;
    std::set<std::size_t> labelledStreets;
    for (const auto& l : labels)
        labelledStreets.insert(l.street);
    EXPECT_EQ(labelledStreets.size(), 2u) << name;
    // Every changed pixel lies in a glyph quad (grown by a pixel for the rasterization); each
    // label has text-coloured pixels (0.2 grey, within 40/255) and halo-white ones.
    long changedOutside = 0, changedInside = 0;
    std::vector<long> text(labels.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char *p = labelled->data(x, y), *q = plain->data(x, y);
            const bool changed = std::max({std::abs(int(p[0]) - int(q[0])), std::abs(int(p[1]) - int(q[1])),
                                           std::abs(int(p[2]) - int(q[2]))}) > 2;
            if (!changed) continue;
            const double wx = x - vp.x + 0.5, wy = y - vp.y + 0.5;
            const bool in = x >= vp.x && y >= vp.y && x < vp.x + vp.w && y < vp.y + vp.h &&
                            inQuads(labels, *font, wx, wy, 1.0);
            (in ? changedInside : changedOutside) += 1;
            if (std::abs(int(p[0]) - 51) < 40 && std::abs(int(p[1]) - 51) < 40 &&
                std::abs(int(p[2]) - 51) < 40)
                for (std::size_t l = 0; l < labels.size(); ++l)
                    if (inQuads({labels[l]}, *font, wx, wy, 0.0)) ++text[l];
        }
    std::cout << "street labels " << name << ": " << labels.size() << " labels, " << changedInside
              << " changed pixels in glyph quads, " << changedOutside
              << " outside; text pixels of the first two " << text[0] << ", " << text[1] << "\n";
    EXPECT_EQ(changedOutside, 0) << name;
    // A 12 px label of 13 glyphs, strokes of about 1.5 px: some 180 text pixels (at least 100).
    for (long t : text)
        EXPECT_GT(t, 100) << name;
}
} // namespace

TEST(StreetLabelsGLTest, LabelsDrawnWhereLaidOutAt1920x1080AnOddSizeAndAnOffsetViewport)
{
    expectLabelsWhereLaidOut(1920, 1080, loatest::Viewport{0, 0, 1920, 1080});
    expectLabelsWhereLaidOut(641, 359, loatest::Viewport{0, 0, 641, 359});
    expectLabelsWhereLaidOut(577, 343, loatest::Viewport{37, 21, 500, 300});
}

TEST(StreetLabelsGLTest, ALabelPartlyUnderARoofIsHiddenWhole)
{
    // A roof 20 m above the street's middle covers the middle glyphs' centres: none of the label
    // is drawn (the frame equals the frame without labels); moved off the label, it is drawn.
    for (bool overLabel : {true, false})
    {
        // A 40 m street at 8 px/m: room for one label (the next one 300 px away would not fit).
        osg::ref_ptr<osg::Group> scene = new osg::Group;
        scene->addChild(namedRoad(1, "Adeline Street", 60, 40, 100, 54).get());
        const double rx = overLabel ? 76.0 : 60.0;
        scene->addChild(loatest::asFeature(loatest::planeQuad(rx, 44, rx + 8, 50, 0, 0, 20).get(), 2,
                                           FeatureType::Building)
                            .get());
        const osg::BoundingBoxd view(40, 27, 0, 160, 67, 20);
        const loatest::Viewport vp{0, 0, 960, 320};
        osg::ref_ptr<osg::Image> labelled = loatest::topDown(scene.get(), "streets", 960, 320, vp, view);
        osg::ref_ptr<osg::Image> plain = loatest::topDown(scene.get(), unlabelled(), 960, 320, vp, view);
        long changed = 0;
        for (int y = 0; y < 320; ++y)
            for (int x = 0; x < 960; ++x)
            {
                const unsigned char *p = labelled->data(x, y), *q = plain->data(x, y);
                changed += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
            }
        loatest::keepFrame("street-labels", *labelled, overLabel ? "roof-over-label" : "roof-beside-label");
        if (overLabel)
            EXPECT_EQ(changed, 0);
        else
            EXPECT_GT(changed, 500);
    }
}

TEST(StreetLabelsGLTest, WestOaklandLabelsLieOnItsStreets)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    const int w = 1920, h = 1080;
    const osg::BoundingBoxd view = loatest::framedView(model.get(), w, h);
    const loatest::Viewport vp{0, 0, w, h};
    osg::ref_ptr<osg::Image> labelled = loatest::topDown(model.get(), "streets", w, h, vp, view);
    osg::ref_ptr<osg::Image> mask =
        loatest::topDown(model.get(), loatest::typeMaskStyle(FeatureType::Street), w, h, vp, view);
    loatest::keepFrame("street-labels", *labelled, "west-oakland-1920x1080");
    std::vector<StreetLabels::Street> streets;
    SignedDistanceFont* font = nullptr;
    osg::ref_ptr<StreetLabels> holder;
    const auto labels = topDownLabels(model.get(), view, w, h, streets, font, holder);
    // Every glyph centre on a street pixel (magenta in the mask, within a pixel).
    long glyphs = 0, onStreet = 0, darkInQuads = 0;
    std::set<std::string> names;
    for (const auto& l : labels)
    {
        names.insert(streets[l.street].label);
        for (const auto& g : l.glyphs)
        {
            ++glyphs;
            bool on = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                {
                    const int x = int(g.centre.x()) + dx, y = int(g.centre.y()) + dy;
                    if (x < 0 || y < 0 || x >= w || y >= h) continue;
                    const unsigned char* p = mask->data(x, y);
                    on = on || (p[0] > p[1] + 30 && p[2] > p[1] + 30);
                }
            onStreet += on;
        }
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char* p = labelled->data(x, y);
            if (p[0] < 90 && p[1] < 90 && p[2] < 90 && inQuads(labels, *font, x + 0.5, y + 0.5, 0.0))
                ++darkInQuads;
        }
    std::cout << "West Oakland: " << labels.size() << " labels (" << names.size() << " names), " << glyphs
              << " glyphs, " << onStreet << " centres on streets, " << darkInQuads << " text pixels\n";
    // 9 names by hand; "Campbell Village Court" names two footways of 131 m and 89 m, about 70
    // and 47 px at this scale (0.53 px/m), shorter than its 22 letters at 10 px (about 150 px).
    EXPECT_EQ(names.size(), 8u);
    EXPECT_EQ(names.count("Campbell Village Court"), 0u);
    EXPECT_GE(labels.size(), 8u);
    EXPECT_EQ(onStreet, glyphs);
    // Bold 10 px glyphs, rotated: about 6 pixels darker than 90/255 each.
    EXPECT_GT(darkInQuads, 4 * glyphs);
}
