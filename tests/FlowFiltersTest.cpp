// The flow-based filters of paper 000 (osgLoA issue 6): the structure tensor and edge tangent
// flow (StructureTensor) hand-computed on ramps and step edges; the DoG / FDoG / XDoG filter
// (DoGFilter) and the flow-based bilateral filter (FlowBilateralFilter) on step edges, constant
// images and noise (the documented failure regime: DoG speckles, FDoG coherent lines), wrap
// modes against extended images, parameters, the registry and serializer round trips.
#include "support/TestSupport.h"

#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterImage>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/FlowBilateralFilter>
#include <osgLoA/filtering/StructureTensor>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

using namespace osgLoA;

namespace
{
const ImageBorder kClamp(WrapMode::Clamp, WrapMode::Clamp);
const ImageBorder kRepeat(WrapMode::Repeat, WrapMode::Repeat);
const ImageBorder kMirror(WrapMode::Mirror, WrapMode::Mirror);

/** I_c(x, y) = a_c x + b_c y + 0.1 per channel c. */
FilterImage ramp(int w, int h, const osg::Vec3f& a, const osg::Vec3f& b)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, osg::Vec4f(a * float(x) + b * float(y) + osg::Vec3f(0.1f, 0.1f, 0.1f), 1.0f));
    return img;
}

/** Uniform noise in [0, 1) in RGB, alpha 1 (a fixed LCG). */
FilterImage noise(int w, int h, unsigned seed)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            float v[3];
            for (float& c : v)
            {
                seed = seed * 1664525u + 1013904223u;
                c = float(seed >> 8) / float(1u << 24);
            }
            img.set(x, y, osg::Vec4f(v[0], v[1], v[2], 1.0f));
        }
    return img;
}

/** 0 left of column x0, `high` from x0 on (a vertical step edge). */
FilterImage verticalStep(int w, int h, int x0, float high = 1.0f)
{
    FilterImage img(w, h, osg::Vec4f(0, 0, 0, 1));
    for (int y = 0; y < h; ++y)
        for (int x = x0; x < w; ++x)
            img.set(x, y, osg::Vec4f(high, high, high, 1));
    return img;
}
} // namespace

TEST(StructureTensorTest, LinearRampGivesTheHandComputedTensor)
{
    // Sobel / 8 of a ramp is its slope exactly; E, F, G sum over the channels.
    const osg::Vec3f a(0.01f, 0.02f, 0.03f), b(0.005f, -0.01f, 0.0f);
    const FilterImage img = ramp(16, 12, a, b);
    const FilterImage t = StructureTensor::tensor(img, kClamp);
    const float E = a * a, F = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], G = b * b;
    for (int y = 1; y < 11; ++y)
        for (int x = 1; x < 15; ++x)
        {
            EXPECT_NEAR(t.get(x, y)[0], E, 1e-7f);
            EXPECT_NEAR(t.get(x, y)[1], F, 1e-7f);
            EXPECT_NEAR(t.get(x, y)[2], G, 1e-7f);
        }
    // Smoothing a constant tensor leaves it (interior texels, away from the
    // clamped border).
    const FilterImage s = StructureTensor::smoothedTensor(img, 1.0f, kClamp);
    EXPECT_NEAR(s.get(8, 6)[0], E, 1e-6f);
    EXPECT_NEAR(s.get(8, 6)[1], F, 1e-6f);
    EXPECT_NEAR(s.get(8, 6)[2], G, 1e-6f);
    // A one-directional ramp (all channels share the direction (2, 1)): A = 1 and
    // t = (-1, 2)/sqrt5 (canonical sign t.y > 0), phi = atan2(1, 2).
    const FilterImage r = ramp(24, 20, osg::Vec3f(0.02f, 0.02f, 0.02f), osg::Vec3f(0.01f, 0.01f, 0.01f));
    const FilterImage f = StructureTensor::flow(r, 2.0f, kClamp);
    const osg::Vec4f v = f.get(12, 10);
    EXPECT_NEAR(v[0], -1.0f / std::sqrt(5.0f), 1e-4f);
    EXPECT_NEAR(v[1], 2.0f / std::sqrt(5.0f), 1e-4f);
    EXPECT_NEAR(v[2], 1.0f, 1e-4f);
    EXPECT_NEAR(v[3], std::atan2(1.0f, 2.0f), 1e-4f);
}

TEST(StructureTensorTest, VerticalStepEdgeHasTangentAlongTheEdgeAndFullAnisotropy)
{
    const FilterImage img = verticalStep(16, 8, 8);
    const FilterImage t = StructureTensor::tensor(img, kClamp);
    // Columns 7 and 8 see the step: fx = (1 + 2 + 1) / 8 = 0.5 per channel, E = 3
    // * 0.25.
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
        {
            const float E = (x == 7 || x == 8) ? 0.75f : 0.0f;
            EXPECT_FLOAT_EQ(t.get(x, y)[0], E) << x << "," << y;
            EXPECT_FLOAT_EQ(t.get(x, y)[1], 0.0f);
            EXPECT_FLOAT_EQ(t.get(x, y)[2], 0.0f);
        }
    const FilterImage f = StructureTensor::flow(img, 2.0f, kClamp);
    for (int y = 0; y < 8; ++y)
        for (int x = 2; x < 14; ++x)
        {
            const osg::Vec4f v = f.get(x, y);
            EXPECT_FLOAT_EQ(v[0], 0.0f) << x << "," << y;
            EXPECT_FLOAT_EQ(v[1], 1.0f) << x << "," << y;
            EXPECT_FLOAT_EQ(v[2], 1.0f) << x << "," << y;
            EXPECT_FLOAT_EQ(v[3], 0.0f) << x << "," << y;
        }
    // The same edge horizontal: t = (1, 0), phi = +-pi/2.
    FilterImage h(8, 16, osg::Vec4f(0, 0, 0, 1));
    for (int y = 8; y < 16; ++y)
        for (int x = 0; x < 8; ++x)
            h.set(x, y, osg::Vec4f(1, 1, 1, 1));
    const osg::Vec4f v = StructureTensor::flow(h, 2.0f, kClamp).get(3, 8);
    EXPECT_FLOAT_EQ(v[0], 1.0f);
    EXPECT_FLOAT_EQ(v[1], 0.0f);
    EXPECT_FLOAT_EQ(v[2], 1.0f);
    EXPECT_NEAR(std::fabs(v[3]), float(M_PI / 2), 1e-6f);
}

