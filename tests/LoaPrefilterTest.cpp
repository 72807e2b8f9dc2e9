// loa-prefilter: the batch tool that pre-filters a model's textures level by level into the
// filter cache (runs the built executable).
#include <osgLoA/filtering/FilterCache>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/util/StateSetVisitor>

#include "support/TestSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

using osgLoA::FilterCache;
using osgLoA::FilterImage;
using osgLoA::ImageBorder;
using osgLoA::MipmapFilter;

namespace
{

const std::string kExe = LOA_PREFILTER_EXE;

osg::ref_ptr<osg::Image> pattern(int w, int h, unsigned seed, GLenum format = GL_RGBA)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, format, GL_UNSIGNED_BYTE);
    const int channels = format == GL_RGB ? 3 : 4;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                img->data(x, y)[c] = static_cast<unsigned char>(
                    c == 3 ? 255 : ((x * (7 + c) + y * 13 + int(seed) * 29) % 23) * 11);
    return img;
}

osg::ref_ptr<osg::Geode> quad(osg::Texture2D* texture, float offset)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(osg::createTexturedQuadGeometry(osg::Vec3(offset, 0, 0), osg::X_AXIS, osg::Y_AXIS));
    geode->getOrCreateStateSet()->setTextureAttributeAndModes(0, texture);
    return geode;
}

osg::ref_ptr<osg::Texture2D> texture(osg::Image* image, osg::Texture::WrapMode wrap, const std::string& name)
{
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(image);
    t->setWrap(osg::Texture::WRAP_S, wrap);
    t->setWrap(osg::Texture::WRAP_T, wrap);
    t->setName(name);
    return t;
}

/** A model with 9 textures: a.png (repeat, twice through two image objects with the same
 *  pixels, and once clamped), b.png (clamp), c.png (mirror, 17x9), a corrupt PNG and a missing
 *  one (each read back as a 0x0 image carrying its file name), a 0x0 inline image (which the
 *  .osgb reader drops, leaving a texture without image) and a packed 5-6-5 image (a format the
 *  filters do not read). 4 distinct good images, 4 bad ones. Writes model.osgb into dir and
 *  returns its path. */
std::string makeModel(const std::string& dir)
{
    osg::ref_ptr<osg::Image> a = pattern(32, 32, 1), b = pattern(24, 16, 2, GL_RGB), c = pattern(17, 9, 3);
    EXPECT_TRUE(osgDB::writeImageFile(*a, dir + "/a.png"));
    EXPECT_TRUE(osgDB::writeImageFile(*b, dir + "/b.png"));
    EXPECT_TRUE(osgDB::writeImageFile(*c, dir + "/c.png"));
    std::ofstream(dir + "/corrupt.png", std::ios::binary) << "\x89PNG\r\n\x1a\n this is not a PNG stream";

    auto external = [](const std::string& file)
    {
        // corrupt.png, missing.png: any content, written as a file reference
        osg::ref_ptr<osg::Image> img = file.find(".png") == file.size() - 4 &&
                                               file.find("/corrupt.png") == std::string::npos &&
                                               file.find("/missing.png") == std::string::npos
                                           ? osgDB::readRefImageFile(file)
                                           : pattern(4, 4, 9);
        img->setFileName(osgDB::getSimpleFileName(file));
        img->setWriteHint(osg::Image::EXTERNAL_FILE);
        return img;
    };
    osg::ref_ptr<osg::Image> empty = new osg::Image;
    empty->setName("empty-inline");
    empty->setWriteHint(osg::Image::STORE_INLINE);
    osg::ref_ptr<osg::Image> packed = new osg::Image;
    packed->allocateImage(8, 8, 1, GL_RGB, GL_UNSIGNED_SHORT_5_6_5);
    std::memset(packed->data(), 0x5a, packed->getTotalSizeInBytes());
    packed->setName("packed565");
    packed->setWriteHint(osg::Image::STORE_INLINE);

    osg::ref_ptr<osg::Group> root = new osg::Group;
    float x = 0;
    root->addChild(quad(texture(external(dir + "/a.png").get(), osg::Texture::REPEAT, "a1").get(), x++));
    root->addChild(quad(texture(external(dir + "/a.png").get(), osg::Texture::REPEAT, "a2").get(), x++));
    root->addChild(
        quad(texture(external(dir + "/a.png").get(), osg::Texture::CLAMP_TO_EDGE, "a3").get(), x++));
    root->addChild(
        quad(texture(external(dir + "/b.png").get(), osg::Texture::CLAMP_TO_EDGE, "b").get(), x++));
    root->addChild(quad(texture(external(dir + "/c.png").get(), osg::Texture::MIRROR, "c").get(), x++));
    root->addChild(
        quad(texture(external(dir + "/corrupt.png").get(), osg::Texture::REPEAT, "bad").get(), x++));
    root->addChild(
        quad(texture(external(dir + "/missing.png").get(), osg::Texture::REPEAT, "missing").get(), x++));
    root->addChild(quad(texture(empty.get(), osg::Texture::REPEAT, "empty").get(), x++));
    root->addChild(quad(texture(packed.get(), osg::Texture::REPEAT, "packed").get(), x++));
    const std::string path = dir + "/model.osgb";
    EXPECT_TRUE(osgDB::writeNodeFile(*root, path));
    return path;
}

