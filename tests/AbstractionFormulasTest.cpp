// The CPU reference of the per-pixel abstraction stages (papers 001, 002) on hand-computed values:
// cel quantization at level boundaries, F = P sigma C E and F = P S^gamma with clamping, the
// bleached edge overlay, the shading share, continuous Kuwahara levels, ID-pass silhouettes.
#include <osgLoA/abstraction/AbstractionFormulas>

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

using namespace osgLoA;

namespace
{
void expectVec(const osg::Vec3f& actual, const osg::Vec3f& expected, const char* what)
{
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(actual[i], expected[i], 1e-6f) << what << " channel " << i;
}
} // namespace

TEST(AbstractionFormulasTest, CelQuantizeAtLevelBoundaries)
{
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.24f, 4), 0.25f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.25f, 4), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.49f, 4), 0.5f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.5f, 4), 0.75f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.75f, 4), 1.0f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(1.0f, 4), 1.0f); // k = min(4, 3)
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.0f, 4), 0.25f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(-2.0f, 4), 0.25f); // clamped
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(3.0f, 4), 1.0f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(std::numeric_limits<float>::quiet_NaN(), 4), 0.25f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.6f, 2), 1.0f);
    EXPECT_FLOAT_EQ(AbstractionFormulas::celQuantize(0.3f, 1), 1.0f);
    try
    {
        AbstractionFormulas::celQuantize(0.5f, 0);
        ADD_FAILURE() << "levels 0 accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("levels"), std::string::npos) << e.what();
    }
}

TEST(AbstractionFormulasTest, ToonPencilOverlayAndShareOnHandValues)
{
    // F = P sigma C E: (0.4, 0.2, 0.8) * 1.5 * 0.5 * 1 = (0.3, 0.15, 0.6).
    expectVec(AbstractionFormulas::toon({0.4f, 0.2f, 0.8f}, 0.5f, 1.0f, 1.5f), {0.3f, 0.15f, 0.6f}, "toon");
    // With an edge at half strength E = 0.5: (0.15, 0.075, 0.3).
    expectVec(AbstractionFormulas::toon({0.4f, 0.2f, 0.8f}, 0.5f, 0.5f, 1.5f), {0.15f, 0.075f, 0.3f},
              "toon E");
    // Clamping: 0.9 * 1.5 = 1.35 -> 1; 0.5 * 1.5 = 0.75; black line E = 0 -> 0.
    expectVec(AbstractionFormulas::toon({0.9f, 0.5f, 1.0f}, 1.0f, 1.0f, 1.5f), {1.0f, 0.75f, 1.0f},
              "toon clamp");
    expectVec(AbstractionFormulas::toon({0.9f, 0.5f, 1.0f}, 1.0f, 0.0f, 1.5f), {0.0f, 0.0f, 0.0f},
              "toon line");

    // F = P S^gamma: S = 0.5, gamma 2 -> factor 0.25.
    expectVec(AbstractionFormulas::pencilSketch({0.8f, 0.4f, 1.0f}, 0.5f, 2.0f), {0.2f, 0.1f, 0.25f},
              "pencil");
    // gamma 0.5, S = 0.25 -> factor 0.5.
    expectVec(AbstractionFormulas::pencilSketch({0.8f, 0.4f, 1.0f}, 0.25f, 0.5f), {0.4f, 0.2f, 0.5f},
              "pencil g");
    // Clamping: S = 2 -> 1; P out of [0, 1] -> clamped result.
    expectVec(AbstractionFormulas::pencilSketch({2.0f, 0.5f, -1.0f}, 2.0f, 1.0f), {1.0f, 0.5f, 0.0f},
              "pencil c");

    const osg::Vec3f c(0.2f, 0.4f, 0.6f);
    expectVec(AbstractionFormulas::overlay(c, 1.0f, 1.0f, 0.0f), c, "no line, no bleach");
    expectVec(AbstractionFormulas::overlay(c, 1.0f, 1.0f, 0.5f), {0.6f, 0.7f, 0.8f}, "bleach 0.5");
    expectVec(AbstractionFormulas::overlay(c, 1.0f, 1.0f, 1.0f), {1.0f, 1.0f, 1.0f}, "bleach 1");
    expectVec(AbstractionFormulas::overlay(c, 0.0f, 1.0f, 0.5f), {0.0f, 0.0f, 0.0f}, "opaque line");
    expectVec(AbstractionFormulas::overlay(c, 0.0f, 0.5f, 0.5f), {0.3f, 0.35f, 0.4f}, "half line, bleach");
    expectVec(AbstractionFormulas::overlay(c, 0.5f, 1.0f, 0.0f), {0.1f, 0.2f, 0.3f}, "grey edge");
    expectVec(AbstractionFormulas::overlay(c, 0.0f, 0.0f, 0.0f), c, "transparent line");

    expectVec(AbstractionFormulas::shadingShare(0.25f, 1.0f), {0.25f, 0.25f, 0.25f}, "share 1");
    expectVec(AbstractionFormulas::shadingShare(0.25f, 0.0f), {1.0f, 1.0f, 1.0f}, "share 0");
    expectVec(AbstractionFormulas::shadingShare(0.25f, 0.5f), {0.625f, 0.625f, 0.625f}, "share 0.5");
}