TEST(StructureTensorTest, FlowIsUndefinedInFlatAndIsotropicRegionsAndFallsBack)
{
    // Flat: all zero -> t = (0, 1), A = 0.
    EXPECT_EQ(StructureTensor::flowOf(0, 0, 0), osg::Vec4f(0, 1, 0, 0));
    // Isotropic (a corner-like tensor E = G, F = 0): A = 0, same fallback.
    EXPECT_EQ(StructureTensor::flowOf(0.5f, 0.0f, 0.5f), osg::Vec4f(0, 1, 0, 0));
    // Nearly isotropic: A small, t a unit vector.
    const osg::Vec4f n = StructureTensor::flowOf(0.5f, 0.001f, 0.5f);
    EXPECT_NEAR(n[2], 0.002f, 1e-5f); // (l1 - l2) / (l1 + l2) = 2 F / (E + G)
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1], 1.0f, 1e-6f);
    const FilterImage f =
        StructureTensor::flow(FilterImage(8, 8, osg::Vec4f(0.3f, 0.6f, 0.9f, 1)), 2.0f, kRepeat);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_EQ(f.get(x, y), osg::Vec4f(0, 1, 0, 0));
    // Eigenvectors: t is orthogonal to the major eigenvector; A in [0, 1] for
    // random tensors.
    for (int i = 0; i < 200; ++i)
    {
        const float E = float((i * 37) % 101) / 100.0f, G = float((i * 53) % 97) / 96.0f;
        const float F = (float((i * 29) % 89) / 88.0f - 0.5f) * 2.0f * std::sqrt(E * G);
        const osg::Vec4f v = StructureTensor::flowOf(E, F, G);
        EXPECT_GE(v[2], 0.0f);
        EXPECT_LE(v[2], 1.0f + 1e-6f);
        EXPECT_TRUE(v[1] > 0.0f || (v[1] == 0.0f && v[0] > 0.0f));
        // The tangent is an eigenvector of the smaller eigenvalue: T t = l2 t.
        const float l2 = 0.5f * (E + G - std::sqrt((E - G) * (E - G) + 4 * F * F));
        if (v[2] > 0.0f)
        {
            EXPECT_NEAR(E * v[0] + F * v[1], l2 * v[0], 1e-5f) << E << " " << F << " " << G;
            EXPECT_NEAR(F * v[0] + G * v[1], l2 * v[1], 1e-5f) << E << " " << F << " " << G;
        }
    }
}

TEST(StructureTensorTest, WrapModesDecideTheBorderDerivatives)
{
    // A vertical step at column 0 of a repeated image: under repeat the wrap seam
    // (column 15 to 0) is an edge too; under clamp and mirror there is none at
    // the image border.
    const FilterImage img = verticalStep(16, 4, 8);
    EXPECT_GT(StructureTensor::tensor(img, kRepeat).get(0, 1)[0], 0.7f);
    EXPECT_GT(StructureTensor::tensor(img, kRepeat).get(15, 1)[0], 0.7f);
    EXPECT_EQ(StructureTensor::tensor(img, kClamp).get(0, 1)[0], 0.0f);
    EXPECT_EQ(StructureTensor::tensor(img, kMirror).get(15, 1)[0], 0.0f);
    // Repeat-wrapped filtering equals the centre of the filtered 3x3 tiling.
    FilterImage noise(12, 10);
    unsigned s = 12345;
    for (float& v : noise.data())
    {
        s = s * 1664525u + 1013904223u;
        v = float(s >> 8) / float(1u << 24);
    }
    FilterImage tiled(36, 30);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 36; ++x)
            tiled.set(x, y, noise.get(x % 12, y % 10));
    const FilterImage a = StructureTensor::smoothedTensor(noise, 1.5f, kRepeat);
    const FilterImage b = StructureTensor::smoothedTensor(tiled, 1.5f, kClamp);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 12; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a.get(x, y)[c], b.get(x + 12, y + 10)[c], 1e-6f);
}

TEST(StructureTensorTest, GpuPassListsChainAndRemapInputs)
{
    const std::vector<GpuFilterPass> st = StructureTensor::tensorPasses(2.0f, -1, 3);
    ASSERT_EQ(st.size(), 3u);
    EXPECT_EQ(st[0].shader, "loa_filter_tensor.comp.glsl");
    EXPECT_EQ(st[0].inputs, std::vector<int>{-1});
    EXPECT_EQ(st[0].radius, 1);
    EXPECT_EQ(st[1].shader, "loa_filter_gaussian.comp.glsl");
    EXPECT_EQ(st[1].inputs, std::vector<int>{3});
    EXPECT_EQ(st[2].inputs, std::vector<int>{4});
    EXPECT_EQ(st[2].radius, 6);
    const std::vector<GpuFilterPass> fl = StructureTensor::flowPasses(0.0f, 2, 5);
    ASSERT_EQ(fl.size(), 2u);
    EXPECT_EQ(fl[0].inputs, std::vector<int>{2});
    EXPECT_EQ(fl[1].inputs, std::vector<int>{5});
}