int runTool(const std::string& args, std::string& out)
{
    return loatest::run("'" + kExe + "' " + args, out);
}

/** name -> bytes of every cache file under dir. */
std::map<std::string, std::string> cacheFiles(const std::string& dir)
{
    std::map<std::string, std::string> files;
    for (const std::string& sub : osgDB::getDirectoryContents(dir))
    {
        if (sub.size() != 2) continue;
        for (const std::string& f : osgDB::getDirectoryContents(dir + "/" + sub))
            if (f.size() > 6 && f.substr(f.size() - 6) == ".loafc")
            {
                std::ifstream in(dir + "/" + sub + "/" + f, std::ios::binary);
                std::ostringstream s;
                s << in.rdbuf();
                files[f] = s.str();
            }
    }
    return files;
}

bool contains(const std::string& text, const std::string& what)
{
    return text.find(what) != std::string::npos;
}

class LoaPrefilter : public ::testing::Test
{
protected:
    void SetUp() override
    {
        if (!osgDB::fileExists(kExe)) GTEST_SKIP() << "loa-prefilter not built: " << kExe;
        dir = loatest::freshDirectory(std::string("LoaPrefilter.") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        model = makeModel(dir);
    }
    std::string dir, model;
};

} // namespace

TEST_F(LoaPrefilter, FiltersGoodImagesAndSkipsBadOnesWithTheirNames)
{
    std::string out;
    const std::string cache = dir + "/cache";
    int rc = runTool("'" + model + "' --filter gaussian:sigma=1 --cache '" + cache + "' --jobs 2", out);
    EXPECT_EQ(rc, 4) << out; // some skipped
    EXPECT_TRUE(contains(out, "9 2D textures, 8 distinct images")) << out;
    EXPECT_TRUE(contains(out, "skipped corrupt.png: is empty (0x0)")) << out;
    EXPECT_TRUE(contains(out, "skipped missing.png: is empty (0x0)")) << out;
    EXPECT_TRUE(contains(out, "skipped texture 'empty': has no image")) << out;
    EXPECT_TRUE(contains(out, "skipped packed565: unsupported image data type 0x8363")) << out;
    EXPECT_TRUE(contains(out, "8 images: 4 filtered, 0 cached, 4 skipped")) << out;
    EXPECT_FALSE(contains(out, "\033[K")) << "no terminal control codes when stderr is not a terminal";
    const auto files = cacheFiles(cache);
    EXPECT_EQ(files.size(), 4u);

    // The second run reads everything from the cache.
    rc = runTool("'" + model + "' --filter gaussian:sigma=1 --cache '" + cache + "'", out);
    EXPECT_EQ(rc, 4) << out;
    EXPECT_TRUE(contains(out, "8 images: 0 filtered, 4 cached, 4 skipped")) << out;
    EXPECT_EQ(cacheFiles(cache), files);

    // Another filter parameter is another set of files.
    rc = runTool("'" + model + "' --filter gaussian:sigma=1.5 --cache '" + cache + "'", out);
    EXPECT_TRUE(contains(out, "4 filtered, 0 cached, 4 skipped")) << out;
    EXPECT_EQ(cacheFiles(cache).size(), 8u);

    // --max-size: a.png (32x32) and b.png (24x16) are too large for 20.
    rc = runTool("'" + model + "' --filter gaussian:sigma=1 --max-size 20 --cache '" + cache + "'", out);
    EXPECT_EQ(rc, 4) << out;
    EXPECT_TRUE(contains(out, "skipped a.png: is 32x32, above --max-size 20")) << out;
    EXPECT_TRUE(contains(out, "skipped b.png: is 24x16, above --max-size 20")) << out;
}

