// The demo city generator: determinism, per-type feature counts, layout, parameter errors.
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/city/CityTextures>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/util/SceneStatistics>

#include <osg/NodeVisitor>
#include <osg/Texture2D>

#include <gtest/gtest.h>

#include <set>

using namespace osgLoA;

namespace
{
struct Features : osg::NodeVisitor
{
    Features() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Node& n) override
    {
        if (const Feature* f = Feature::get(n)) tags.push_back(f);
        traverse(n);
    }
    std::vector<osg::ref_ptr<const Feature>> tags;
    int count(FeatureType type, const std::string& subtype = "*") const
    {
        int c = 0;
        for (const auto& t : tags)
            c += t->getType() == type && (subtype == "*" || t->getSubType() == subtype);
        return c;
    }
};

CityParameters noRiverSmall()
{
    CityParameters p = CityParameters::small();
    p.river = false;
    return p;
}
} // namespace

TEST(CityGeneratorTest, SameParametersGiveTheSameGraph)
{
    const CityParameters p = CityParameters::small();
    const std::string a = loatest::toOsgt(*CityGenerator(p).generate());
    const std::string b = loatest::toOsgt(*CityGenerator(p).generate());
    ASSERT_GT(a.size(), 10000u) << "the .osgt writer produced nothing";
    EXPECT_EQ(a, b);
}

TEST(CityGeneratorTest, AnotherSeedGivesAnotherCity)
{
    CityParameters p = CityParameters::small();
    const std::string a = loatest::toOsgt(*CityGenerator(p).generate());
    p.seed = 2;
    const std::string b = loatest::toOsgt(*CityGenerator(p).generate());
    EXPECT_NE(a, b);
}

// Hand count for the small city without a river (12 free blocks):
// road lines x: 5 (lines 0 and 3 major), y: 4 (lines 0 and 3 major) -> 9 streets, 4 major;
// landmarks min(2, 12) = 2; parks round(0.17 * 12) = 2; forests round(0.17 * 12) = 2.
TEST(CityGeneratorTest, PerTypeFeatureCountsWithoutRiver)
{
    Features f;
    CityGenerator(noRiverSmall()).generate()->accept(f);
    EXPECT_EQ(f.count(FeatureType::Terrain), 1);
    EXPECT_EQ(f.count(FeatureType::Water), 0);
    EXPECT_EQ(f.count(FeatureType::Street), 9);
    EXPECT_EQ(f.count(FeatureType::Street, "major"), 4);
    EXPECT_EQ(f.count(FeatureType::Street, "minor"), 5);
    EXPECT_EQ(f.count(FeatureType::Green), 4);
    EXPECT_EQ(f.count(FeatureType::Green, "park"), 2);
    EXPECT_EQ(f.count(FeatureType::Green, "coniferous"), 1);
    EXPECT_EQ(f.count(FeatureType::Green, "deciduous"), 1);
    EXPECT_EQ(f.count(FeatureType::Building, "landmark"), 2);
    // 6 building blocks, each with two rows of at least two lots (a few lots stay empty).
    EXPECT_GE(f.count(FeatureType::Building) - 2, 6 * 3);
    EXPECT_EQ(f.count(FeatureType::Generic), 0);
    int landmarks = 0;
    for (const auto& t : f.tags)
        landmarks += t->getLandmark();
    EXPECT_EQ(landmarks, 2);
}

TEST(CityGeneratorTest, EveryFeatureTypeOfThePapersIsPresentByDefault)
{
    Features f;
    CityGenerator(CityParameters()).generate()->accept(f);
    for (FeatureType t : {FeatureType::Terrain, FeatureType::Water, FeatureType::Street, FeatureType::Green,
                          FeatureType::Building})
        EXPECT_GT(f.count(t), 0) << toString(t);
    EXPECT_EQ(f.count(FeatureType::Water, "river"), 1);
    EXPECT_GT(f.count(FeatureType::Green, "mixed"), 0);
    EXPECT_EQ(f.count(FeatureType::Building, "landmark"), 4);
}

TEST(CityGeneratorTest, FeatureIdsAreUniqueAndContiguous)
{
    Features f;
    CityGenerator(CityParameters::small()).generate()->accept(f);
    std::set<unsigned> ids;
    for (const auto& t : f.tags)
        ids.insert(t->getId());
    ASSERT_EQ(ids.size(), f.tags.size());
    EXPECT_EQ(*ids.begin(), 1u);
    EXPECT_EQ(*ids.rbegin(), f.tags.size());
    EXPECT_EQ(f.tags.front()->getType(), FeatureType::Terrain); // terrain gets id 1
}

TEST(CityGeneratorTest, DefaultCityIsWithinTheTriangleBudget)
{
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters()).generate();
    const SceneStatistics s = SceneStatistics::collect(*city);
    EXPECT_GE(s.triangles, 50000u);
    EXPECT_LE(s.triangles, 150000u);
    EXPECT_GE(s.textures, 12u);
}

TEST(CityGeneratorTest, ScaledParametersGrowTheCity)
{
    const auto small = SceneStatistics::collect(*CityGenerator(CityParameters()).generate());
    const auto big = SceneStatistics::collect(*CityGenerator(CityParameters().scaled(1.5)).generate());
    EXPECT_GT(big.triangles, small.triangles * 3 / 2);
}

