// Post-process filtering (paper 000 Eq. 1, osgLoA::PostProcessFiltering): the children render into
// the frame texture exactly as they render directly; the filter stage computes the filter's CPU
// reference on that frame; the full-screen pass shows it texel for pixel; the textures follow the
// viewport; filters without GPU passes are refused; the filter stage is timed only when asked;
// the node's settings survive .osgt/.osgb round trips.
#include "support/TestSupport.h"

#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/PostProcessFiltering>
#include <osgLoA/render/OffscreenRenderer>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace osgLoA;

namespace
{
/** A deterministic texture: stripes, a checker and noise (content at every frequency). */
osg::ref_ptr<osg::Texture2D> patternTexture(int size)
{
    FilterImage img(size, size);
    unsigned seed = 777;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24);
            const float stripes = 0.5f + 0.45f * std::sin(0.7f * float(x));
            const float checker = ((x / 8 + y / 8) % 2) ? 0.85f : 0.15f;
            img.set(x, y, osg::Vec4f(stripes, checker, 0.3f + 0.6f * n, 1.0f));
        }
    img.quantize8();
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(img.toImage().get());
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    return t;
}

/** A textured, unlit ground plane seen obliquely (near texels magnified, far ones minified). */
osg::ref_ptr<osg::Geode> groundPlane()
{
    osg::ref_ptr<osg::Geometry> g = osg::createTexturedQuadGeometry(osg::Vec3(-20, 0, 0), osg::Vec3(40, 0, 0),
                                                                    osg::Vec3(0, 80, 0), 0, 0, 10, 20);
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    osg::StateSet* ss = geode->getOrCreateStateSet();
    ss->setTextureAttributeAndModes(0, patternTexture(64).get());
    ss->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    return geode;
}

osg::ref_ptr<OffscreenRenderer> renderer(int w, int h, osg::Node* scene)
{
    OffscreenRenderer::Settings s;
    s.width = w;
    s.height = h;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(scene);
    r->setViewMatrixAsLookAt(osg::Vec3d(0, -4, 3), osg::Vec3d(0, 12, 0), osg::Vec3d(0, 0, 1));
    return r;
}

FilterImage fromRender(const osg::Image& img)
{
    return FilterImage::fromImage(img);
}

/** Reads a texture's level 0 as floats (its context current). */
FilterImage readTexture(osg::Texture2D& t, unsigned contextID)
{
    osg::Texture::TextureObject* to = t.getTextureObject(contextID);
    if (!to) return FilterImage();
    FilterImage out(t.getTextureWidth(), t.getTextureHeight());
    glBindTexture(GL_TEXTURE_2D, to->id());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out.data().data());
    glBindTexture(GL_TEXTURE_2D, 0);
    return out;
}

osg::ref_ptr<GaussianFilter> gaussian(float sigma)
{
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(sigma);
    return f;
}

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
} // namespace

TEST(PostProcessFilteringGLTest, TheFrameIsTheDirectRenderingAndAnIdentityFilterShowsItUnchanged)
{
    osg::ref_ptr<osg::Geode> plane = groundPlane();
    osg::ref_ptr<OffscreenRenderer> direct = renderer(160, 120, plane.get());
    const FilterImage reference = fromRender(*direct->renderImage());

    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    post->addChild(plane.get());
    post->setFilter(gaussian(0.0f).get()); // sigma 0 copies the image
    osg::ref_ptr<OffscreenRenderer> r = renderer(160, 120, post.get());
    const FilterImage shown = fromRender(*r->renderImage());
    // The same rasterization and texture sampling, once into RGBA8 and once into RGBA32F then
    // RGBA8: the float frame rounds to the same bytes, except where the 8-bit conversion of the
    // two paths rounds a value at exactly k + 0.5 differently (at most 1/255).
    EXPECT_LE(FilterImage::maxAbsDifference(reference, shown), 1.0f / 255.0f + 1e-6f);
    EXPECT_LT(FilterImage::meanAbsDifference(reference, shown), 0.01 / 255.0);
    EXPECT_EQ(post->getFilteredFrames(), 1u);
    EXPECT_TRUE(post->getLastError().empty()) << post->getLastError();
    // The children's only new parent is the group (the scene camera reaches them through a proxy):
    // paths, bounds and intersections stay the group's. (The other parent is the direct viewer's
    // camera.)
    EXPECT_EQ(plane->getNumParents(), 2u);
    EXPECT_EQ(post->getSceneCamera()->getNumChildren(), 1u);
    EXPECT_NE(post->getSceneCamera()->getChild(0), plane.get());
    EXPECT_TRUE(post->getBound().valid());
}

