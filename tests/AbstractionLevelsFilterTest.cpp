// AbstractionLevelsFilter (paper 001 §4.1): the iterated Kuwahara levels and the per-pixel level
// chosen by the focus weight in alpha, against KuwaharaFilter applied by hand and hand-computed
// level weights; its pass list; its parameters; the serializer round trip.
#include <osgLoA/abstraction/AbstractionLevelsFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/KuwaharaFilter>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <cmath>
#include <fstream>

using namespace osgLoA;

namespace
{
/** Noisy stripes (something for Kuwahara to do) with the focus weight phi(x) = x / (w - 1). */
FilterImage stripes(int w = 24, int h = 12)
{
    FilterImage img(w, h);
    unsigned seed = 5;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24) - 0.5f;
            const float v = ((x / 3) % 2 ? 0.8f : 0.2f) + 0.2f * n;
            img.set(x, y, osg::Vec4f(v, 1.0f - v, 0.5f + 0.3f * n, float(x) / float(w - 1)));
        }
    return img;
}

float maxRgbDifference(const FilterImage& a, const FilterImage& b)
{
    float m = 0.0f;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 3; ++c)
                m = std::max(m, std::fabs(a.get(x, y)[c] - b.get(x, y)[c]));
    return m;
}
} // namespace

TEST(AbstractionLevelsFilterTest, LevelFollowsTheFocusWeight)
{
    osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter; // radius 2, 3 levels, focus 0
    EXPECT_FLOAT_EQ(f->level(0.0f), 3.0f);
    EXPECT_FLOAT_EQ(f->level(1.0f), 0.0f);
    EXPECT_FLOAT_EQ(f->level(0.5f), 1.5f);
    EXPECT_FLOAT_EQ(f->level(2.0f), 0.0f); // clamped
    f->setIterationsFocus(1);
    EXPECT_FLOAT_EQ(f->level(0.25f), 2.5f); // mix(3, 1, 0.25)
    // Tent weights: lambda 1.5 is half level 1, half level 2.
    EXPECT_FLOAT_EQ(AbstractionLevelsFilter::levelWeight(1.5f, 1), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionLevelsFilter::levelWeight(1.5f, 2), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionLevelsFilter::levelWeight(1.5f, 0), 0.0f);
    EXPECT_FLOAT_EQ(AbstractionLevelsFilter::levelWeight(3.0f, 3), 1.0f);
}

TEST(AbstractionLevelsFilterTest, EachPixelIsTheBlendOfItsTwoLevels)
{
    const FilterImage in = stripes();
    const ImageBorder border(WrapMode::Clamp, WrapMode::Clamp);
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(2);
    std::vector<FilterImage> levels{in};
    for (int i = 0; i < 3; ++i)
        levels.push_back(k->apply(levels.back(), border));
    // Iterating changes the image (the test is not vacuous).
    EXPECT_GT(maxRgbDifference(levels[1], levels[3]), 0.01f);

    osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter;
    const FilterImage out = f->apply(in, border);
    for (int y = 0; y < in.height(); ++y)
        for (int x = 0; x < in.width(); ++x)
        {
            const float phi = in.get(x, y)[3];
            const float lambda = 3.0f * (1.0f - phi);
            const int lo = std::min(int(std::floor(lambda)), 2);
            const float t = lambda - float(lo);
            for (int c = 0; c < 3; ++c)
            {
                const float expected = (1.0f - t) * levels[lo].get(x, y)[c] + t * levels[lo + 1].get(x, y)[c];
                ASSERT_NEAR(out.get(x, y)[c], expected, 1e-5f) << x << "," << y;
            }
            EXPECT_EQ(out.get(x, y)[3], phi); // phi passes through
        }
    // The focus column (phi = 1) is the input itself; the far column (phi = 0) three iterations.
    for (int y = 0; y < in.height(); ++y)
    {
        EXPECT_EQ(out.get(in.width() - 1, y)[0], in.get(in.width() - 1, y)[0]);
        EXPECT_NEAR(out.get(0, y)[0], levels[3].get(0, y)[0], 1e-6f);
    }
}

TEST(AbstractionLevelsFilterTest, UniformLevelIsThePlainIteratedFilter)
{
    const FilterImage in = stripes();
    const ImageBorder border(WrapMode::Repeat, WrapMode::Mirror);
    osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter;
    f->setRadius(4);
    f->setIterations(2);
    f->setIterationsFocus(2);
    osg::ref_ptr<KuwaharaFilter> k = new KuwaharaFilter;
    k->setRadius(4);
    const FilterImage expected = k->apply(k->apply(in, border), border);
    EXPECT_EQ(maxRgbDifference(f->apply(in, border), expected), 0.0f);
    // No blend pass: exactly the two iterations' passes.
    EXPECT_EQ(f->gpuPasses().size(), 2 * k->gpuPasses().size());
}

TEST(AbstractionLevelsFilterTest, PassesChainTheIterationsIntoTheBlend)
{
    osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter; // 3 iterations + blend
    const std::vector<GpuFilterPass> p = f->gpuPasses();
    ASSERT_EQ(p.size(), 10u);
    // Iteration 2's passes read iteration 1's output (pass 2) where Kuwahara reads its input.
    EXPECT_EQ(p[3].inputs, std::vector<int>({2}));
    EXPECT_EQ(p[5].inputs, std::vector<int>({3, 4, 2}));
    EXPECT_EQ(p[9].shader, "loa_filter_abstraction_levels.comp.glsl");
    EXPECT_EQ(p[9].inputs, std::vector<int>({-1, 2, 5, 8}));
    EXPECT_EQ(f->dependencyRadius(), 3 * 2 * 2); // each Kuwahara iteration reads r twice
}

TEST(AbstractionLevelsFilterTest, ParametersAreChecked)
{
    osg::ref_ptr<ImageFilter> f = FilterRegistry::create("abstraction_levels:radius=4,iterations=2");
    EXPECT_EQ(f->getParameterString(), "abstraction_levels:radius=4,iterations=2,iterations_focus=0");
    EXPECT_THROW(f->setParameter("iterations", 4.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("radius", 0.0), std::invalid_argument);
    f->setParameter("iterations_focus", 3.0);
    try
    {
        f->checkParameters();
        FAIL() << "iterations_focus > iterations accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("iterations_focus"), std::string::npos) << e.what();
    }
}

TEST(AbstractionLevelsFilterTest, SerializerRoundTrip)
{
    osg::ref_ptr<AbstractionLevelsFilter> f = new AbstractionLevelsFilter;
    f->setRadius(4);
    f->setIterations(2);
    f->setIterationsFocus(1);
    const std::string dir = loatest::freshDirectory("AbstractionLevelsFilterTest");
    ASSERT_TRUE(osgDB::writeObjectFile(*f, dir + "/a.osgt"));
    osg::ref_ptr<AbstractionLevelsFilter> back =
        dynamic_cast<AbstractionLevelsFilter*>(osgDB::readRefObjectFile(dir + "/a.osgt").get());
    ASSERT_TRUE(back.valid());
    EXPECT_EQ(back->getParameterString(), f->getParameterString());
    ASSERT_TRUE(osgDB::writeObjectFile(*back, dir + "/b.osgt"));
    std::ifstream a(dir + "/a.osgt"), b(dir + "/b.osgt");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
              std::string(std::istreambuf_iterator<char>(b), {}));
}
