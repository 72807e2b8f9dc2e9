// The edge filters' CPU references (SobelFilter "sobel", CannyFilter "canny"): Sobel magnitudes
// computed by hand on a unit step, a diagonal ramp and a constant, under each wrap mode; the
// threshold's edge image; Canny's one-texel-wide closed contour around a square (texels counted
// by hand), no edges in bounded noise, hysteresis keeping weak edges connected to strong ones
// and dropping isolated ones, bounded hysteresis cutting chains after the given number of
// steps; parameter validation (low > high refused), registry specifications and serializer
// round trips.
#include <osgLoA/filtering/CannyFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/SobelFilter>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

using namespace osgLoA;

namespace
{
const WrapMode kModes[3] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};

/** A w x h grey image with value v(x, y) and the given alpha. */
template <class F> FilterImage greyImage(int w, int h, F v, float alpha = 1.0f)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float g = v(x, y);
            img.set(x, y, osg::Vec4f(g, g, g, alpha));
        }
    return img;
}

/** A square of value 1 over [a, b]^2 on 0, in an n x n image. */
FilterImage square(int n, int a, int b)
{
    return greyImage(n, n, [=](int x, int y) { return x >= a && x <= b && y >= a && y <= b ? 1.0f : 0.0f; });
}

bool isEdge(const FilterImage& edges, int x, int y)
{
    return edges.get(x, y)[0] == 0.0f;
}

int edgeCount(const FilterImage& edges)
{
    int n = 0;
    for (int y = 0; y < edges.height(); ++y)
        for (int x = 0; x < edges.width(); ++x)
            n += isEdge(edges, x, y);
    return n;
}

/** Edge images hold only 0 and 1 in R, G and B. */
bool isBinary(const FilterImage& edges)
{
    for (int y = 0; y < edges.height(); ++y)
        for (int x = 0; x < edges.width(); ++x)
            for (int c = 0; c < 3; ++c)
                if (edges.get(x, y)[c] != edges.get(x, y)[0] ||
                    (edges.get(x, y)[c] != 0.0f && edges.get(x, y)[c] != 1.0f))
                    return false;
    return true;
}

/** Number of 2x2 blocks made entirely of edge texels (0 for one-texel-wide contours). */
int fullBlocks(const FilterImage& edges)
{
    int n = 0;
    for (int y = 0; y + 1 < edges.height(); ++y)
        for (int x = 0; x + 1 < edges.width(); ++x)
            n += isEdge(edges, x, y) && isEdge(edges, x + 1, y) && isEdge(edges, x, y + 1) &&
                 isEdge(edges, x + 1, y + 1);
    return n;
}

/** Whether the edges separate (cx, cy) from the image corner: a 4-connected flood fill of
 *  non-edge texels from (0, 0) does not reach it (an 8-connected closed curve blocks 4-connected
 *  paths). */
bool encloses(const FilterImage& edges, int cx, int cy)
{
    const int w = edges.width(), h = edges.height();
    std::vector<char> seen(std::size_t(w * h), 0);
    std::vector<std::pair<int, int>> stack = {{0, 0}};
    seen[0] = 1;
    while (!stack.empty())
    {
        const auto [x, y] = stack.back();
        stack.pop_back();
        if (x == cx && y == cy) return false;
        const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (const auto& s : d)
        {
            const int nx = x + s[0], ny = y + s[1];
            if (nx < 0 || ny < 0 || nx >= w || ny >= h || seen[std::size_t(ny * w + nx)] ||
                isEdge(edges, nx, ny))
                continue;
            seen[std::size_t(ny * w + nx)] = 1;
            stack.push_back({nx, ny});
        }
    }
    return true;
}

/** Writes, reads back and writes again; the two files must be identical. */
template <class T> osg::ref_ptr<T> roundTrip(const T& object, const std::string& dir, const std::string& ext)
{
    const std::string first = dir + "/" + object.filterName() + "-first." + ext;
    const std::string second = dir + "/" + object.filterName() + "-second." + ext;
    EXPECT_TRUE(osgDB::writeObjectFile(object, first)) << first;
    osg::ref_ptr<T> back = dynamic_cast<T*>(osgDB::readRefObjectFile(first).get());
    EXPECT_TRUE(back.valid()) << first << " did not read back";
    if (!back) return back;
    EXPECT_TRUE(osgDB::writeObjectFile(*back, second)) << second;
    EXPECT_FALSE(loatest::fileBytes(first).empty());
    EXPECT_EQ(loatest::fileBytes(first), loatest::fileBytes(second)) << object.filterName() << "." << ext;
    return back;
}

