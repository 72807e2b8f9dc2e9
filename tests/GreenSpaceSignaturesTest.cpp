// Green-space signatures (paper 004 Figure 8B; osgLoA::GreenSpaceSignatures): the CPU twins of the
// shader's texture bombing (cell hash, anchor placement, levels, presence, symbol shapes) against
// values computed by hand or by an independent implementation of the hash, the claim that no
// symbol is cut at a cell border (the reach-limited lookup against a brute-force one over a
// wide neighbourhood), the sub-type codes, and the ground map of a green feature with a tree.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/GreenSpaceSignatures>
#include <osgLoA/styles/TreeSilhouettes>

#include <osg/Geode>
#include <osg/Group>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace osgLoA;
using GSS = GreenSpaceSignatures;

TEST(GreenSpaceSignaturesTest, SubTypeCodesAndTheirSymbols)
{
    EXPECT_EQ(FeatureSubType::names().size(), std::size_t(FeatureSubType::kCount));
    EXPECT_EQ(FeatureSubType::code(""), 0);
    EXPECT_EQ(FeatureSubType::code("deciduous"), 1);
    EXPECT_EQ(FeatureSubType::code("coniferous"), 2);
    EXPECT_EQ(FeatureSubType::code("Park"), 6); // case-insensitive
    EXPECT_EQ(FeatureSubType::code("major"), 32);
    EXPECT_EQ(FeatureSubType::code("no-such-kind"), 0);
    for (int c = 1; c < FeatureSubType::kCount; ++c)
    {
        if (!FeatureSubType::names()[std::size_t(c)].empty())
        {
            EXPECT_EQ(FeatureSubType::code(FeatureSubType::names()[std::size_t(c)]), c);
        }
    }
    EXPECT_EQ(GSS::symbolOf("deciduous"), GSS::DECIDUOUS);
    EXPECT_EQ(GSS::symbolOf("coniferous"), GSS::CONIFEROUS);
    EXPECT_EQ(GSS::symbolOf("mixed"), GSS::MIXED);
    EXPECT_EQ(GSS::symbolOf("forest"), GSS::MIXED); // OSM landuse=forest without leaf_type
    EXPECT_EQ(GSS::symbolOf("park"), GSS::GRASS);
    EXPECT_EQ(GSS::symbolOf("grassland"), GSS::GRASS);
    EXPECT_EQ(GSS::symbolOf("heath"), GSS::SCRUB);
    EXPECT_EQ(GSS::symbolOf("orchard"), GSS::ORCHARD);
    EXPECT_EQ(GSS::symbolOf(""), GSS::GRASS);
    EXPECT_EQ(GSS::symbolOf("farmland"), GSS::GRASS); // not in the table: code 0, as ""
    EXPECT_EQ(GSS::symbolOf("tree"), GSS::NONE);      // a single tree is drawn as itself
    EXPECT_EQ(GSS::symbolOf("river"), GSS::NONE);     // not a green space
    // The style carries the mapping as a uniform array indexed by the code.
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("signatures");
    ASSERT_TRUE(style.valid());
    const osg::Uniform* symbols = style->getParameter("loa_signatures_symbols");
    ASSERT_NE(symbols, nullptr);
    EXPECT_EQ(symbols->getNumElements(), unsigned(FeatureSubType::kCount));
    int v = -1;
    symbols->getElement(2, v);
    EXPECT_EQ(v, int(GSS::CONIFEROUS));
    symbols->getElement(6, v);
    EXPECT_EQ(v, int(GSS::GRASS));
}

TEST(GreenSpaceSignaturesTest, CellHashMatchesAnIndependentImplementation)
{
    // Values from a Python implementation of the same PCG hash (docs/styles.md gives the formula).
    EXPECT_EQ(GSS::hash(0, 0, 0, 1u), 2485072028u);
    EXPECT_EQ(GSS::hash(3, -2, 1, 2u), 2885358569u);
    EXPECT_EQ(GSS::hash(-7, 11, -3, 3u), 657363352u);
    EXPECT_DOUBLE_EQ(GSS::unit(2485072028u), 0.5786008834838867);
    EXPECT_DOUBLE_EQ(GSS::unit(0xffffffffu), 16777215.0 / 16777216.0);
}