// The cache files are what MipmapFilter makes of the images (same keys, same bytes).
TEST_F(LoaPrefilter, CacheHoldsMipmapFilterResults)
{
    std::string out;
    const std::string cache = dir + "/cache";
    runTool("'" + model + "' --filter gaussian:sigma=1 --cache '" + cache + "'", out);
    osg::ref_ptr<FilterCache> fc = new FilterCache(cache);
    osg::ref_ptr<osgLoA::GaussianFilter> g = new osgLoA::GaussianFilter;
    g->setSigma(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    osg::ref_ptr<osg::Image> c = osgDB::readRefImageFile(dir + "/c.png");
    ASSERT_TRUE(c.valid());
    const ImageBorder mirror(osgLoA::WrapMode::Mirror, osgLoA::WrapMode::Mirror);
    osg::ref_ptr<osg::Image> cached = fc->load(FilterCache::makeKey(*c, mirror, *g));
    ASSERT_TRUE(cached.valid()) << out;
    osg::ref_ptr<osg::Image> expected = mf->filterImage(*c, mirror);
    ASSERT_EQ(cached->getTotalSizeInBytesIncludingMipmaps(), expected->getTotalSizeInBytesIncludingMipmaps());
    EXPECT_EQ(std::memcmp(cached->data(), expected->data(), expected->getTotalSizeInBytesIncludingMipmaps()),
              0);
    EXPECT_EQ(cached->getNumMipmapLevels(), 5u); // 17x9 8x4 4x2 2x1 1x1
}

// Shards 0/2 and 1/2 together do exactly what one unsharded run does; --jobs does not change
// the result.
TEST_F(LoaPrefilter, ShardsAndJobs)
{
    std::string out;
    runTool("'" + model + "' --filter gaussian:sigma=1 --jobs 1 --cache '" + dir + "/all'", out);
    const auto all = cacheFiles(dir + "/all");
    ASSERT_EQ(all.size(), 4u) << out;

    std::string out0, out1;
    EXPECT_EQ(runTool("'" + model + "' --filter gaussian:sigma=1 --shard 0/2 --cache '" + dir + "/s0'", out0),
              4)
        << out0;
    runTool("'" + model + "' --filter gaussian:sigma=1 --shard 1/2 --cache '" + dir + "/s1'", out1);
    const auto s0 = cacheFiles(dir + "/s0"), s1 = cacheFiles(dir + "/s1");
    EXPECT_FALSE(s0.empty());
    EXPECT_FALSE(s1.empty());
    std::map<std::string, std::string> both = s0;
    for (const auto& kv : s1)
        EXPECT_TRUE(both.insert(kv).second) << kv.first << " is in both shards";
    EXPECT_EQ(both, all);
    EXPECT_TRUE(contains(out0, "shard 0/2: 4")) << out0; // 8 images dealt 4 + 4
    EXPECT_TRUE(contains(out1, "shard 1/2: 4")) << out1;
    // Every skip is reported by exactly one shard.
    const auto skips = [](const std::string& o)
    {
        std::size_t n = 0;
        for (std::size_t at = o.find("] skipped "); at != std::string::npos;
             at = o.find("] skipped ", at + 1))
            ++n;
        return n;
    };
    EXPECT_EQ(skips(out0) + skips(out1), 4u) << out0 << out1;

    // Shards into the same directory, one after the other: the second finds none of its
    // images cached (disjoint), and the union is the unsharded result.
    runTool("'" + model + "' --filter gaussian:sigma=1 --shard 0/2 --cache '" + dir + "/shared'", out);
    runTool("'" + model + "' --filter gaussian:sigma=1 --shard 1/2 --cache '" + dir + "/shared'", out);
    EXPECT_TRUE(contains(out, " 0 cached")) << out;
    EXPECT_EQ(cacheFiles(dir + "/shared"), all);

    runTool("'" + model + "' --filter gaussian:sigma=1 --jobs 3 --cache '" + dir + "/jobs3'", out);
    EXPECT_TRUE(contains(out, "on 3 thread(s)")) << out;
    EXPECT_EQ(cacheFiles(dir + "/jobs3"), all);
}

// --export writes the model with the filtered textures; an .osgb keeps every level.
TEST_F(LoaPrefilter, ExportRoundTripHasTheFilteredLevels)
{
    std::string out;
    const std::string exported = dir + "/filtered.osgb";
    const int rc = runTool("'" + model + "' --filter gaussian:sigma=1 --cache '" + dir +
                               "/cache' --export '" + exported + "'",
                           out);
    EXPECT_EQ(rc, 4) << out;
    EXPECT_TRUE(contains(out, "(5 textures with filtered levels)")) << out;
    osg::ref_ptr<osg::Node> back = osgDB::readNodeFile(exported);
    ASSERT_TRUE(back.valid());
    std::map<std::string, osg::Texture2D*> byName;
    osgLoA::StateSetVisitor v(
        [&](osg::StateSet& ss)
        {
            if (auto* t =
                    dynamic_cast<osg::Texture2D*>(ss.getTextureAttribute(0, osg::StateAttribute::TEXTURE)))
                byName[t->getName()] = t;
        });
    back->accept(v);
    ASSERT_EQ(byName.size(), 9u);

    osg::ref_ptr<osgLoA::GaussianFilter> g = new osgLoA::GaussianFilter;
    g->setSigma(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    const std::map<std::string, std::string> files = {
        {"a1", "a.png"}, {"a2", "a.png"}, {"a3", "a.png"}, {"b", "b.png"}, {"c", "c.png"}};
    for (const auto& kv : files)
    {
        SCOPED_TRACE(kv.first);
        osg::Texture2D* t = byName[kv.first];
        ASSERT_NE(t, nullptr);
        ASSERT_NE(t->getImage(), nullptr);
        ASSERT_TRUE(t->getImage()->isMipmap());
        EXPECT_EQ(t->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
        EXPECT_FALSE(t->getUseHardwareMipMapGeneration());
        osg::ref_ptr<osg::Image> original = osgDB::readRefImageFile(dir + "/" + kv.second);
        ASSERT_TRUE(original.valid());
        osg::ref_ptr<osg::Image> expected = mf->filterImage(*original, ImageBorder::of(*t));
        const std::vector<FilterImage> a = MipmapFilter::levelsOf(*t->getImage()),
                                       b = MipmapFilter::levelsOf(*expected);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t k = 0; k < a.size(); ++k)
            EXPECT_EQ(FilterImage::maxAbsDifference(a[k], b[k], true), 0.0f) << "level " << k;
    }
    // The skipped textures keep what they had.
    ASSERT_NE(byName["packed"]->getImage(), nullptr);
    EXPECT_FALSE(byName["packed"]->getImage()->isMipmap());
    EXPECT_EQ(byName["packed"]->getImage()->getDataType(), GLenum(GL_UNSIGNED_SHORT_5_6_5));
    // No temporary files are left beside the export.
    for (const std::string& f : osgDB::getDirectoryContents(dir))
        EXPECT_FALSE(contains(f, ".tmp")) << f;
}

// The demo city through the loacity pseudo-loader: every texture filtered, exit status 0.
TEST_F(LoaPrefilter, DemoCityPseudoLoader)
{
    std::string out;
    const int rc =
        runTool("demo.loacity -O 'seed=2 blocksX=2 blocksY=2' --filter gaussian:sigma=0.5 --cache '" + dir +
                    "/cache'",
                out);
    EXPECT_EQ(rc, 0) << out;
    EXPECT_TRUE(contains(out, " 0 skipped")) << out;
    EXPECT_FALSE(cacheFiles(dir + "/cache").empty());
}

TEST_F(LoaPrefilter, UsageAndFailureExitCodes)
{
    struct Case
    {
        std::string args;
        int rc;
        std::string message;
    };
    const std::string m = "'" + model + "'", c = " --cache '" + dir + "/cache'";
    std::ofstream(dir + "/bare.osgt") << "#Ascii Scene\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n"
                                         "osg::Group {\n  UniqueID 1\n}\n";
    const std::vector<Case> cases = {
        {"'" + dir + "/bare.osgt' --filter gaussian" + c, 1, "has no 2D texture to filter"},
        {"", 2, "no MODEL given"},
        {m + c, 2, "--filter is required"},
        {m + " --filter gaussian --out '" + dir + "/cache'", 2, "unknown option '--out'"}, // now --cache
        {m + " --filter nosuchfilter" + c, 2, "--filter: "},
        {m + " --filter gaussian:sigma=-1" + c, 2, "sigma"},
        {m + " --filter gaussian --shard 2/2" + c, 2, "I must be in 0..1"},
        {m + " --filter gaussian --shard 0/0" + c, 2, "N must be at least 1"},
        {m + " --filter gaussian --shard x" + c, 2, "is not I/N"},
        {m + " --filter gaussian --jobs 0" + c, 2, "--jobs must be at least 1"},
        {m + " --filter gaussian --jobs many" + c, 2, "--jobs 'many'"},
        {m + " --filter gaussian --frobnicate" + c, 2, "unknown option '--frobnicate'"},
        {m + " --filter gaussian --export out.obj" + c, 2, "must name an .osgb file"},
        {m + " --filter gaussian --shard 0/2 --export x.osgb" + c, 2, "without --shard"},
        {m + " '" + dir + "/nothere.osgb' --filter gaussian" + c, 1, "nothere.osgb"}, // several models
        {"'" + dir + "/nothere.osgb' --filter gaussian" + c, 1, "cannot read"},
        {m + " --filter gaussian --cache '" + dir + "/a.png/cache'", 1, "is not usable"},
    };
    for (const Case& k : cases)
    {
        std::string out;
        EXPECT_EQ(runTool(k.args, out), k.rc) << k.args << "\n" << out;
        EXPECT_TRUE(contains(out, k.message)) << k.args << "\n" << out;
    }
    std::string out;
    EXPECT_EQ(runTool("--help", out), 0);
    EXPECT_TRUE(contains(out, "exit status")) << out;
    EXPECT_EQ(runTool("--list-filters", out), 0);
    EXPECT_TRUE(contains(out, "gaussian")) << out;
}