TEST(PostProcessFilteringGLTest, TheFilterStageComputesTheCpuReferenceOnTheFrame)
{
    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    post->addChild(groundPlane().get());
    osg::ref_ptr<GaussianFilter> f = gaussian(2.0f);
    post->setFilter(f.get());
    osg::ref_ptr<OffscreenRenderer> r = renderer(96, 72, post.get());
    const FilterImage shown = fromRender(*r->renderImage());

    r->getContext()->makeCurrent();
    const unsigned id = r->getContext()->getState()->getContextID();
    const FilterImage frame = readTexture(*post->getFrameTexture(), id);
    const FilterImage filtered = readTexture(*post->getFilteredTexture(), id);
    ASSERT_EQ(frame.width(), 96);
    ASSERT_EQ(frame.height(), 72);
    // F on the frame with clamp-to-edge borders: the engine's passes against the CPU reference
    // (both sum the same products; 1e-5 is what GaussianFilterGLTest holds them to).
    const FilterImage cpu = f->apply(frame, ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    EXPECT_LT(FilterImage::maxAbsDifference(cpu, filtered), 1e-5f);
    // The filter changed something (the frame has texture detail everywhere).
    EXPECT_GT(FilterImage::meanAbsDifference(frame, filtered), 0.01);
    // The full-screen pass shows the filtered frame texel for pixel, rounded to 8 bits.
    FilterImage expected = filtered;
    expected.quantize8();
    EXPECT_LE(FilterImage::maxAbsDifference(expected, shown), 0.5f / 255.0f + 1e-4f);
}

TEST(PostProcessFilteringGLTest, TexturesFollowTheViewportAndEachContextHasItsEngine)
{
    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    post->addChild(groundPlane().get());
    post->setFilter(gaussian(1.5f).get());
    osg::ref_ptr<OffscreenRenderer> a = renderer(64, 48, post.get());
    osg::ref_ptr<OffscreenRenderer> b = renderer(100, 30, post.get());
    const FilterImage first = fromRender(*a->renderImage());
    EXPECT_EQ(post->getFrameTexture()->getTextureWidth(), 64);
    // (Each viewer believes its context is still current from its last frame: make it so.)
    b->getContext()->makeCurrent();
    const FilterImage other = fromRender(*b->renderImage());
    EXPECT_EQ(post->getFrameTexture()->getTextureWidth(), 100);
    EXPECT_EQ(post->getFrameTexture()->getTextureHeight(), 30);
    EXPECT_EQ(other.width(), 100);
    a->getContext()->makeCurrent();
    const FilterImage again = fromRender(*a->renderImage());
    EXPECT_EQ(post->getFrameTexture()->getTextureWidth(), 64);
    // Back at the first size, the first context draws the same frame.
    EXPECT_LE(FilterImage::maxAbsDifference(first, again), 1.0f / 255.0f + 1e-6f);
    EXPECT_EQ(post->getFilteredFrames(), 3u);
    EXPECT_TRUE(post->getLastError().empty()) << post->getLastError();
}

TEST(PostProcessFilteringGLTest, DisabledOrWithoutFilterTheChildrenDrawDirectly)
{
    osg::ref_ptr<osg::Geode> plane = groundPlane();
    osg::ref_ptr<OffscreenRenderer> direct = renderer(80, 60, plane.get());
    const FilterImage reference = fromRender(*direct->renderImage());
    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    post->addChild(plane.get());
    osg::ref_ptr<OffscreenRenderer> r = renderer(80, 60, post.get());
    EXPECT_EQ(FilterImage::maxAbsDifference(reference, fromRender(*r->renderImage())), 0.0f);
    post->setFilter(gaussian(3.0f).get());
    post->setEnabled(false);
    EXPECT_EQ(FilterImage::maxAbsDifference(reference, fromRender(*r->renderImage())), 0.0f);
    EXPECT_EQ(post->getFilteredFrames(), 0u);
}

TEST(PostProcessFilteringGLTest, RefusesFiltersWithoutGpuPasses)
{
    struct CpuOnly : public GaussianFilter
    {
        std::vector<GpuFilterPass> gpuPasses() const override { return {}; }
        std::string filterName() const override { return "cpu-only"; }
    };
    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    osg::ref_ptr<CpuOnly> f = new CpuOnly;
    try
    {
        post->setFilter(f.get());
        FAIL() << "no error";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("filter 'cpu-only' has no GPU passes"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(post->getFilter(), nullptr);
}

// The filter stage's milliseconds (for loa-bench): measured between two glFinish calls only when
// asked. The numbers are printed (Gaussian sigma 2 at 320x240 and 800x600), not asserted.
TEST(PostProcessFilteringGLTest, TheFilterStageIsTimedOnlyWhenAsked)
{
    osg::ref_ptr<osg::Geode> plane = groundPlane();
    for (const auto& size : {std::make_pair(320, 240), std::make_pair(800, 600)})
    {
        osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
        post->addChild(plane.get());
        post->setFilter(gaussian(2.0f).get());
        osg::ref_ptr<OffscreenRenderer> r = renderer(size.first, size.second, post.get());
        r->renderImage(); // warm-up: shader compilation, texture allocation
        EXPECT_LT(post->getLastFilterMilliseconds(), 0.0) << "timed without being asked";
        post->setMeasureFilterTime(true);
        std::vector<double> ms;
        for (int i = 0; i < 5; ++i)
        {
            r->renderImage();
            ms.push_back(post->getLastFilterMilliseconds());
            EXPECT_GT(ms.back(), 0.0);
        }
        std::sort(ms.begin(), ms.end());
        std::cout << "gaussian sigma 2 at " << size.first << "x" << size.second << ": filter stage median "
                  << ms[2] << " ms (min " << ms[0] << ", max " << ms[4] << ") over 5 frames\n";
        EXPECT_EQ(post->getFilteredFrames(), 6u);
    }
}

TEST(PostProcessFilteringGLTest, SettingsSurviveOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("PostProcessFilteringGLTest");
    osg::ref_ptr<PostProcessFiltering> post = new PostProcessFiltering;
    post->setName("post");
    post->setFilter(gaussian(3.5f).get());
    post->setEnabled(false);
    post->setMeasureFilterTime(true);
    post->addChild(new osg::Group);
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string first = dir + "/post-first." + ext, second = dir + "/post-second." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(*post, first)) << first;
        osg::ref_ptr<PostProcessFiltering> back =
            dynamic_cast<PostProcessFiltering*>(osgDB::readRefNodeFile(first).get());
        ASSERT_TRUE(back.valid()) << first;
        ASSERT_TRUE(osgDB::writeNodeFile(*back, second)) << second;
        EXPECT_EQ(fileBytes(first), fileBytes(second)) << ext;
        const GaussianFilter* f = dynamic_cast<const GaussianFilter*>(back->getFilter());
        ASSERT_TRUE(f) << ext;
        EXPECT_FLOAT_EQ(f->getSigma(), 3.5f);
        EXPECT_FALSE(back->getEnabled());
        EXPECT_TRUE(back->getMeasureFilterTime());
        EXPECT_EQ(back->getNumChildren(), 1u);
    }
    // Defaults: enabled, untimed, no filter.
    osg::ref_ptr<PostProcessFiltering> plain = new PostProcessFiltering;
    ASSERT_TRUE(osgDB::writeNodeFile(*plain, dir + "/plain.osgt"));
    osg::ref_ptr<PostProcessFiltering> back =
        dynamic_cast<PostProcessFiltering*>(osgDB::readRefNodeFile(dir + "/plain.osgt").get());
    ASSERT_TRUE(back.valid());
    EXPECT_TRUE(back->getEnabled());
    EXPECT_FALSE(back->getMeasureFilterTime());
    EXPECT_EQ(back->getFilter(), nullptr);
    // A copy shares (shallow) or clones (deep) the filter.
    osg::ref_ptr<PostProcessFiltering> shallow = new PostProcessFiltering(*post);
    EXPECT_EQ(shallow->getFilter(), post->getFilter());
    osg::ref_ptr<PostProcessFiltering> deep = new PostProcessFiltering(*post, osg::CopyOp::DEEP_COPY_ALL);
    ASSERT_TRUE(deep->getFilter());
    EXPECT_NE(deep->getFilter(), post->getFilter());
    EXPECT_NE(deep->getFrameTexture(), post->getFrameTexture());
}