TEST(GreenSpaceSignaturesTest, AnchorsLieInTheirCells)
{
    // Without jitter, the cell centre: ((c + 1/2) 2^l).
    EXPECT_EQ(GSS::anchor(0, 0, 0, 0.0), osg::Vec2d(0.5, 0.5));
    EXPECT_EQ(GSS::anchor(3, -2, 1, 0.0), osg::Vec2d(7.0, -3.0));
    EXPECT_EQ(GSS::anchor(-1, 5, -2, 0.0), osg::Vec2d(-0.125, 1.375));
    // Cell (0, 0) of level 0 with full jitter: u = 0.5786 (salt 1) moves x by +0.0786.
    EXPECT_NEAR(GSS::anchor(0, 0, 0, 1.0).x(), 0.5786008834838867, 1e-12);
    for (int l = -3; l <= 3; ++l)
        for (int cy = -20; cy <= 20; ++cy)
            for (int cx = -20; cx <= 20; ++cx)
            {
                const double s = std::ldexp(1.0, l);
                const osg::Vec2d a = GSS::anchor(cx, cy, l, 1.0);
                ASSERT_GE(a.x(), cx * s);
                ASSERT_LT(a.x(), (cx + 1) * s);
                ASSERT_GE(a.y(), cy * s);
                ASSERT_LT(a.y(), (cy + 1) * s);
            }
    // Mixed forests draw both symbols, about half each, by the cell's hash.
    int conifers = 0, total = 0;
    for (int cy = 0; cy < 40; ++cy)
        for (int cx = 0; cx < 40; ++cx, ++total)
            conifers += GSS::cellSymbol(GSS::MIXED, cx, cy, 2) == GSS::CONIFEROUS ? 1 : 0;
    EXPECT_NEAR(double(conifers) / total, 0.5, 0.05);
    EXPECT_EQ(GSS::cellSymbol(GSS::ORCHARD, 1, 2, 3), GSS::DECIDUOUS);
    EXPECT_EQ(GSS::cellSymbol(GSS::GRASS, 1, 2, 3), GSS::GRASS);
}