// ---------------------------------------------------------------------------------------------
// Helpers for the filters.

namespace
{
/** The image tiled 3x3 (repeat), or with mirrored neighbours (mirror: GL_MIRRORED_REPEAT repeats
 *  the edge texel, so the flipped copies sit edge to edge), or padded by n texels of clamped
 *  border (clamp). Filtering it with any border and taking the centre equals filtering the image
 *  with that wrap mode, as long as the filter reaches less than one image size. */
FilterImage extended(const FilterImage& img, WrapMode mode)
{
    const int w = img.width(), h = img.height();
    FilterImage out(3 * w, 3 * h);
    for (int y = 0; y < 3 * h; ++y)
        for (int x = 0; x < 3 * w; ++x)
            out.set(x, y, img.fetch(x - w, y - h, ImageBorder(mode, mode)));
    return out;
}

float centreDifference(const FilterImage& a, const FilterImage& big)
{
    float d = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 4; ++c)
                d = std::max(d, std::fabs(a.get(x, y)[c] - big.get(x + a.width(), y + a.height())[c]));
    return d;
}

/** Connected fragments (8-neighbourhood) of "line" texels (red < 0.5) and the line texel count. */
std::pair<int, int> lineFragments(const FilterImage& img)
{
    const int w = img.width(), h = img.height();
    std::vector<int> label(std::size_t(w) * std::size_t(h), 0);
    int fragments = 0, pixels = 0;
    auto line = [&](int x, int y) { return img.get(x, y)[0] < 0.5f; };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            if (!line(x, y)) continue;
            ++pixels;
            if (label[std::size_t(y * w + x)]) continue;
            ++fragments;
            std::vector<std::pair<int, int>> stack{{x, y}};
            label[std::size_t(y * w + x)] = fragments;
            while (!stack.empty())
            {
                const auto [cx, cy] = stack.back();
                stack.pop_back();
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                    {
                        const int nx = cx + dx, ny = cy + dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h || !line(nx, ny)) continue;
                        int& l = label[std::size_t(ny * w + nx)];
                        if (l) continue;
                        l = fragments;
                        stack.push_back({nx, ny});
                    }
            }
        }
    return {fragments, pixels};
}

/** The number of line fragments of at most maxSize texels (speckles). */
int smallFragments(const FilterImage& img, int maxSize)
{
    const int w = img.width(), h = img.height();
    std::vector<char> seen(std::size_t(w) * std::size_t(h), 0);
    int count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            if (img.get(x, y)[0] >= 0.5f || seen[std::size_t(y * w + x)]) continue;
            int size = 0;
            std::vector<std::pair<int, int>> stack{{x, y}};
            seen[std::size_t(y * w + x)] = 1;
            while (!stack.empty())
            {
                const auto [cx, cy] = stack.back();
                stack.pop_back();
                ++size;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                    {
                        const int nx = cx + dx, ny = cy + dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h || img.get(nx, ny)[0] >= 0.5f) continue;
                        char& s = seen[std::size_t(ny * w + nx)];
                        if (s) continue;
                        s = 1;
                        stack.push_back({nx, ny});
                    }
            }
            count += size <= maxSize;
        }
    return count;
}

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/** Writes, reads, writes again; the two files must be the same bytes. */
osg::ref_ptr<ImageFilter> roundTrip(const ImageFilter& filter, const std::string& dir, const std::string& ext)
{
    const std::string first = dir + "/" + filter.filterName() + "-first." + ext;
    const std::string second = dir + "/" + filter.filterName() + "-second." + ext;
    EXPECT_TRUE(osgDB::writeObjectFile(filter, first)) << first;
    osg::ref_ptr<ImageFilter> back = dynamic_cast<ImageFilter*>(osgDB::readRefObjectFile(first).get());
    EXPECT_TRUE(back.valid()) << first;
    if (!back) return back;
    EXPECT_TRUE(osgDB::writeObjectFile(*back, second)) << second;
    EXPECT_FALSE(fileBytes(first).empty());
    EXPECT_EQ(fileBytes(first), fileBytes(second)) << ext;
    return back;
}