TEST(CityGeneratorTest, MeshHeightInterpolatesTheTerrainAtGridVertices)
{
    CityGenerator g(CityParameters::small());
    const CityLayout& L = g.getLayout();
    const int n = CityParameters::small().terrainResolution;
    const double sx = (L.terrainBounds.xMax() - L.terrainBounds.xMin()) / (n - 1);
    const double sy = (L.terrainBounds.yMax() - L.terrainBounds.yMin()) / (n - 1);
    for (int j = 0; j < n; j += 7)
        for (int i = 0; i < n; i += 5)
        {
            const double x = L.terrainBounds.xMin() + i * sx, y = L.terrainBounds.yMin() + j * sy;
            EXPECT_NEAR(g.meshHeight(x, y), g.terrainHeight(x, y), 1e-4);
        }
    // Midway along a cell diagonal the mesh is the mean of the diagonal's ends.
    const double x0 = L.terrainBounds.xMin() + 3 * sx, y0 = L.terrainBounds.yMin() + 4 * sy;
    EXPECT_NEAR(g.meshHeight(x0 + sx / 2, y0 + sy / 2),
                0.5 * (g.meshHeight(x0, y0) + g.meshHeight(x0 + sx, y0 + sy)), 1e-4);
}

TEST(CityGeneratorTest, TheRiverBedIsBelowWaterAndTheCityAboveIt)
{
    CityGenerator g(CityParameters::small());
    const CityLayout& L = g.getLayout();
    for (double y = L.cityBounds.yMin(); y <= L.cityBounds.yMax(); y += 25.0)
    {
        EXPECT_LT(g.terrainHeight(g.riverCenterX(y), y), L.waterLevel);
        // 60 m beyond the water's edge the bank is dry.
        EXPECT_GT(g.terrainHeight(g.riverCenterX(y) + 42.0 / 2 + 60.0, y), L.waterLevel + 1.0);
    }
}

TEST(CityGeneratorTest, FacadeTexturesMixPowerOfTwoAndOtherSizesAndAreMipmapped)
{
    int pot = 0, npot = 0;
    auto isPot = [](int v) { return v > 0 && (v & (v - 1)) == 0; };
    for (const FacadeStyle& s : CityTextures::facadeStyles())
    {
        osg::ref_ptr<osg::Image> img = CityTextures::facade(s);
        EXPECT_EQ(img->s(), s.width);
        EXPECT_EQ(img->t(), s.height);
        (isPot(s.width) && isPot(s.height) ? pot : npot)++;
        osg::ref_ptr<osg::Texture2D> t = CityTextures::makeTexture(img.get());
        EXPECT_EQ(t->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
        EXPECT_FALSE(t->getResizeNonPowerOfTwoHint());
    }
    EXPECT_GE(pot, 2);
    EXPECT_GE(npot, 2);
    EXPECT_THROW(CityTextures::surface("marble"), std::invalid_argument);
}

TEST(CityGeneratorTest, GeneratedImagesAreSharedAndStatic)
{
    // One image per style and process, shared by every scene (no per-import copies).
    const FacadeStyle& s = CityTextures::facadeStyles().front();
    osg::ref_ptr<osg::Image> a = CityTextures::facade(s), b = CityTextures::facade(s);
    EXPECT_EQ(a.get(), b.get());
    EXPECT_EQ(a->getDataVariance(), osg::Object::STATIC);
    EXPECT_EQ(CityTextures::surface("water").get(), CityTextures::surface("water").get());
    EXPECT_NE(CityTextures::surface("water").get(), CityTextures::surface("terrain").get());
}

TEST(CityGeneratorTest, ImpossibleParametersAreRejectedByName)
{
    CityParameters p;
    p.blocksX = 0;
    try
    {
        CityGenerator g(p);
        FAIL() << "blocksX=0 was accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("blocksX"), std::string::npos) << e.what();
    }
    CityParameters q;
    q.parkFraction = 0.7;
    q.forestFraction = 0.5;
    EXPECT_THROW(q.validate(), std::invalid_argument);
    CityParameters r;
    r.majorRoadWidth = 5.0; // narrower than minor roads
    EXPECT_THROW(r.validate(), std::invalid_argument);
}

TEST(CityGeneratorTest, ParametersParseAndPrintRoundTrip)
{
    CityParameters p;
    p.parse("seed=7, blocksX=6 blocksY=4 river=false riverWidth=30.5");
    EXPECT_EQ(p.seed, 7u);
    EXPECT_EQ(p.blocksX, 6);
    EXPECT_FALSE(p.river);
    EXPECT_DOUBLE_EQ(p.riverWidth, 30.5);
    CityParameters q;
    q.parse(p.toString());
    EXPECT_EQ(q.toString(), p.toString());
    EXPECT_THROW(p.parse("colour=red"), std::invalid_argument);
    EXPECT_THROW(p.parse("blocksX=2.5"), std::invalid_argument);
    EXPECT_THROW(p.parse("seed=-1"), std::invalid_argument);
    EXPECT_THROW(p.parse("blocksX"), std::invalid_argument);
    EXPECT_THROW(p.parse("blockSize=nan"), std::invalid_argument);
}