TEST(GreenSpaceSignaturesTest, LevelsFollowTheScreen)
{
    GSS::Parameters p; // C = 10 pixels
    // sigma = 0.1 m per pixel: C sigma = 1 m, l = 0: cells of 1 m are 10 px on screen.
    EXPECT_EQ(GSS::level(0.1, p), 0);
    // 0.3 m: C sigma = 3, l = ceil(log2 3) = 2: 4 m cells are 13.3 px.
    EXPECT_EQ(GSS::level(0.3, p), 2);
    EXPECT_EQ(GSS::level(0.01, p), -3); // 0.1 -> ceil(-3.32) = -3
    // Fade in from C to 2C, out from 2C to 4C.
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(10.0, p), 0.0);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(15.0, p), 0.5);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(20.0, p), 1.0);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(30.0, p), 0.5);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(40.0, p), 0.0);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(5.0, p), 0.0);
    // The two levels' fractions sum to 1 at the ends of a level's range, so zooming through a
    // level boundary changes nothing: level l at S = C (0) and l + 1 at 2C (1), then l at 2C (1)
    // and l + 1 at 4C (0).
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(10.0, p) + GSS::visibleFraction(20.0, p), 1.0);
    EXPECT_DOUBLE_EQ(GSS::visibleFraction(20.0, p) + GSS::visibleFraction(40.0, p), 1.0);
    // Presence: all symbols at f = 1, none at 0; half-way, the hashes below 0.55 - 0.1.
    EXPECT_DOUBLE_EQ(GSS::presence(1.0, 0.99999), 1.0);
    EXPECT_DOUBLE_EQ(GSS::presence(0.0, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(GSS::presence(0.5, 0.45), 1.0);
    EXPECT_NEAR(GSS::presence(0.5, 0.5), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(GSS::presence(0.5, 0.56), 0.0);
    // Reach: symbol 11 px + 1.5 over cells of 10 px: 2 cells; of 20 px: 1.
    EXPECT_EQ(GSS::reachCells(10.0, p), 2);
    EXPECT_EQ(GSS::reachCells(20.0, p), 1);
    EXPECT_EQ(GSS::reachCells(12.5, p), 1);
}

TEST(GreenSpaceSignaturesTest, SymbolShapes)
{
    bool ink = false;
    // Deciduous: the crown's centre is 0.34 inside the crown; the trunk is ink.
    EXPECT_NEAR(GSS::symbolDistance(GSS::DECIDUOUS, osg::Vec2d(0.0, 0.64), ink), -0.34, 1e-12);
    EXPECT_FALSE(ink);
    EXPECT_NEAR(GSS::symbolDistance(GSS::DECIDUOUS, osg::Vec2d(0.0, 0.15), ink), -0.06, 1e-12);
    EXPECT_TRUE(ink);
    EXPECT_NEAR(GSS::symbolDistance(GSS::DECIDUOUS, osg::Vec2d(0.5, 0.64), ink), 0.16, 1e-12);
    // Coniferous: the apex is on the border; the base's midpoint (0, 0.22) is where trunk and
    // triangle meet; (0, 0.5) is inside, 0.3 * 0.78 / hypot(0.3, 0.76) from the slanted sides.
    EXPECT_NEAR(GSS::symbolDistance(GSS::CONIFEROUS, osg::Vec2d(0.0, 0.98), ink), 0.0, 1e-12);
    const double side = (0.3 * (0.98 - 0.5)) / std::hypot(0.3, 0.76);
    EXPECT_NEAR(GSS::symbolDistance(GSS::CONIFEROUS, osg::Vec2d(0.0, 0.5), ink), -std::min(side, 0.28), 1e-9);
    EXPECT_FALSE(ink);
    // Grass: three strokes from (0, 0.04); the middle one's tip at (0, 0.62), 0.05 wide.
    EXPECT_NEAR(GSS::symbolDistance(GSS::GRASS, osg::Vec2d(0.0, 0.3), ink), -0.05, 1e-12);
    EXPECT_TRUE(ink);
    EXPECT_NEAR(GSS::symbolDistance(GSS::GRASS, osg::Vec2d(0.0, 0.72), ink), 0.05, 1e-12);
    // Every symbol lies within one symbol height of its anchor (the reach the lookup relies on).
    for (int s = GSS::DECIDUOUS; s < GSS::SYMBOL_COUNT; ++s)
        for (int k = 0; k < 360; ++k)
        {
            const double a = k * M_PI / 180.0;
            EXPECT_GT(GSS::symbolDistance(GSS::Symbol(s), osg::Vec2d(std::cos(a), std::sin(a)), ink), 0.0);
        }
}

TEST(GreenSpaceSignaturesTest, NoSymbolIsCutAtACellBorder)
{
    // A top-down orthographic view of flat ground at sigma world units per pixel: the lookup over
    // the cells within reach finds exactly what a brute-force lookup over 6 cells around finds,
    // at every pixel, for sigmas across two level boundaries.
    GSS::Parameters p;
    // Full jitter puts anchors at their cells' borders, and symbols of 18 px (the largest that
    // cells of C = 10 px allow) reach two cells away where cells are under 19.5 px (with the
    // defaults, 11 px and jitter 0.6, a symbol hardly ever leaves the next cell).
    p.jitter = 1.0f;
    p.symbolPixels = 18.0f;
    for (double sigma : {0.1, 0.13, 0.16, 0.17, 0.18, 0.19, 0.27, 0.4})
    {
        const GSS::Projector project = [&](const osg::Vec3d& w)
        { return osg::Vec3d(w.x() / sigma, w.y() / sigma, 0); };
        int symbolPixels = 0, mismatches = 0;
        for (int py = 0; py < 160; ++py)
            for (int px = 0; px < 160; ++px)
            {
                const osg::Vec2d pixel(px + 0.5, py + 0.5);
                const osg::Vec3d world(pixel.x() * sigma, pixel.y() * sigma, 0.0);
                const GSS::Sample s =
                    GSS::sample(GSS::MIXED, world, osg::Vec3d(0, 0, 1), pixel, sigma, project, p);
                // Brute force: every cell within 6 of the pixel's, both levels, lowest anchor first.
                double alpha = 0.0, bestY = std::numeric_limits<double>::infinity();
                const int l0 = GSS::level(sigma, p);
                for (int l = l0; l <= l0 + 1; ++l)
                {
                    const double size = std::ldexp(1.0, l);
                    const double f = GSS::visibleFraction(size / sigma, p);
                    const int bx = int(std::floor(world.x() / size)), by = int(std::floor(world.y() / size));
                    for (int j = -6; j <= 6; ++j)
                        for (int i = -6; i <= 6; ++i)
                        {
                            const double pres = GSS::presence(f, GSS::unit(GSS::hash(bx + i, by + j, l, 3u)));
                            if (pres <= 0.0) continue;
                            const osg::Vec2d a = GSS::anchor(bx + i, by + j, l, double(p.jitter));
                            bool ink = false;
                            const double d =
                                GSS::symbolDistance(GSS::cellSymbol(GSS::MIXED, bx + i, by + j, l),
                                                    (pixel - a / sigma) / GSS::symbolSize(p), ink) *
                                GSS::symbolSize(p);
                            const double c = std::clamp(0.5 - d, 0.0, 1.0) * pres;
                            if (c > 0.0 && a.y() / sigma < bestY)
                            {
                                bestY = a.y() / sigma;
                                alpha = c;
                            }
                        }
                }
                symbolPixels += alpha > 0.0 ? 1 : 0;
                mismatches += std::fabs(alpha - s.alpha) > 1e-12 ? 1 : 0;
            }
        EXPECT_EQ(mismatches, 0) << "sigma " << sigma;
        // Symbols cover a good share of the ground (not an empty test).
        EXPECT_GT(symbolPixels, 160 * 160 / 20) << "sigma " << sigma;
    }
}

TEST(GreenSpaceSignaturesTest, GroundMapIsTheLowestGreenSurface)
{
    // A green feature: ground z = 2 over [0, 10]^2 and a tree crown z = 9 over [4, 6]^2; a
    // terrain feature beside it at z = 0 is not green.
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(loatest::planeQuad(0, 0, 10, 10, 0, 0, 2).get());
    geode->addDrawable(loatest::planeQuad(4, 4, 6, 6, 0, 0, 9).get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(loatest::asFeature(geode.get(), 1, FeatureType::Green).get());
    root->addChild(
        loatest::asFeature(loatest::planeQuad(20, 0, 30, 10).get(), 2, FeatureType::Terrain).get());
    const GSS::GroundMap map = GSS::computeGroundMap(*root);
    ASSERT_TRUE(map.valid());
    EXPECT_EQ(map.greenFeatures, 1u);
    EXPECT_EQ(map.triangles, 4u);
    // Texels of 0.25 (10 / 2046 is finer than the minimum), one of margin: 42 x 42; texel centres
    // inside [0, 10]^2 are 0.125 .. 9.875: 40 x 40.
    EXPECT_DOUBLE_EQ(map.grid.texelSize, 0.25);
    EXPECT_EQ(map.grid.width, 42);
    EXPECT_EQ(map.groundTexels, std::size_t(1600));
    EXPECT_FLOAT_EQ(map.at(5.0, 5.0), 2.0f); // under the crown: the ground
    EXPECT_FLOAT_EQ(map.at(1.0, 9.0), 2.0f);
    EXPECT_EQ(map.at(-0.2, 5.0), GSS::GroundMap::kNoGround);
    // A green feature that is a tree alone: a crown top (z = 9, up) over an underside (z = 6,
    // facing down). The underside is no ground: the map holds the top, so the crown is not taken
    // for vegetation: the tree stays drawn.
    osg::ref_ptr<osg::Geode> tree = new osg::Geode;
    tree->addDrawable(loatest::planeQuad(2, 2, 4, 4, 0, 0, 9).get());
    tree->addDrawable(loatest::planeQuad(4, 2, 2, 4, 0, 0, 6).get()); // reversed: facing down
    osg::ref_ptr<osg::Group> single = new osg::Group;
    single->addChild(loatest::asFeature(tree.get(), 5, FeatureType::Green).get());
    const GSS::GroundMap treeMap = GSS::computeGroundMap(*single);
    ASSERT_TRUE(treeMap.valid());
    EXPECT_FLOAT_EQ(treeMap.at(3.0, 3.0), 9.0f);
    // No green feature: no map; impossible parameters: an error naming them.
    osg::ref_ptr<osg::Group> bare = new osg::Group;
    bare->addChild(loatest::asFeature(loatest::planeQuad(0, 0, 1, 1).get(), 3, FeatureType::Terrain).get());
    EXPECT_FALSE(GSS::computeGroundMap(*bare).valid());
    EXPECT_THROW(GSS::computeGroundMap(*root, 2), std::invalid_argument);
    EXPECT_THROW(GSS::computeGroundMap(*root, 64, -1.0), std::invalid_argument);
}

// --- tree silhouettes (osgLoA::TreeSilhouettes, paper 004 Figure 8C) -------------------------------

TEST(TreeSilhouettesTest, SpriteCountIsTheAreaTimesTheDensityOnAverageAndCapped)
{
    // floor(x + U) with U uniform in [0, 1): x on average, floor(x) or floor(x) + 1 each time.
    for (double x : {0.3, 2.3, 5.75})
    {
        double sum = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i)
        {
            const int c = TreeSilhouettes::spriteCount(x, 1.0, TreeSilhouettes::pcg(std::uint32_t(i)));
            EXPECT_TRUE(c == int(std::floor(x)) || c == int(std::floor(x)) + 1) << x << " " << c;
            sum += c;
        }
        EXPECT_NEAR(sum / n, x, 0.02) << x;
    }
    EXPECT_EQ(TreeSilhouettes::spriteCount(40.0, 1.0, 12345u), TreeSilhouettes::kMaxSprites);
    EXPECT_EQ(TreeSilhouettes::spriteCount(0.0, 1.0, 0xffffffffu), 0);
}

TEST(TreeSilhouettesTest, LeavesLieInTheTriangleSpreadOutAndFixedInTheWorld)
{
    const osg::Vec3d a(0, 0, 0), b(40, 0, 0), c(0, 40, 0);
    const std::uint32_t h = TreeSilhouettes::triangleHash(a, b, c);
    // Order-independent, changed by a centimetre.
    EXPECT_EQ(h, TreeSilhouettes::triangleHash(b, c, a));
    EXPECT_EQ(h, TreeSilhouettes::triangleHash(c, b, a));
    EXPECT_NE(h, TreeSilhouettes::triangleHash(a, b, c + osg::Vec3d(0.01, 0, 0)));
    std::vector<osg::Vec3d> bs;
    for (int k = 0; k < TreeSilhouettes::kMaxSprites; ++k)
    {
        const osg::Vec3d w = TreeSilhouettes::spriteBarycentric(h, k);
        EXPECT_GE(w.x(), -1e-12);
        EXPECT_GE(w.y(), 0.0);
        EXPECT_GE(w.z(), 0.0);
        EXPECT_NEAR(w.x() + w.y() + w.z(), 1.0, 1e-12);
        bs.push_back(w);
    }
    // The R2 sequence keeps 8 points of a triangle apart (no two closer than 0.08 in (u, v)).
    double closest = 1e9;
    for (std::size_t i = 0; i < bs.size(); ++i)
        for (std::size_t j = i + 1; j < bs.size(); ++j)
            closest = std::min(closest, osg::Vec2d(bs[i].y() - bs[j].y(), bs[i].z() - bs[j].z()).length());
    EXPECT_GT(closest, 0.08);
}

namespace
{
/** Drawables named TreeCrown, counted independently of the marker. */
struct CrownCounter : public osg::NodeVisitor
{
    CrownCounter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    unsigned named = 0, marked = 0, drawables = 0;
    void apply(osg::Drawable& d) override
    {
        ++drawables;
        named += d.getName() == "TreeCrown";
        marked += TreeSilhouettes::isCrown(d);
    }
};
} // namespace

TEST(TreeSilhouettesTest, CrownsOfTheDemoCityAndOfARealBlockByHand)
{
    // The demo city: every tree crown drawable (one per green space with trees) and nothing else.
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters::small()).generate();
    CrownCounter before;
    city->accept(before);
    ASSERT_GT(before.named, 0u);
    EXPECT_EQ(TreeSilhouettes::markCrowns(*city), before.named);
    CrownCounter after;
    city->accept(after);
    EXPECT_EQ(after.marked, before.named);

    // OpenCity block (real models): 7 tree geometries by hand (docs/test-scenes.md: 5 tree
    // pieces of one card object each, light-of-star's "small tree" and "tree"); the park's ground
    // shares a translucent atlas but lies flat.
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/test-scenes/opencity-block.osgt";
    if (!osgDB::fileExists(std::string(LOA_SOURCE_DIR) + "/data/cache/opencity-data/pine2/pine2.ac"))
        GTEST_SKIP() << "the OpenCity models are absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> block = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(block.valid());
    FeatureClassifier().classify(*block); // as loa-render and the loa plugin do
    EXPECT_EQ(TreeSilhouettes::markCrowns(*block), 7u);
}

TEST(TreeSilhouettesTest, QuadsBecomeTrianglesOfTheSameSurface)
{
    osg::ref_ptr<osg::Geometry> g = loatest::planeQuad(0, 0, 2, 1);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    unsigned lines = 7;
    EXPECT_EQ(GraphicStyle::triangulate(*geode, &lines), 1u);
    EXPECT_EQ(lines, 0u);
    ASSERT_EQ(g->getNumPrimitiveSets(), 1u);
    const osg::PrimitiveSet* ps = g->getPrimitiveSet(0);
    EXPECT_EQ(ps->getMode(), GLenum(GL_TRIANGLES));
    ASSERT_EQ(ps->getNumIndices(), 6u);
    // Two triangles covering the quad: areas sum to 2.
    const osg::Vec3Array& v = *static_cast<const osg::Vec3Array*>(g->getVertexArray());
    double area = 0.0;
    for (unsigned t = 0; t < 2; ++t)
    {
        const osg::Vec3 p0 = v[ps->index(3 * t)], p1 = v[ps->index(3 * t + 1)], p2 = v[ps->index(3 * t + 2)];
        area += 0.5 * ((p1 - p0) ^ (p2 - p0)).length();
    }
    EXPECT_NEAR(area, 2.0, 1e-6);
    g->addPrimitiveSet(new osg::DrawArrays(GL_LINES, 0, 2));
    EXPECT_EQ(GraphicStyle::triangulate(*geode, &lines), 0u);
    EXPECT_EQ(lines, 1u);
}

TEST(TreeSilhouettesTest, StylesWithAGeometryStageRoundTrip)
{
    // The two styles with a geometry stage (trees, object-edges), a parameter changed.
    const struct
    {
        const char *style, *geometry, *fragment, *parameter;
    } cases[] = {{"trees", "loa_tree_sprites.geom.glsl", "loa_style_trees.frag.glsl", "loa_trees_density"},
                 {"object-edges", "loa_object_edges.geom.glsl", "loa_style_object_edges.frag.glsl",
                  "loa_objectEdges_width"}};
    const std::string dir = loatest::freshDirectory("TreeSilhouettesTest");
    for (const auto& c : cases)
    {
        osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create(c.style);
        ASSERT_TRUE(s.valid()) << c.style;
        EXPECT_EQ(s->getGeometryShader(), c.geometry);
        s->getParameter(c.parameter)->set(3.5f);
        for (const char* ext : {"osgt", "osgb"})
        {
            const std::string path = dir + "/" + c.style + "." + ext;
            ASSERT_TRUE(osgDB::writeObjectFile(*s, path));
            osg::ref_ptr<GraphicStyle> back =
                dynamic_cast<GraphicStyle*>(osgDB::readRefObjectFile(path).get());
            ASSERT_TRUE(back.valid()) << path;
            EXPECT_EQ(back->getGeometryShader(), c.geometry) << path;
            EXPECT_EQ(back->getFragmentShader(), c.fragment) << path;
            float v = 0.0f;
            ASSERT_NE(back->getParameter(c.parameter), nullptr) << path;
            back->getParameter(c.parameter)->get(v);
            EXPECT_EQ(v, 3.5f) << path;
        }
        EXPECT_THROW(s->setGeometryShader("loa_style_trees.frag.glsl"), std::invalid_argument);
        EXPECT_THROW(s->setGeometryShader("../x.geom.glsl"), std::invalid_argument);
    }
}