// Y of grey g is (0.299 + 0.587 + 0.114) g = g up to float rounding of the weighted sum.
constexpr float kTol = 2e-6f;
} // namespace

// ---------------------------------------------------------------------------------------------
// Sobel

TEST(EdgeFiltersTest, SobelUnitStepGivesMagnitudeOneBesideTheStep)
{
    // Columns 0..4 are 0, 5..9 are 1. At x = 4 and x = 5 the three rows each see a difference
    // of 1 between x+1 and x-1: gx = 1 + 2 + 1 = 4, gy = 0, M = 4 / 4 = 1. Elsewhere inside,
    // x+1 and x-1 are equal: M = 0. At the border the wrap mode decides: clamp and mirror read
    // column 0 for x = -1 and column 9 for x = 10 (M = 0 there); repeat reads column 9 (value 1)
    // for x = -1: gx(0) = 4 (0 - 1) = -4, M = 1, and column 0 (value 0) for x = 10: M(9) = 1.
    const FilterImage img = greyImage(
        10, 6, [](int x, int) { return x >= 5 ? 1.0f : 0.0f; }, 0.3f);
    osg::ref_ptr<SobelFilter> f = new SobelFilter;
    for (WrapMode m : kModes)
    {
        const ImageBorder border(m, m);
        const FilterImage out = f->apply(img, border);
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 10; ++x)
            {
                const bool step = x == 4 || x == 5;
                const bool seam = m == WrapMode::Repeat && (x == 0 || x == 9);
                const float expected = step || seam ? 1.0f : 0.0f;
                EXPECT_NEAR(out.get(x, y)[0], expected, kTol) << ImageBorder::name(m) << " " << x << "," << y;
                EXPECT_EQ(out.get(x, y)[0], out.get(x, y)[1]);
                EXPECT_EQ(out.get(x, y)[0], out.get(x, y)[2]);
                EXPECT_EQ(out.get(x, y)[3], 0.3f);
                EXPECT_EQ(SobelFilter::magnitude(img, x, y, border), out.get(x, y)[0]);
            }
    }
    // The step's sign is in the gradient: gx = +4 across a rising step.
    EXPECT_NEAR(SobelFilter::gradient(img, 4, 2, ImageBorder())[0], 4.0f, 4 * kTol);
    EXPECT_NEAR(SobelFilter::gradient(img, 4, 2, ImageBorder())[1], 0.0f, 4 * kTol);
}