TEST(AbstractionFormulasTest, BlendLevelsBetweenNeighbouringIterations)
{
    // Three constant levels 0.1, 0.5, 0.9 (alpha 0.2, 0.6, 1.0); lambda per pixel in a 6x1 image.
    std::vector<FilterImage> levels = {FilterImage(6, 1, osg::Vec4f(0.1f, 0.1f, 0.1f, 0.2f)),
                                       FilterImage(6, 1, osg::Vec4f(0.5f, 0.5f, 0.5f, 0.6f)),
                                       FilterImage(6, 1, osg::Vec4f(0.9f, 0.9f, 0.9f, 1.0f))};
    FilterImage lambda(6, 1);
    const float l[6] = {0.0f, 0.5f, 1.5f, 2.0f, 3.0f, -1.0f};
    const float want[6] = {0.1f, 0.3f, 0.7f, 0.9f, 0.9f, 0.1f}; // 3 and -1 are clamped
    const float wantAlpha[6] = {0.2f, 0.4f, 0.8f, 1.0f, 1.0f, 0.2f};
    for (int x = 0; x < 6; ++x)
        lambda.set(x, 0, osg::Vec4f(l[x], 99.0f, 99.0f, 99.0f)); // only channel 0 counts
    const FilterImage out = AbstractionFormulas::blendLevels(levels, lambda);
    ASSERT_EQ(out.width(), 6);
    for (int x = 0; x < 6; ++x)
    {
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out.get(x, 0)[c], want[x], 1e-6f) << "lambda " << l[x];
        EXPECT_NEAR(out.get(x, 0)[3], wantAlpha[x], 1e-6f) << "lambda " << l[x];
    }
    EXPECT_THROW(AbstractionFormulas::blendLevels({}, lambda), std::invalid_argument);
    levels[1] = FilterImage(5, 1);
    try
    {
        AbstractionFormulas::blendLevels(levels, lambda);
        ADD_FAILURE() << "mismatched sizes accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("levels[1]"), std::string::npos) << e.what();
    }
}

TEST(AbstractionFormulasTest, SilhouettesOfATwoObjectIdImage)
{
    // 6x4: object A (red) everywhere except a 2x2 block of object B at x = 2..3, y = 1..2, whose
    // colour differs from A's only in blue. Alpha differs at (0, 0) and must not count.
    //   y=3  A A A A A A        . . # # . .
    //   y=2  A A B B A A   ->   . . # . # .
    //   y=1  A A B B A A        . . # # # .
    //   y=0  A A A A A A        . . . . . .
    // Black: a pixel whose left or lower neighbour (clamped) has another id: a one-pixel line on
    // the right/top side of each boundary, 7 pixels.
    const osg::Vec4f a(1.0f, 0.0f, 0.0f, 1.0f), b(1.0f, 0.0f, 0.5f, 1.0f);
    FilterImage ids(6, 4, a);
    ids.set(0, 0, osg::Vec4f(1.0f, 0.0f, 0.0f, 0.0f));
    for (int y = 1; y <= 2; ++y)
        for (int x = 2; x <= 3; ++x)
            ids.set(x, y, b);
    const FilterImage s = AbstractionFormulas::silhouettes(ids);
    const char* expected[4] = {"......", "..###.", "..#.#.", "..##.."}; // rows y = 0..3
    int black = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x)
        {
            const osg::Vec4f v = s.get(x, y);
            const bool isBlack = v[0] == 0.0f;
            black += isBlack ? 1 : 0;
            EXPECT_EQ(isBlack, expected[y][x] == '#') << x << ", " << y;
            EXPECT_EQ(v[0], v[1]);
            EXPECT_EQ(v[0], v[2]);
            EXPECT_EQ(v[3], 1.0f);
            EXPECT_TRUE(v[0] == 0.0f || v[0] == 1.0f);
        }
    EXPECT_EQ(black, 7);
    // One id everywhere: no silhouettes (the clamped border does not count as a boundary).
    const FilterImage none = AbstractionFormulas::silhouettes(FilterImage(5, 3, a));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            EXPECT_EQ(none.get(x, y)[0], 1.0f);
}
