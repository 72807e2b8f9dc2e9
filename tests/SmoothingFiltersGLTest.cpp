// The GPU passes of the smoothing filters (bilateral, guided, domain transform, quantization) against their
// CPU references, on a real photograph crop and a synthetic image, with every wrap mode; L0 smoothing has
// none and is refused. Prints the GPU and CPU times at 256 x 256.
#include <osgLoA/filtering/BilateralFilter>
#include <osgLoA/filtering/ColorQuantizationFilter>
#include <osgLoA/filtering/DomainTransformFilter>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/GuidedFilter>
#include <osgLoA/filtering/L0Smoothing>
#include <osgLoA/render/HeadlessContext>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

using namespace osgLoA;

namespace
{
using GpuFixture = loatest::GpuFilterFixture;

/** A skimage photograph from the test-data cache or the shared data, or null. */
osg::ref_ptr<osg::Image> photograph(const std::string& name)
{
    for (const std::string& dir : {std::string(LOA_SOURCE_DIR "/data/cache/python3-skimage/"),
                                   std::string(LOA_SOURCE_DIR "/../shared/data/images/")})
        if (osgDB::fileExists(dir + name)) return osgDB::readRefImageFile(dir + name);
    return nullptr;
}

FilterImage crop(const FilterImage& img, int x0, int y0, int w, int h)
{
    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.set(x, y, img.get(x0 + x, y0 + y));
    return out;
}

/** Sinusoids, a hard edge, 8-bit noise and a varying alpha; 8-bit values. */
FilterImage synthetic(int w, int h)
{
    FilterImage img(w, h);
    unsigned seed = 777;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24);
            const float r = 0.5f + 0.4f * std::sin(0.3f * float(x)) * std::cos(0.17f * float(y));
            const float g = x + y > (w + h) / 2 ? 0.85f : 0.15f;
            img.set(x, y, osg::Vec4f(r, g, 0.3f + 0.4f * n, 0.25f + 0.5f * float(x) / float(w)));
        }
    img.quantize8();
    return img;
}

/** The filters and their GPU-vs-CPU bar: max |diff| over RGB <= 1e-4 (1/40 of an 8-bit level, far inside the
 *  2/255 aim). Both sides compute the same float expressions in the same order; what differs is the driver's
 *  exp/pow/tanh, fused multiply-adds and the CPU references' double accumulation (bilateral, guided, domain
 *  transform); measured on llvmpipe: <= 5e-6 (the Lab conversions' pow), <= 1e-6 otherwise. */
const float kBar = 1e-4f;
const std::vector<std::string>& cases()
{
    static const std::vector<std::string> c = {
        "bilateral:sigma_d=2,sigma_r=0.1",
        "bilateral:sigma_d=1.5,sigma_r=6,color_space=lab,range_norm=l1",
        "guided:radius=3,eps=0.005",
        "domain_transform:sigma_s=10,sigma_r=0.2",
        "domain_transform:sigma_s=30,sigma_r=0.5,iterations=2",
        "quantize:levels=8,phi_q=3",
    };
    return c;
}

void compareAll(GpuFixture& gpu, const FilterImage& img, const std::string& label)
{
    const ImageBorder borders[4] = {{WrapMode::Repeat, WrapMode::Repeat},
                                    {WrapMode::Clamp, WrapMode::Clamp},
                                    {WrapMode::Mirror, WrapMode::Mirror},
                                    {WrapMode::Repeat, WrapMode::Mirror}};
    for (const std::string& spec : cases())
    {
        osg::ref_ptr<ImageFilter> f = FilterRegistry::create(spec);
        float worst = 0;
        double meanWorst = 0;
        for (const ImageBorder& border : borders)
        {
            const FilterImage cpu = f->apply(img, border);
            const FilterImage out = gpu.engine->filter(*f, img, border);
            const float d = FilterImage::maxAbsDifference(cpu, out);
            worst = std::max(worst, d);
            meanWorst = std::max(meanWorst, FilterImage::meanAbsDifference(cpu, out));
            EXPECT_LE(d, kBar) << label << " " << spec << " " << ImageBorder::name(border.s) << "/"
                               << ImageBorder::name(border.t);
            // Alpha passes through exactly.
            float alpha = 0;
            for (std::size_t k = 0; k < out.texelCount(); ++k)
                alpha = std::max(alpha, std::fabs(out.data()[k * 4 + 3] - img.data()[k * 4 + 3]));
            EXPECT_EQ(alpha, 0.0f) << label << " " << spec;
        }
        std::printf("GPU vs CPU %-9s %-62s max %.2e (%.3f/255) mean %.1e\n", label.c_str(), spec.c_str(),
                    worst, worst * 255.0f, meanWorst);
    }
}
} // namespace

TEST(SmoothingFiltersGLTest, GpuPassesMatchTheCpuReferencesOnAPhotograph)
{
    osg::ref_ptr<osg::Image> photo = photograph("chelsea.png");
    if (!photo) GTEST_SKIP() << "chelsea.png not found (scripts/fetch-test-data)";
    GpuFixture gpu;
    // 75 x 61: not a multiple of the 8x8 tiles; the cat's eye and fur.
    compareAll(gpu, crop(FilterImage::fromImage(*photo), 140, 60, 75, 61), "chelsea");
}

TEST(SmoothingFiltersGLTest, GpuPassesMatchTheCpuReferencesOnASyntheticImage)
{
    GpuFixture gpu;
    compareAll(gpu, synthetic(45, 37), "synthetic");
}

TEST(SmoothingFiltersGLTest, L0HasNoGpuPassesAndIsRefused)
{
    GpuFixture gpu;
    osg::ref_ptr<L0Smoothing> f = new L0Smoothing;
    EXPECT_THROW(gpu.engine->filter(*f, synthetic(8, 8), ImageBorder()), GpuFilterError);
}

TEST(SmoothingFiltersGLTest, TimingsAt256)
{
    osg::ref_ptr<osg::Image> photo = photograph("astronaut.png");
    const FilterImage img =
        photo ? crop(FilterImage::fromImage(*photo), 128, 64, 256, 256) : synthetic(256, 256);
    GpuFixture gpu;
    const ImageBorder border(WrapMode::Repeat, WrapMode::Repeat);
    for (const char* spec :
         {"bilateral", "bilateral:color_space=lab,sigma_r=5", "guided", "domain_transform", "quantize"})
    {
        osg::ref_ptr<ImageFilter> f = FilterRegistry::create(spec);
        gpu.engine->filter(*f, img, border); // compiles the programs
        auto t0 = std::chrono::steady_clock::now();
        const FilterImage out = gpu.engine->filter(*f, img, border);
        const double tg = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        t0 = std::chrono::steady_clock::now();
        const FilterImage cpu = f->apply(img, border);
        const double tc = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("256x256 %-70s GPU %.3f s (upload, %zu passes, download) CPU %.3f s, max diff %.2e\n",
                    f->getParameterString().c_str(), tg, f->gpuPasses().size(), tc,
                    FilterImage::maxAbsDifference(cpu, out));
        EXPECT_LE(FilterImage::maxAbsDifference(cpu, out), kBar) << spec;
    }
}