TEST(EdgeFiltersTest, SobelDiagonalRampHandValues)
{
    // Y = a (x + y), a = 1/32, 16 x 16. Inside: Y(x+1) - Y(x-1) = 2a on each row, gx = 4 * 2a
    // = 8a, gy = 8a likewise, M = sqrt(128) a / 4 = 2 sqrt(2) a.
    // Clamp, x = 0, 0 < y < 15: column -1 reads column 0, so each row differs by a: gx = 4a;
    // gy = (1 + 2 + 1) 2a = 8a; M = sqrt(16 + 64) a / 4 = sqrt(5) a.
    // Clamp, corner (0, 0): gx = 4a, gy = 4a, M = sqrt(32) a / 4 = sqrt(2) a.
    // Repeat, x = 0, 0 < y < 15: column -1 reads column 15, Y(1) - Y(15) = -14a on each row:
    // gx = -56a, gy = 8a, M = sqrt(3136 + 64) a / 4 = sqrt(200) a.
    const float a = 1.0f / 32.0f;
    const FilterImage img = greyImage(16, 16, [=](int x, int y) { return a * float(x + y); });
    osg::ref_ptr<SobelFilter> f = new SobelFilter;
    const FilterImage clamp = f->apply(img, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    const FilterImage repeat = f->apply(img, ImageBorder(WrapMode::Repeat, WrapMode::Clamp));
    for (int y = 1; y < 15; ++y)
        for (int x = 1; x < 15; ++x)
        {
            EXPECT_NEAR(clamp.get(x, y)[0], 2.0f * std::sqrt(2.0f) * a, kTol) << x << "," << y;
            EXPECT_NEAR(repeat.get(x, y)[0], 2.0f * std::sqrt(2.0f) * a, kTol) << x << "," << y;
        }
    for (int y = 1; y < 15; ++y)
    {
        EXPECT_NEAR(clamp.get(0, y)[0], std::sqrt(5.0f) * a, kTol) << y;
        EXPECT_NEAR(repeat.get(0, y)[0], std::sqrt(200.0f) * a, 4 * kTol) << y;
    }
    EXPECT_NEAR(clamp.get(0, 0)[0], std::sqrt(2.0f) * a, kTol);
}

TEST(EdgeFiltersTest, SobelConstantImageGivesZero)
{
    const FilterImage img(13, 9, osg::Vec4f(0.2f, 0.7f, 0.4f, 0.5f));
    osg::ref_ptr<SobelFilter> f = new SobelFilter;
    for (WrapMode m : kModes)
    {
        const FilterImage out = f->apply(img, ImageBorder(m, m));
        EXPECT_EQ(FilterImage::maxAbsDifference(out, FilterImage(13, 9)), 0.0f) << ImageBorder::name(m);
    }
}

TEST(EdgeFiltersTest, SobelThresholdGivesBlackEdgesOnWhite)
{
    // A step of height 0.5 between columns 4 and 5: M = 0.5 on columns 4 and 5, 0 elsewhere.
    // t = 0.4: those columns black (0), the rest white (1). t = 0.6: all white. t = 0.5: M >= t
    // holds where M = 0.5 up to rounding, so the test uses 0.4 and 0.6 around it.
    const FilterImage img = greyImage(
        10, 5, [](int x, int) { return x >= 5 ? 0.75f : 0.25f; }, 0.6f);
    osg::ref_ptr<SobelFilter> f = new SobelFilter;
    f->setThreshold(0.4f);
    const FilterImage edges = f->apply(img, ImageBorder());
    EXPECT_TRUE(isBinary(edges));
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 10; ++x)
        {
            EXPECT_EQ(isEdge(edges, x, y), x == 4 || x == 5) << x << "," << y;
            EXPECT_EQ(edges.get(x, y)[3], 0.6f);
        }
    f->setThreshold(0.6f);
    EXPECT_EQ(edgeCount(f->apply(img, ImageBorder())), 0);
}