double seconds(const std::function<void()>& f)
{
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

// ---------------------------------------------------------------------------------------------
// DoGFilter

TEST(DoGFilterTest, StepGivesALineOnTheDarkSideAndWhiteElsewhere)
{
    // A vertical step from black (L* 0) to white (L* 100) at column 20.
    const FilterImage img = verticalStep(40, 16, 20);
    for (bool flow : {false, true})
    {
        osg::ref_ptr<DoGFilter> dog = new DoGFilter;
        dog->setFlow(flow);
        const FilterImage out = dog->apply(img, kClamp);
        for (int y = 0; y < 16; ++y)
        {
            // The outer kernel reaches ceil(3 * 1.6) = 5 texels: columns <= 14 see only L* = 0,
            // u = 0 >= epsilon: white. The bright side has u > 0: white.
            for (int x = 0; x <= 14; ++x)
                EXPECT_EQ(out.get(x, y)[0], 1.0f) << flow << " " << x << "," << y;
            for (int x = 20; x < 40; ++x)
                EXPECT_EQ(out.get(x, y)[0], 1.0f) << flow << " " << x << "," << y;
            // The line: the four dark columns next to the step are black (hand computation with the
            // erf: u(19) ~ -6.5, u(17) ~ -5 L* units, 1 + tanh(2 u) < 0.01; column 16: 0.013).
            for (int x = 16; x <= 19; ++x)
                EXPECT_LT(out.get(x, y)[0], x == 16 ? 0.02f : 0.01f) << flow << " " << x << "," << y;
            EXPECT_EQ(out.get(3, y)[1], out.get(3, y)[0]); // grey
            EXPECT_EQ(out.get(3, y)[3], 1.0f);             // alpha kept
        }
    }
    // Along a straight step the FDoG is the isotropic DoG: the 1-D kernel across the edge is
    // the separable Gaussian's, the flow smoothing averages equal values.
    osg::ref_ptr<DoGFilter> a = new DoGFilter, b = new DoGFilter;
    a->setFlow(false);
    a->setPhi(0.05f); // soft, so that the comparison sees the response and not just 0 and 1
    b->setPhi(0.05f);
    const float d = FilterImage::maxAbsDifference(a->apply(img, kClamp), b->apply(img, kClamp));
    EXPECT_LT(d, 2e-3f);
    std::printf("[ measured ] DoG vs FDoG on a straight step (phi 0.05): max |diff| %.2g\n", d);
}

TEST(DoGFilterTest, ConstantImagesStayConstantWhiteInEdgesMode)
{
    for (float v : {0.0f, 0.3f, 1.0f})
    {
        const FilterImage img(20, 14, osg::Vec4f(v, v, v, 0.5f));
        for (bool flow : {false, true})
        {
            osg::ref_ptr<DoGFilter> dog = new DoGFilter;
            dog->setFlow(flow);
            const FilterImage out = dog->apply(img, kRepeat);
            for (int y = 0; y < 14; ++y)
                for (int x = 0; x < 20; ++x)
                    EXPECT_EQ(out.get(x, y), osg::Vec4f(1, 1, 1, 0.5f)) << v << " " << flow;
            // XDoG mode: continuous tone, u = L*, T(L*) everywhere.
            dog->setMode(DoGFilter::XDOG);
            dog->setEpsilon(60.0f);
            dog->setPhi(0.1f);
            const FilterImage tone = dog->apply(img, kRepeat);
            const float L = FlowBilateralFilter::rgbToLab(osg::Vec3f(v, v, v))[0];
            const float expected = L >= 60.0f ? 1.0f : 1.0f + std::tanh(0.1f * (L - 60.0f));
            for (int y = 0; y < 14; ++y)
                for (int x = 0; x < 20; ++x)
                    EXPECT_NEAR(tone.get(x, y)[0], expected, 2e-4f) << v << " " << flow;
        }
    }
}

TEST(DoGFilterTest, XDoGThresholdIsTheSoftStepOfWinnemoeller2012)
{
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    dog->setEpsilon(0.5f);
    dog->setPhi(2.0f);
    EXPECT_EQ(dog->threshold(0.5f), 1.0f);
    EXPECT_EQ(dog->threshold(7.0f), 1.0f);
    EXPECT_NEAR(dog->threshold(0.0f), 1.0f + std::tanh(-1.0f), 1e-6f); // 0.2384
    EXPECT_NEAR(dog->threshold(-1000.0f), 0.0f, 1e-6f);
    dog->setPhi(0.0f); // phi 0: everything below epsilon is 1 + tanh(0) = 1
    EXPECT_EQ(dog->threshold(-3.0f), 1.0f);
    // Mode xdog scales D by 1 / (1 - tau) = 1 + p.
    dog->setTau(0.95f);
    EXPECT_FLOAT_EQ(dog->responseScale(), 1.0f);
    dog->setMode(DoGFilter::XDOG);
    EXPECT_NEAR(dog->responseScale(), 20.0f, 1e-4f);
    // XDoG on a step (continuous tone): the dark side is darkened next to the edge, the bright
    // side brightened (sharpening), flat parts are T(L*).
    osg::ref_ptr<DoGFilter> x = new DoGFilter;
    x->setMode(DoGFilter::XDOG);
    x->setFlow(false);
    x->setTau(0.95f);
    x->setEpsilon(50.0f);
    x->setPhi(0.05f);
    FilterImage img(40, 8, osg::Vec4f(0.4f, 0.4f, 0.4f, 1)); // L* 43.2
    for (int y = 0; y < 8; ++y)
        for (int c = 20; c < 40; ++c)
            img.set(c, y, osg::Vec4f(0.6f, 0.6f, 0.6f, 1)); // L* 63.2
    const FilterImage out = x->apply(img, kClamp);
    const float flatDark = 1.0f + std::tanh(0.05f * (43.22f - 50.0f));
    EXPECT_NEAR(out.get(5, 4)[0], flatDark, 2e-3f);
    EXPECT_LT(out.get(19, 4)[0], flatDark - 0.2f);
    EXPECT_EQ(out.get(20, 4)[0], 1.0f);
    EXPECT_EQ(out.get(35, 4)[0], 1.0f);
}

TEST(DoGFilterTest, OnNoiseDoGSpecklesWhereFDoGDrawsCoherentLines)
{
    // Known failure regime (Kang et al. 2007 Fig. 7; Kyprianidis & Döllner 2008 Fig. 9): the
    // isotropic DoG of a noisy image breaks lines into short fragments and scatters speckles;
    // the FDoG, averaging along the flow, draws fewer, longer, coherent lines. The image: a disc
    // and diagonal stripes (contrast 0.3 and 0.15) plus uniform noise of amplitude 0.2.
    const int n = 128;
    const FilterImage nz = noise(n, n, 99);
    FilterImage img(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
        {
            const float dx = float(x) - 64.0f, dy = float(y) - 64.0f;
            const bool disc = dx * dx + dy * dy < 900.0f;
            float v = disc ? 0.65f : 0.35f;
            if (((x + y) / 12) % 2 == 0 && !disc) v += 0.15f;
            v += 0.2f * (nz.get(x, y)[0] - 0.5f);
            img.set(x, y, osg::Vec4f(v, v, v, 1));
        }
    osg::ref_ptr<DoGFilter> dog = new DoGFilter, fdog = new DoGFilter;
    dog->setFlow(false);
    const FilterImage a = dog->apply(img, kMirror), b = fdog->apply(img, kMirror);
    const auto [dogFragments, dogPixels] = lineFragments(a);
    const auto [fdogFragments, fdogPixels] = lineFragments(b);
    const int dogSpeckles = smallFragments(a, 8), fdogSpeckles = smallFragments(b, 8);
    std::printf(
        "[ measured ] %dx%d noisy disc+stripes: DoG %d fragments (%d of <= 8 texels) / %d line texels, "
        "FDoG %d (%d) / %d\n",
        n, n, dogFragments, dogSpeckles, dogPixels, fdogFragments, fdogSpeckles, fdogPixels);
    EXPECT_LT(fdogFragments * 4, dogFragments);
    EXPECT_LT(fdogSpeckles * 8, dogSpeckles);
    const double dogMean = double(dogPixels) / dogFragments, fdogMean = double(fdogPixels) / fdogFragments;
    EXPECT_GT(fdogMean, 3.0 * dogMean); // longer lines
}

TEST(DoGFilterTest, FlatRegionsWithoutFlowFallBackGracefully)
{
    // A flat image with one small bright square: the flow is undefined (A = 0, t = (0, 1)) away
    // from the square; the FDoG is white and finite there, and draws the square's outline.
    FilterImage img(32, 32, osg::Vec4f(0.2f, 0.2f, 0.2f, 1));
    for (int y = 14; y < 18; ++y)
        for (int x = 14; x < 18; ++x)
            img.set(x, y, osg::Vec4f(0.9f, 0.9f, 0.9f, 1));
    osg::ref_ptr<DoGFilter> fdog = new DoGFilter;
    const FilterImage flow = StructureTensor::flow(img, fdog->getRho(), kClamp);
    EXPECT_EQ(flow.get(2, 2)[2], 0.0f);
    const FilterImage out = fdog->apply(img, kClamp);
    int dark = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
        {
            const float v = out.get(x, y)[0];
            ASSERT_TRUE(std::isfinite(v));
            if (std::abs(x - 16) > 10 || std::abs(y - 16) > 10)
            {
                EXPECT_EQ(v, 1.0f) << x << "," << y;
            }
            dark += v < 0.5f;
        }
    EXPECT_GT(dark, 16); // the outline around the square
}

TEST(DoGFilterTest, WrapModesEqualFilteringTheExtendedImage)
{
    // The isotropic DoG: every wrap mode equals filtering the extended image (3x3 tiling, mirrored
    // tiling, clamped padding) and taking the centre.
    const FilterImage img = noise(24, 20, 7);
    for (WrapMode m : {WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp})
    {
        osg::ref_ptr<DoGFilter> dog = new DoGFilter;
        dog->setFlow(false);
        dog->setPhi(0.1f); // soft: differences show
        const FilterImage a = dog->apply(img, ImageBorder(m, m));
        const FilterImage b = dog->apply(extended(img, m), kClamp);
        EXPECT_LT(centreDifference(a, b), 1e-4f) << ImageBorder::name(m);
    }
    // The FDoG under repeat equals the tiled image's: a repeating texture has no seam.
    osg::ref_ptr<DoGFilter> fdog = new DoGFilter;
    fdog->setPhi(0.1f);
    fdog->setRho(1.0f); // reach 1 + 3 + 3 + 6 + 10 < 20
    EXPECT_LT(
        centreDifference(fdog->apply(img, kRepeat), fdog->apply(extended(img, WrapMode::Repeat), kClamp)),
        1e-4f);
    // Mirror and clamp extend the tensor (the flow field), not the image: the tensor read past
    // the border is the border's tensor, where the mirrored image's would have F negated and the
    // clamped image's has no derivative across the border. The results differ from the extended
    // image's only within the filter's reach of the border.
    const FilterImage big = noise(64, 56, 8);
    const int reach = fdog->dependencyRadius();
    for (WrapMode m : {WrapMode::Mirror, WrapMode::Clamp})
    {
        const FilterImage a = fdog->apply(big, ImageBorder(m, m));
        const FilterImage b = fdog->apply(extended(big, m), kClamp);
        float inner = 0, band = 0;
        for (int y = 0; y < 56; ++y)
            for (int x = 0; x < 64; ++x)
            {
                const float d = std::fabs(a.get(x, y)[0] - b.get(x + 64, y + 56)[0]);
                const bool interior = x >= reach && y >= reach && x < 64 - reach && y < 56 - reach;
                (interior ? inner : band) = std::max(interior ? inner : band, d);
            }
        EXPECT_LT(inner, 1e-4f) << ImageBorder::name(m);
        std::printf("[ measured ] FDoG %s border band (%d texels) vs the extended image: max |diff| %.3f\n",
                    ImageBorder::name(m), reach, band);
    }
}

TEST(DoGFilterTest, ParametersRegistryAndErrors)
{
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    EXPECT_EQ(dog->getParameterString(),
              "dog:sigma_e=1,k=1.6,tau=0.99,epsilon=0,phi=2,sigma_m=3,rho=2,flow=1,mode=edges");
    dog->setParameter("mode", "xdog");
    EXPECT_EQ(dog->getMode(), DoGFilter::XDOG);
    dog->setParameter("flow", 0.0);
    EXPECT_FALSE(dog->getFlow());
    EXPECT_THROW(dog->setParameter("tau", 1.0), std::invalid_argument); // 1 / (1 - tau)
    EXPECT_THROW(dog->setParameter("sigma_e", 0.0), std::invalid_argument);
    EXPECT_THROW(dog->setParameter("flow", 0.5), std::invalid_argument);
    EXPECT_THROW(dog->setParameter("mode", "lines"), std::invalid_argument);
    EXPECT_THROW(dog->setParameter("sigma", 1.0), std::invalid_argument);
    dog->setTau(1.5f); // set directly: refused when used
    EXPECT_THROW(dog->apply(FilterImage(4, 4), kClamp), std::invalid_argument);

    osg::ref_ptr<ImageFilter> f = FilterRegistry::create("dog:sigma_e=1.5,flow=0,mode=xdog,epsilon=40");
    ASSERT_TRUE(f.valid());
    const DoGFilter* d = dynamic_cast<const DoGFilter*>(f.get());
    ASSERT_NE(d, nullptr);
    EXPECT_FLOAT_EQ(d->getSigmaE(), 1.5f);
    EXPECT_FALSE(d->getFlow());
    EXPECT_EQ(d->getMode(), DoGFilter::XDOG);
    EXPECT_FLOAT_EQ(d->getEpsilon(), 40.0f);
    EXPECT_FALSE(FilterRegistry::description("dog").empty());

    // The pass lists: isotropic 3 (Lab, two blurs); flow: Lab, tensor (3), across, along.
    EXPECT_EQ(d->gpuPasses().size(), 3u);
    osg::ref_ptr<DoGFilter> g = new DoGFilter;
    const std::vector<GpuFilterPass> p = g->gpuPasses();
    ASSERT_EQ(p.size(), 6u);
    EXPECT_EQ(p[4].inputs, (std::vector<int>{0, 3}));
    EXPECT_EQ(p[5].inputs, (std::vector<int>{4, 3}));
    EXPECT_EQ(g->dependencyRadius(), 1 + 6 + 6 + 6 + 10);
}

TEST(DoGFilterTest, SerializerRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FlowFiltersDoG");
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    dog->setSigmaE(1.25f);
    dog->setK(2.0f);
    dog->setTau(0.95f);
    dog->setEpsilon(30.0f);
    dog->setPhi(0.25f);
    dog->setSigmaM(2.5f);
    dog->setRho(1.5f);
    dog->setFlow(false);
    dog->setMode(DoGFilter::XDOG);
    for (const char* ext : {"osgt", "osgb"})
    {
        osg::ref_ptr<ImageFilter> back = roundTrip(*dog, dir, ext);
        ASSERT_TRUE(back.valid());
        EXPECT_EQ(back->getParameterString(), dog->getParameterString()) << ext;
    }
    osg::ref_ptr<DoGFilter> def = new DoGFilter;
    osg::ref_ptr<ImageFilter> back = roundTrip(*def, dir, "osgt");
    ASSERT_TRUE(back.valid());
    EXPECT_EQ(back->getParameterString(), def->getParameterString());
}

// ---------------------------------------------------------------------------------------------
// FlowBilateralFilter

TEST(FlowBilateralFilterTest, CieLabConversionMatchesReferenceValues)
{
    const osg::Vec3f white = FlowBilateralFilter::rgbToLab(osg::Vec3f(1, 1, 1));
    EXPECT_NEAR(white[0], 100.0f, 1e-3f);
    EXPECT_NEAR(white[1], 0.0f, 1e-3f);
    EXPECT_NEAR(white[2], 0.0f, 1e-3f);
    // sRGB red, green, blue (Lindbloom's calculator, D65): (53.24, 80.09, 67.20), (87.73,
    // -86.18, 83.18), (32.30, 79.19, -107.86).
    const osg::Vec3f r = FlowBilateralFilter::rgbToLab(osg::Vec3f(1, 0, 0));
    const osg::Vec3f g = FlowBilateralFilter::rgbToLab(osg::Vec3f(0, 1, 0));
    const osg::Vec3f b = FlowBilateralFilter::rgbToLab(osg::Vec3f(0, 0, 1));
    EXPECT_NEAR(r[0], 53.24f, 0.01f);
    EXPECT_NEAR(r[1], 80.09f, 0.01f);
    EXPECT_NEAR(r[2], 67.20f, 0.01f);
    EXPECT_NEAR(g[0], 87.73f, 0.01f);
    EXPECT_NEAR(g[1], -86.18f, 0.01f);
    EXPECT_NEAR(g[2], 83.18f, 0.01f);
    EXPECT_NEAR(b[0], 32.30f, 0.01f);
    EXPECT_NEAR(b[1], 79.19f, 0.01f);
    EXPECT_NEAR(b[2], -107.86f, 0.01f);
    EXPECT_NEAR(FlowBilateralFilter::rgbToLab(osg::Vec3f(0.5f, 0.5f, 0.5f))[0], 53.39f, 0.01f);
    // Round trip.
    float worst = 0;
    for (int i = 0; i < 1000; ++i)
    {
        const osg::Vec3f c(float(i % 10) / 9.0f, float((i / 10) % 10) / 9.0f, float(i / 100) / 9.0f);
        const osg::Vec3f back = FlowBilateralFilter::labToRgb(FlowBilateralFilter::rgbToLab(c));
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::fabs(back[k] - c[k]));
    }
    EXPECT_LT(worst, 2e-5f);
}

TEST(FlowBilateralFilterTest, ConstantStaysConstantAndNaZeroIsTheIdentity)
{
    const FilterImage img(20, 16, osg::Vec4f(0.2f, 0.5f, 0.7f, 0.25f));
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    const FilterImage out = f->apply(img, kRepeat);
    EXPECT_LT(FilterImage::maxAbsDifference(out, img, true), 1e-5f);
    const FilterImage nz = noise(20, 16, 3);
    f->setNa(0);
    EXPECT_LT(FilterImage::maxAbsDifference(f->apply(nz, kClamp), nz, true), 2e-5f);
    EXPECT_EQ(f->gpuPasses().size(), 2u); // Lab and back: no tensor without iterations
}

TEST(FlowBilateralFilterTest, SmoothsNoiseAndKeepsTheStepEdge)
{
    // Two flat colours (Lab distance ~ 47) with noise of +-0.04: the filter removes most of the
    // noise on each side and keeps the step (sigma_r = 5 << 47).
    const int w = 40, h = 24, x0 = 20;
    const FilterImage nz = noise(w, h, 11);
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const float base = x < x0 ? 0.3f : 0.7f;
            const float v = base + 0.08f * (nz.get(x, y)[0] - 0.5f);
            img.set(x, y, osg::Vec4f(v, v, v, 1));
        }
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    const FilterImage out = f->apply(img, kMirror);
    auto spread = [&](const FilterImage& im, int xa, int xb)
    {
        double s = 0, s2 = 0;
        int n = 0;
        for (int y = 0; y < h; ++y)
            for (int x = xa; x < xb; ++x, ++n)
            {
                s += im.get(x, y)[0];
                s2 += double(im.get(x, y)[0]) * im.get(x, y)[0];
            }
        return std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)));
    };
    const double before = spread(img, 2, x0 - 2), after = spread(out, 2, x0 - 2);
    std::printf(
        "[ measured ] flow bilateral on a noisy step: std %.4f -> %.4f (left), %.4f -> %.4f (right)\n",
        before, after, spread(img, x0 + 2, w - 2), spread(out, x0 + 2, w - 2));
    EXPECT_LT(after, 0.25 * before);
    EXPECT_LT(spread(out, x0 + 2, w - 2), 0.25 * spread(img, x0 + 2, w - 2));
    // The step stays a step: the columns next to it keep their side's level.
    for (int y = 0; y < h; ++y)
    {
        EXPECT_NEAR(out.get(x0 - 1, y)[0], 0.3f, 0.03f) << y;
        EXPECT_NEAR(out.get(x0, y)[0], 0.7f, 0.03f) << y;
    }
}

TEST(FlowBilateralFilterTest, SmoothsAlongTheEdgeNotAcrossIt)
{
    // A diagonal stripe pattern with a weak contrast (below sigma_r): the isotropic-looking
    // bilateral would blur it away; the orientation-aligned filter smooths along the stripes
    // (the 1-D pass along g averages across, along t along). Compare the contrast after the
    // tangent pass alone with that after the gradient pass alone.
    const int n = 48;
    FilterImage img(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
        {
            const float v = 0.5f + 0.03f * std::sin(float(x + y) * 0.6f);
            img.set(x, y, osg::Vec4f(v, v, v, 1));
        }
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    f->setSigmaR(20.0f);
    const FilterImage tensor = StructureTensor::smoothedTensor(img, 2.0f, kRepeat);
    const FilterImage flow = StructureTensor::flow(tensor);
    // The tangent of stripes x + y = const is (1, -1)/sqrt2 -> canonical (-1, 1)/sqrt2.
    EXPECT_NEAR(flow.get(20, 20)[0], -std::sqrt(0.5f), 1e-3f);
    EXPECT_NEAR(flow.get(20, 20)[1], std::sqrt(0.5f), 1e-3f);
    const FilterImage lab = FlowBilateralFilter::toLab(img);
    const FilterImage along = f->bilateralPass(lab, tensor, 1, kRepeat);
    const FilterImage across = f->bilateralPass(lab, tensor, 0, kRepeat);
    float amplitudeIn = 0, amplitudeAlong = 0, amplitudeAcross = 0;
    for (int x = 10; x < 38; ++x)
    {
        amplitudeIn = std::max(amplitudeIn, std::fabs(lab.get(x, 24)[0] - 53.39f));
        amplitudeAlong = std::max(amplitudeAlong, std::fabs(along.get(x, 24)[0] - 53.39f));
        amplitudeAcross = std::max(amplitudeAcross, std::fabs(across.get(x, 24)[0] - 53.39f));
    }
    std::printf("[ measured ] stripe amplitude (L*) %.3f: along t %.3f, across (along g) %.3f\n", amplitudeIn,
                amplitudeAlong, amplitudeAcross);
    EXPECT_NEAR(amplitudeAlong, amplitudeIn, 0.02f * amplitudeIn);
    EXPECT_LT(amplitudeAcross, 0.3f * amplitudeIn);
}

TEST(FlowBilateralFilterTest, NeMattersOnlyWithTheEdgeOverlay)
{
    const FilterImage img = verticalStep(32, 12, 16, 0.8f);
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    f->setNa(2);
    f->setNe(0);
    const FilterImage a = f->apply(img, kClamp);
    f->setNe(3);
    EXPECT_EQ(FilterImage::maxAbsDifference(a, f->apply(img, kClamp), true), 0.0f);
    // With edges: the colour output times the FDoG edges (black line on the dark side).
    f->setEdges(FlowBilateralFilter::FDOG_EDGES);
    f->setNe(1);
    const FilterImage e = f->apply(img, kClamp);
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    const FilterImage edges = dog->flowDoG(
        f->bilateralPass(f->bilateralPass(FlowBilateralFilter::toLab(img),
                                          StructureTensor::smoothedTensor(img, 2.0f, kClamp), 0, kClamp),
                         StructureTensor::smoothedTensor(img, 2.0f, kClamp), 1, kClamp),
        StructureTensor::smoothedTensor(img, 2.0f, kClamp), kClamp);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(e.get(x, y)[c], a.get(x, y)[c] * edges.get(x, y)[0], 1e-6f) << x << "," << y;
    EXPECT_LT(e.get(15, 5)[0], 0.01f); // the line
    // The step is sharp already, so ne changes the edges little, but the overlay is recomputed.
    f->setNe(4);
    EXPECT_LT(FilterImage::maxAbsDifference(e, f->apply(img, kClamp)), 0.2f);
}

TEST(FlowBilateralFilterTest, WrapModesEqualFilteringTheExtendedImage)
{
    // Repeat: the 3x3 tiling's centre (no seam). Mirror and clamp extend the tensor, not the
    // image (see DoGFilterTest.WrapModesEqualFilteringTheExtendedImage): equal in the interior.
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    f->setRho(1.0f);
    f->setNa(1);
    f->setSigmaD(2.0f);
    f->setSigmaR(20.0f); // reach 1 + 3 + 3 + 5 + 5 < 20
    const FilterImage img = noise(24, 20, 5);
    EXPECT_LT(centreDifference(f->apply(img, kRepeat), f->apply(extended(img, WrapMode::Repeat), kClamp)),
              1e-4f);
    const FilterImage big = noise(48, 44, 6);
    const int reach = f->dependencyRadius();
    for (WrapMode m : {WrapMode::Mirror, WrapMode::Clamp})
    {
        const FilterImage a = f->apply(big, ImageBorder(m, m));
        const FilterImage b = f->apply(extended(big, m), kClamp);
        float inner = 0;
        for (int y = reach; y < 44 - reach; ++y)
            for (int x = reach; x < 48 - reach; ++x)
                for (int c = 0; c < 4; ++c)
                    inner = std::max(inner, std::fabs(a.get(x, y)[c] - b.get(x + 48, y + 44)[c]));
        EXPECT_LT(inner, 1e-4f) << ImageBorder::name(m);
    }
}

TEST(FlowBilateralFilterTest, ParametersRegistryAndErrors)
{
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    EXPECT_EQ(f->getParameterString(), "flow_bilateral:rho=2,ne=1,na=4,sigma_d=4,sigma_r=5,edges=none");
    EXPECT_THROW(f->setParameter("na", 1.5), std::invalid_argument);
    EXPECT_THROW(f->setParameter("na", -1.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("sigma_d", 0.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("sigma_r", 1000.0), std::invalid_argument);
    EXPECT_THROW(f->setParameter("edges", "dog"), std::invalid_argument);
    f->setParameter("edges", "fdog");
    EXPECT_EQ(f->getEdges(), FlowBilateralFilter::FDOG_EDGES);
    f->setSigmaD(-1.0f);
    EXPECT_THROW(f->apply(FilterImage(4, 4), kClamp), std::invalid_argument);

    osg::ref_ptr<ImageFilter> g = FilterRegistry::create("flow_bilateral:na=2,sigma_r=4.25");
    const FlowBilateralFilter* fb = dynamic_cast<const FlowBilateralFilter*>(g.get());
    ASSERT_NE(fb, nullptr);
    EXPECT_EQ(fb->getNa(), 2);
    EXPECT_FLOAT_EQ(fb->getSigmaR(), 4.25f);
    // Passes: Lab, tensor (3), 2 per iteration, back to sRGB.
    EXPECT_EQ(fb->gpuPasses().size(), 1u + 3u + 4u + 1u);
    EXPECT_EQ(fb->dependencyRadius(), 1 + 6 + 6 + 4 * 9);
    osg::ref_ptr<FlowBilateralFilter> e = new FlowBilateralFilter;
    e->setEdges(FlowBilateralFilter::FDOG_EDGES);
    const std::vector<GpuFilterPass> p = e->gpuPasses();
    ASSERT_EQ(p.size(), 1u + 3u + 8u + 2u + 1u);
    EXPECT_EQ(p[12].inputs, (std::vector<int>{5, 3})); // FDoG of the image after ne = 1 iteration
    EXPECT_EQ(p[14].inputs, (std::vector<int>{11, 13}));
}

TEST(FlowBilateralFilterTest, SerializerRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FlowFiltersBilateral");
    osg::ref_ptr<FlowBilateralFilter> f = new FlowBilateralFilter;
    f->setRho(1.5f);
    f->setNe(2);
    f->setNa(3);
    f->setSigmaD(3.0f);
    f->setSigmaR(4.25f);
    f->setEdges(FlowBilateralFilter::FDOG_EDGES);
    for (const char* ext : {"osgt", "osgb"})
    {
        osg::ref_ptr<ImageFilter> back = roundTrip(*f, dir, ext);
        ASSERT_TRUE(back.valid());
        EXPECT_EQ(back->getParameterString(), f->getParameterString()) << ext;
    }
}

TEST(FlowFiltersTest, CpuTimings256)
{
    const FilterImage img = noise(256, 256, 1);
    osg::ref_ptr<DoGFilter> dog = new DoGFilter, fdog = new DoGFilter;
    dog->setFlow(false);
    osg::ref_ptr<FlowBilateralFilter> fb = new FlowBilateralFilter;
    const double tTensor = seconds([&] { StructureTensor::flow(img, 2.0f, kClamp); });
    const double tDog = seconds([&] { dog->apply(img, kClamp); });
    const double tFdog = seconds([&] { fdog->apply(img, kClamp); });
    const double tFb = seconds([&] { fb->apply(img, kClamp); });
    std::printf("[ measured ] CPU 256x256: tensor+flow (rho 2) %.3f s, DoG %.3f s, FDoG %.3f s, "
                "flow_bilateral (defaults: na 4) %.3f s\n",
                tTensor, tDog, tFdog, tFb);
    SUCCEED();
}