TEST(EdgeFiltersTest, SobelParametersAndRegistry)
{
    osg::ref_ptr<ImageFilter> f = FilterRegistry::create("sobel:threshold=0.25");
    ASSERT_TRUE(dynamic_cast<SobelFilter*>(f.get()));
    EXPECT_FLOAT_EQ(static_cast<SobelFilter*>(f.get())->getThreshold(), 0.25f);
    EXPECT_EQ(f->getParameterString(), "sobel:threshold=0.25");
    EXPECT_EQ(f->dependencyRadius(), 1);
    try
    {
        f->setParameter("threshold", 4.5);
        FAIL() << "threshold 4.5 accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("threshold"), std::string::npos) << e.what();
    }
    static_cast<SobelFilter*>(f.get())->setThreshold(-1.0f);
    EXPECT_THROW(f->apply(FilterImage(4, 4), ImageBorder()), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Canny

TEST(EdgeFiltersTest, CannySquareGivesAClosedThinContourOfTheHandCount)
{
    // sigma = 0, a square of 1 over [a, b]^2 = [8, 19]^2 (n = 12 texels a side) in 28 x 28.
    // Straight sides: across the step two texels tie (M = 1); the tie rule keeps the smaller
    // coordinate, so the contour runs outside the square on the left (x = a-1) and top
    // (y = a-1) and inside on the right (x = b) and bottom (y = b). Near the corners (computed
    // by hand, L = 255 Y, integer Sobel):
    //   (a, a): gx = gy = 3 * 255, diagonal, its diagonal neighbours (a-1, a-1) (gx = gy = 255)
    //           and (a+1, a+1) (0) are smaller: kept;
    //   (a-1, a): gx = 3 * 255, gy = 255, horizontal, its right neighbour (a, a) is larger:
    //           suppressed (and (a, a-1) alike); (a-1, b) and (b, a-1) alike next to the
    //           corners (b, a) / (a, b): suppressed;
    //   (b, a) and (a, b): gx = -gy = +-3 * 255, diagonal through (b+1, a-1) / (b-1, a+1): kept.
    // Contour: x = a-1 for a < y < b (n-2), y = a-1 for a < x < b (n-2), x = b for a <= y <= b
    // (n), y = b for a <= x <= b (n, sharing (b, b)), and (a, a): 2(n-2) + 2n - 1 + 1 = 4n - 4.
    const int a = 8, b = 19, n = b - a + 1;
    const FilterImage img = square(28, a, b);
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    f->setSigma(0.0f);
    const FilterImage edges = f->apply(img, ImageBorder());
    EXPECT_TRUE(isBinary(edges));
    EXPECT_EQ(edgeCount(edges), 4 * n - 4);
    for (int k = a + 1; k < b; ++k)
    {
        EXPECT_TRUE(isEdge(edges, a - 1, k)) << k;
        EXPECT_TRUE(isEdge(edges, k, a - 1)) << k;
        EXPECT_TRUE(isEdge(edges, b, k)) << k;
        EXPECT_TRUE(isEdge(edges, k, b)) << k;
    }
    EXPECT_TRUE(isEdge(edges, a, a));
    EXPECT_TRUE(isEdge(edges, b, a));
    EXPECT_TRUE(isEdge(edges, a, b));
    EXPECT_TRUE(isEdge(edges, b, b));
    EXPECT_EQ(fullBlocks(edges), 0);
    EXPECT_TRUE(encloses(edges, 14, 14));

    // With the default smoothing (sigma 1) the corners round off; the contour stays closed and
    // one texel wide, between the rings just outside and just inside the square.
    f->setSigma(1.0f);
    const FilterImage smooth = f->apply(img, ImageBorder());
    const int count = edgeCount(smooth);
    std::cout << "canny sigma 1 square contour: " << count << " texels (sigma 0: " << 4 * n - 4 << ")"
              << std::endl;
    EXPECT_EQ(fullBlocks(smooth), 0);
    EXPECT_TRUE(encloses(smooth, 14, 14));
    EXPECT_GE(count, 4 * n - 12);
    EXPECT_LE(count, 4 * n + 4);
    for (int y = 0; y < 28; ++y)
        for (int x = 0; x < 28; ++x)
            if (isEdge(smooth, x, y))
            {
                EXPECT_TRUE(x >= a - 1 && x <= b + 1 && y >= a - 1 && y <= b + 1) << x << "," << y;
                EXPECT_FALSE(x > a + 1 && x < b - 1 && y > a + 1 && y < b - 1) << x << "," << y;
            }
}

TEST(EdgeFiltersTest, CannyNoiseBelowTheHighThresholdGivesNoEdges)
{
    // Uniform noise in [0.3, 0.7]: after smoothing the values stay in [0.3, 0.7] (a convex
    // combination), after 8-bit rounding within 1/255 more, so each Sobel component is at most
    // 4 * (0.4 + 1/255) and M <= sqrt(2) (0.4 + 1/255) = 0.571 < high = 0.6: no strong texel,
    // hence no edge at all (weak texels alone never survive hysteresis).
    unsigned seed = 12345;
    const FilterImage img = greyImage(64, 64,
                                      [&](int, int)
                                      {
                                          seed = seed * 1664525u + 1013904223u;
                                          return 0.3f + 0.4f * float(seed >> 8) / float(1u << 24);
                                      });
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    f->setLow(0.3f);
    f->setHigh(0.6f);
    EXPECT_EQ(edgeCount(f->apply(img, ImageBorder())), 0);
    // Control: the same noise unsmoothed with the default thresholds is full of edges, so the
    // zero above is the thresholds' doing.
    f->setSigma(0.0f);
    f->setLow(0.1f);
    f->setHigh(0.2f);
    const int noisy = edgeCount(f->apply(img, ImageBorder()));
    std::cout << "canny noise, sigma 0, 0.1/0.2: " << noisy << " edge texels of 4096" << std::endl;
    EXPECT_GT(noisy, 400);
}

namespace
{
/** Rows 0..5 black; rows 6..11 of value `left` for x < 20 and `right` for x >= 20. The step
 *  between rows 5 and 6 has M = left (strong for left = 0.5, high 0.4) on the left and M = right
 *  (weak for right = 0.25, low 0.2) on the right; the tie rule keeps row 5. */
FilterImage twoStep(float left, float right)
{
    return greyImage(40, 12, [=](int x, int y) { return y < 6 ? 0.0f : (x < 20 ? left : right); });
}
} // namespace

TEST(EdgeFiltersTest, CannyHysteresisKeepsConnectedWeakEdgesOnly)
{
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    f->setSigma(0.0f);
    f->setLow(0.2f);
    f->setHigh(0.4f);
    const ImageBorder border;
    // Weak line touching a strong segment: row 5, x = 21..39, is weak (M = 0.25) and survives
    // through its connection (via the short vertical edge at x = 19..20) to the strong row
    // 5, x = 0..18.
    const FilterImage touching = twoStep(0.5f, 0.25f);
    const FilterImage classes = f->edgeClasses(touching, border);
    const FilterImage edges = f->apply(touching, border);
    for (int x = 0; x <= 18; ++x)
    {
        EXPECT_EQ(classes.get(x, 5)[0], 1.0f) << x;
        EXPECT_TRUE(isEdge(edges, x, 5)) << x;
    }
    for (int x = 21; x < 40; ++x)
    {
        EXPECT_EQ(classes.get(x, 5)[0], 0.5f) << x;
        EXPECT_TRUE(isEdge(edges, x, 5)) << x;
    }
    // Isolated weak line: the same weak step everywhere: all of row 5 is weak, nothing is
    // strong, no edge survives.
    const FilterImage isolated = twoStep(0.25f, 0.25f);
    const FilterImage weakOnly = f->edgeClasses(isolated, border);
    for (int x = 0; x < 40; ++x)
        EXPECT_EQ(weakOnly.get(x, 5)[0], 0.5f) << x;
    EXPECT_EQ(edgeCount(f->apply(isolated, border)), 0);
    // Bounded: the weak texels at 8-connected weak-path distance d from the strong ones are
    // (20, 6) at d = 1 and (21 + i, 5) at d = 2 + i; 5 steps reach x = 21..24.
    const FilterImage bounded = f->applyBoundedHysteresis(touching, border, 5);
    for (int x = 21; x < 40; ++x)
        EXPECT_EQ(isEdge(bounded, x, 5), x <= 24) << x;
    EXPECT_EQ(edgeCount(f->applyBoundedHysteresis(touching, border, 64)), edgeCount(edges));
}

TEST(EdgeFiltersTest, BoundedHysteresisIsBreadthFirstOverEightNeighbours)
{
    // Hand-built classes: a strong texel at (0, 2), a weak chain going right along row 2 to
    // x = 9, stepping diagonally to (10, 3) and on to x = 15; a separate weak texel at (18, 3)
    // (a gap of two texels); a weak texel at (0, 4), two rows below the seed (not a neighbour).
    FilterImage classes(20, 6);
    auto set = [&](int x, int y, float c) { classes.set(x, y, osg::Vec4f(c, c, c, 1)); };
    set(0, 2, 1.0f);
    for (int x = 1; x <= 9; ++x)
        set(x, 2, 0.5f);
    for (int x = 10; x <= 15; ++x)
        set(x, 3, 0.5f);
    set(18, 3, 0.5f);
    set(0, 4, 0.5f);
    const ImageBorder border;
    for (int k : {0, 1, 4, 9, 10, 15, -1})
    {
        const FilterImage h = CannyFilter::hysteresis(classes, border, k);
        const int reach = k < 0 ? 15 : k; // chain texel x is at distance x
        for (int x = 1; x <= 15; ++x)
            EXPECT_EQ(h.get(x, x <= 9 ? 2 : 3)[0], x <= reach ? 1.0f : 0.5f) << "k " << k << " x " << x;
        EXPECT_EQ(h.get(18, 3)[0], 0.5f);
        EXPECT_EQ(h.get(0, 4)[0], 0.5f);
    }
    // Repeat wraps neighbours: a weak texel at (19, 2) touches the seed (0, 2) across the seam.
    set(19, 2, 0.5f);
    EXPECT_EQ(
        CannyFilter::hysteresis(classes, ImageBorder(WrapMode::Repeat, WrapMode::Clamp), 1).get(19, 2)[0],
        1.0f);
    EXPECT_EQ(
        CannyFilter::hysteresis(classes, ImageBorder(WrapMode::Clamp, WrapMode::Clamp), 1).get(19, 2)[0],
        0.5f);
}

TEST(EdgeFiltersTest, CannyRefusesLowAboveHighAndBadValues)
{
    osg::ref_ptr<CannyFilter> f = new CannyFilter;
    f->setLow(0.5f);
    f->setHigh(0.3f);
    try
    {
        f->apply(FilterImage(8, 8), ImageBorder());
        FAIL() << "low > high accepted";
    }
    catch (const std::invalid_argument& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("low"), std::string::npos) << what;
        EXPECT_NE(what.find("high"), std::string::npos) << what;
    }
    EXPECT_THROW(f->checkParameters(), std::invalid_argument);
    EXPECT_THROW(f->applyBoundedHysteresis(FilterImage(8, 8), ImageBorder(), 3), std::invalid_argument);
    f->setHigh(0.5f); // low == high is allowed: no weak band
    EXPECT_NO_THROW(f->checkParameters());
    // Specifications set parameters in order; the pair is checked once all are set.
    osg::ref_ptr<ImageFilter> g =
        FilterRegistry::create("canny:low=0.3,high=0.5,sigma=2,hysteresis_iterations=12");
    ASSERT_TRUE(dynamic_cast<CannyFilter*>(g.get()));
    EXPECT_NO_THROW(g->checkParameters());
    EXPECT_EQ(g->getParameterString(), "canny:sigma=2,low=0.3,high=0.5,hysteresis_iterations=12");
    // Radii: 2 Gaussian passes of ceil(3 sigma) = 6, gradient 1, suppression 1, 12 hysteresis.
    EXPECT_EQ(g->dependencyRadius(), 2 * 6 + 2 + 12);
    EXPECT_EQ(g->gpuPasses().size(), 2u + 2u + 12u + 1u);
    for (const auto& [name, value] :
         std::vector<std::pair<std::string, double>>{{"sigma", 8.5},
                                                     {"low", -0.1},
                                                     {"high", 4.5},
                                                     {"hysteresis_iterations", 65},
                                                     {"hysteresis_iterations", 2.5}})
    {
        try
        {
            g->setParameter(name, value);
            FAIL() << name << " = " << value << " accepted";
        }
        catch (const std::invalid_argument& e)
        {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(CannyFilter::squaredThreshold(0.0f), 0);
    EXPECT_EQ(CannyFilter::squaredThreshold(1.0f), 1020 * 1020);
    EXPECT_EQ(CannyFilter::squaredThreshold(0.5f), 510 * 510);
}

TEST(EdgeFiltersTest, SerializerRoundTrips)
{
    const std::string dir = loatest::freshDirectory("EdgeFiltersRoundTrip");
    osg::ref_ptr<SobelFilter> s = new SobelFilter;
    s->setThreshold(0.35f);
    osg::ref_ptr<CannyFilter> c = new CannyFilter;
    c->setSigma(1.5f);
    c->setLow(0.05f);
    c->setHigh(0.3f);
    c->setHysteresisIterations(20);
    for (const char* ext : {"osgt", "osgb"})
    {
        osg::ref_ptr<SobelFilter> sb = roundTrip(*s, dir, ext);
        ASSERT_TRUE(sb.valid());
        EXPECT_EQ(sb->getParameterString(), s->getParameterString());
        EXPECT_EQ(sb->getThreshold(), 0.35f);
        osg::ref_ptr<CannyFilter> cb = roundTrip(*c, dir, ext);
        ASSERT_TRUE(cb.valid());
        EXPECT_EQ(cb->getParameterString(), c->getParameterString());
        EXPECT_EQ(cb->getHysteresisIterations(), 20);
        EXPECT_EQ(cb->getLow(), 0.05f);
    }
}
