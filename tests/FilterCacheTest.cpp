// FilterCache: the disk cache of filtered mip pyramids, and MipmapFilter through it.
#include <osgLoA/filtering/FilterCache>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/MipmapFilter>

#include "support/TestSupport.h"

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

using osgLoA::FilterCache;
using osgLoA::FilterCacheKey;
using osgLoA::FilterImage;
using osgLoA::ImageBorder;
using osgLoA::MipmapFilter;
using osgLoA::WrapMode;

namespace
{

osg::ref_ptr<osg::Image> testImage(int w, int h, unsigned seed = 1, GLenum format = GL_RGBA)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    const int channels = format == GL_RGB ? 3 : 4;
    img->allocateImage(w, h, 1, format, GL_UNSIGNED_BYTE, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
            {
                unsigned n = unsigned(x * 131 + y * 977 + c * 31) * 2654435761u + seed * 40503u;
                img->data(x, y)[c] = static_cast<unsigned char>((n >> 13) & 0xff);
            }
    return img;
}

osg::ref_ptr<osgLoA::GaussianFilter> gaussian(float sigma)
{
    osg::ref_ptr<osgLoA::GaussianFilter> g = new osgLoA::GaussianFilter;
    g->setSigma(sigma);
    return g;
}

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeFile(const std::string& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
}

bool sameImage(const osg::Image& a, const osg::Image& b)
{
    return a.s() == b.s() && a.t() == b.t() && a.getNumMipmapLevels() == b.getNumMipmapLevels() &&
           a.getTotalSizeInBytesIncludingMipmaps() == b.getTotalSizeInBytesIncludingMipmaps() &&
           std::memcmp(a.data(), b.data(), a.getTotalSizeInBytesIncludingMipmaps()) == 0;
}

/** Sets an environment variable for one scope. */
struct ScopedEnv
{
    std::string name, old;
    bool had;
    ScopedEnv(const std::string& n, const char* value) : name(n)
    {
        const char* o = std::getenv(n.c_str());
        had = o != nullptr;
        if (had) old = o;
        if (value)
            ::setenv(n.c_str(), value, 1);
        else
            ::unsetenv(n.c_str());
    }
    ~ScopedEnv()
    {
        if (had)
            ::setenv(name.c_str(), old.c_str(), 1);
        else
            ::unsetenv(name.c_str());
    }
};

} // namespace

TEST(FilterCache, HashesAreFnv1aAndAWordHash)
{
    // FNV-1a 64 reference values (the high half).
    EXPECT_EQ(FilterCache::hash128("", 0).high, 0xcbf29ce484222325ull);
    EXPECT_EQ(FilterCache::hash128("a", 1).high, 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(FilterCache::hash128("foobar", 6).high, 0x85944171f73967e8ull);
    // The low half depends on every byte and on the length.
    EXPECT_NE(FilterCache::hash128("abcdefgh", 8).low, FilterCache::hash128("abcdefgi", 8).low);
    EXPECT_NE(FilterCache::hash128("abcdefgh\0", 9).low, FilterCache::hash128("abcdefgh", 8).low);
    FilterCacheKey k;
    k.high = 0x0123456789abcdefull;
    k.low = 0xfedcba9876543210ull;
    EXPECT_EQ(k.hex(), "0123456789abcdeffedcba9876543210");
}

// The key changes with any pixel, the size, the format, either wrap mode and any filter
// parameter; it does not change with row padding.
TEST(FilterCache, KeyDependsOnEverythingThatChangesTheResult)
{
    osg::ref_ptr<osg::Image> img = testImage(8, 4);
    const ImageBorder clamp(WrapMode::Clamp, WrapMode::Clamp);
    const std::string params = "gaussian:sigma=2";
    const FilterCacheKey base = FilterCache::makeKey(FilterCache::imageHash(*img), clamp, params);
    std::set<std::string> keys{base.hex()};

    osg::ref_ptr<osg::Image> pixel = new osg::Image(*img, osg::CopyOp::DEEP_COPY_ALL);
    pixel->data(5, 3)[1] ^= 1;
    keys.insert(FilterCache::makeKey(FilterCache::imageHash(*pixel), clamp, params).hex());

    osg::ref_ptr<osg::Image> reshaped = new osg::Image; // the same bytes as 4x8
    reshaped->allocateImage(4, 8, 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    std::memcpy(reshaped->data(), img->data(), img->getTotalSizeInBytes());
    keys.insert(FilterCache::makeKey(FilterCache::imageHash(*reshaped), clamp, params).hex());
    osg::ref_ptr<osg::Image> bgra = new osg::Image(*img, osg::CopyOp::DEEP_COPY_ALL);
    bgra->setPixelFormat(GL_BGRA);
    keys.insert(FilterCache::makeKey(FilterCache::imageHash(*bgra), clamp, params).hex());

    const FilterCacheKey h = FilterCache::imageHash(*img);
    keys.insert(FilterCache::makeKey(h, ImageBorder(WrapMode::Repeat, WrapMode::Clamp), params).hex());
    keys.insert(FilterCache::makeKey(h, ImageBorder(WrapMode::Clamp, WrapMode::Repeat), params).hex());
    keys.insert(FilterCache::makeKey(h, ImageBorder(WrapMode::Mirror, WrapMode::Clamp), params).hex());
    keys.insert(FilterCache::makeKey(h, clamp, "gaussian:sigma=2.0001").hex());
    keys.insert(FilterCache::makeKey(h, clamp, "bilateral:sigma=2").hex());
    EXPECT_EQ(keys.size(), 9u); // all different
    for (const std::string& k : keys)
        EXPECT_EQ(k.size(), 32u);

    // Row padding is not part of the image: RGB 3x2 rows packed to 1 and to 4 bytes.
    osg::ref_ptr<osg::Image> packed1 = testImage(3, 2, 5, GL_RGB);
    osg::ref_ptr<osg::Image> packed4 = new osg::Image;
    packed4->allocateImage(3, 2, 1, GL_RGB, GL_UNSIGNED_BYTE, 4);
    for (int y = 0; y < 2; ++y)
        std::memcpy(packed4->data(0, y), packed1->data(0, y), 9);
    EXPECT_EQ(FilterCache::imageHash(*packed1), FilterCache::imageHash(*packed4));
    // ... nor the image's name.
    packed4->setFileName("other.png");
    EXPECT_EQ(FilterCache::imageHash(*packed1), FilterCache::imageHash(*packed4));

    osg::ref_ptr<osg::Image> empty = new osg::Image;
    EXPECT_THROW(FilterCache::imageHash(*empty), std::invalid_argument);
}

TEST(FilterCache, EncodeDecodeAndEveryCorruptionIsAMiss)
{
    osg::ref_ptr<osg::Image> img = testImage(5, 3);
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(1.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get());
    osg::ref_ptr<osg::Image> pyramid = mf->filterImage(*img, ImageBorder());
    const FilterCacheKey key = FilterCache::makeKey(*img, ImageBorder(), *g);
    const std::string bytes = FilterCache::encode(key, *pyramid);
    // 32 header + 3 levels x 8 + 8 payload size + (5x3 + 2x1 + 1x1) x 4 + 8 checksum
    EXPECT_EQ(bytes.size(), 32u + 24 + 8 + 18 * 4 + 8);
    EXPECT_EQ(bytes.substr(0, 8), "osgLoAFC");
    std::string why;
    osg::ref_ptr<osg::Image> back = FilterCache::decode(bytes, key, why);
    ASSERT_TRUE(back.valid()) << why;
    EXPECT_TRUE(sameImage(*back, *pyramid));

    FilterCacheKey other = key;
    other.low ^= 1;
    EXPECT_FALSE(FilterCache::decode(bytes, other, why).valid());
    EXPECT_NE(why.find("holds key"), std::string::npos) << why;
    // Every truncation and every single-byte change is detected.
    for (std::size_t n = 0; n < bytes.size(); ++n)
        EXPECT_FALSE(FilterCache::decode(bytes.substr(0, n), key, why).valid()) << "truncated to " << n;
    EXPECT_FALSE(FilterCache::decode(bytes + "x", key, why).valid());
    for (std::size_t i = 0; i < bytes.size(); ++i)
    {
        std::string bad = bytes;
        bad[i] = char(bad[i] ^ 0x5a);
        EXPECT_FALSE(FilterCache::decode(bad, key, why).valid()) << "byte " << i;
    }
    // Another format version is refused by name.
    std::string v2 = bytes;
    v2[8] = 2;
    EXPECT_FALSE(FilterCache::decode(v2, key, why).valid());
    EXPECT_NE(why.find("format version 2"), std::string::npos) << why;
    // Only RGBA8 pyramids down to 1x1 are stored.
    EXPECT_THROW(FilterCache::encode(key, *img), std::invalid_argument);
}

// The second load of the same texture and filter is a file read with the identical result; a
// change of any parameter, pixel or wrap mode is a miss.
TEST(FilterCache, MipmapFilterHitsOnSecondLoadAndMissesOnAnyChange)
{
    const std::string dir = loatest::freshDirectory("FilterCache.hits");
    osg::ref_ptr<FilterCache> cache = new FilterCache(dir);
    osg::ref_ptr<osgLoA::GaussianFilter> g = gaussian(2.0f);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(g.get(), cache.get());
    osg::ref_ptr<osg::Image> img = testImage(64, 32);
    const ImageBorder repeat(WrapMode::Repeat, WrapMode::Repeat);

    MipmapFilter::Result r1, r2;
    osg::ref_ptr<osg::Image> first = mf->filterImage(*img, repeat, &r1);
    EXPECT_EQ(r1.source, MipmapFilter::CPU);
    EXPECT_TRUE(r1.stored);
    EXPECT_TRUE(osgDB::fileExists(cache->pathOf(r1.key)));
    EXPECT_EQ(cache->getMisses(), 1u);
    EXPECT_EQ(cache->getHits(), 0u);
    EXPECT_EQ(cache->getStores(), 1u);

    osg::ref_ptr<osg::Image> second = mf->filterImage(*img, repeat, &r2);
    EXPECT_EQ(r2.source, MipmapFilter::CACHE);
    EXPECT_FALSE(r2.stored);
    EXPECT_EQ(r2.key, r1.key);
    EXPECT_EQ(cache->getHits(), 1u);
    EXPECT_TRUE(sameImage(*first, *second));
    EXPECT_TRUE(second->isMipmap());
    std::printf("[ measured ] 64x32 gaussian sigma 2: filtered %.2f ms, cache hit %.2f ms\n", r1.milliseconds,
                r2.milliseconds);

    // A new cache object on the same directory (another process) hits too.
    osg::ref_ptr<FilterCache> again = new FilterCache(dir);
    osg::ref_ptr<MipmapFilter> mf2 = new MipmapFilter(gaussian(2.0f).get(), again.get());
    MipmapFilter::Result r3;
    EXPECT_TRUE(sameImage(*mf2->filterImage(*img, repeat, &r3), *first));
    EXPECT_EQ(r3.source, MipmapFilter::CACHE);

    auto sourceOf = [&](MipmapFilter& m, const osg::Image& i, const ImageBorder& b)
    {
        MipmapFilter::Result r;
        m.filterImage(i, b, &r);
        return r.source;
    };
    // Parameter.
    osg::ref_ptr<MipmapFilter> other = new MipmapFilter(gaussian(2.5f).get(), cache.get());
    EXPECT_EQ(sourceOf(*other, *img, repeat), MipmapFilter::CPU);
    // Pixel.
    osg::ref_ptr<osg::Image> changed = new osg::Image(*img, osg::CopyOp::DEEP_COPY_ALL);
    changed->data(63, 31)[0] ^= 0x10;
    EXPECT_EQ(sourceOf(*mf, *changed, repeat), MipmapFilter::CPU);
    // Wrap mode (each axis).
    EXPECT_EQ(sourceOf(*mf, *img, ImageBorder(WrapMode::Clamp, WrapMode::Repeat)), MipmapFilter::CPU);
    EXPECT_EQ(sourceOf(*mf, *img, ImageBorder(WrapMode::Repeat, WrapMode::Mirror)), MipmapFilter::CPU);
    // ... and each of those is a hit the second time.
    EXPECT_EQ(sourceOf(*other, *img, repeat), MipmapFilter::CACHE);
    EXPECT_EQ(sourceOf(*mf, *changed, repeat), MipmapFilter::CACHE);
    EXPECT_EQ(sourceOf(*mf, *img, ImageBorder(WrapMode::Repeat, WrapMode::Mirror)), MipmapFilter::CACHE);
    EXPECT_EQ(cache->getCorrupt(), 0u);
}

// A corrupt or truncated file is a miss with a warning, and the filter rewrites it.
TEST(FilterCache, CorruptAndTruncatedFilesAreRewritten)
{
    const std::string dir = loatest::freshDirectory("FilterCache.corrupt");
    osg::ref_ptr<FilterCache> cache = new FilterCache(dir);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(gaussian(1.0f).get(), cache.get());
    osg::ref_ptr<osg::Image> img = testImage(16, 16, 3);
    MipmapFilter::Result r;
    osg::ref_ptr<osg::Image> good = mf->filterImage(*img, ImageBorder(), &r);
    const std::string path = cache->pathOf(r.key);
    const std::string bytes = readFile(path);
    ASSERT_FALSE(bytes.empty());

    const std::string damaged[] = {
        bytes.substr(0, bytes.size() / 2), std::string(), std::string(bytes.size(), '\0'),
        bytes.substr(0, 100) + std::string(1, char(bytes[100] ^ 1)) + bytes.substr(101)};
    unsigned long corrupt = 0;
    for (const std::string& bad : damaged)
    {
        writeFile(path, bad);
        EXPECT_FALSE(cache->load(r.key).valid());
        EXPECT_EQ(cache->getCorrupt(), ++corrupt);
        MipmapFilter::Result again;
        osg::ref_ptr<osg::Image> redone = mf->filterImage(*img, ImageBorder(), &again);
        EXPECT_EQ(again.source, MipmapFilter::CPU);
        EXPECT_TRUE(again.stored);
        EXPECT_EQ(cache->getCorrupt(), ++corrupt); // filterImage's own load saw it too
        EXPECT_TRUE(sameImage(*redone, *good));
        EXPECT_EQ(readFile(path), bytes) << "the file is rewritten";
        EXPECT_TRUE(cache->load(r.key).valid());
    }
}

// Writers of the same key in parallel (threads of one process, the hard case: same pid) never
// leave a torn file: every load while they run is a hit on a complete file or a clean miss.
TEST(FilterCache, ConcurrentWritersOfOneKeyDoNotTearTheFile)
{
    const std::string dir = loatest::freshDirectory("FilterCache.concurrent");
    osg::ref_ptr<FilterCache> cache = new FilterCache(dir);
    osg::ref_ptr<osg::Image> img = testImage(128, 128, 4);
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(gaussian(1.0f).get());
    mf->setNumThreads(1);
    osg::ref_ptr<osg::Image> pyramid = mf->filterImage(*img, ImageBorder());
    const FilterCacheKey key = FilterCache::makeKey(*img, ImageBorder(), *mf->getFilter());

    std::atomic<bool> stop{false};
    std::atomic<int> failures{0}, hits{0};
    std::vector<std::thread> writers;
    for (int i = 0; i < 4; ++i)
        writers.emplace_back(
            [&]
            {
                for (int n = 0; n < 25; ++n)
                {
                    try
                    {
                        cache->store(key, *pyramid);
                    }
                    catch (const std::exception&)
                    {
                        ++failures;
                    }
                }
            });
    std::thread reader(
        [&]
        {
            while (!stop)
            {
                osg::ref_ptr<osg::Image> got = cache->load(key);
                if (got.valid())
                {
                    ++hits;
                    if (!sameImage(*got, *pyramid)) ++failures;
                }
            }
        });
    for (std::thread& t : writers)
        t.join();
    stop = true;
    reader.join();
    EXPECT_EQ(failures.load(), 0);
    EXPECT_EQ(cache->getCorrupt(), 0u);
    EXPECT_EQ(cache->getStores(), 100u);
    EXPECT_GT(hits.load(), 0);
    // No temporary files are left behind.
    const std::string sub = dir + "/" + key.hex().substr(0, 2);
    int files = 0;
    for (const std::string& f : osgDB::getDirectoryContents(sub))
        if (f != "." && f != "..") ++files;
    EXPECT_EQ(files, 1);
}

// A directory that cannot be created: store and checkWritable throw naming it; MipmapFilter
// still returns the result and says why nothing was stored (the documented fallback).
TEST(FilterCache, UnwritableDirectory)
{
    const std::string dir = loatest::freshDirectory("FilterCache.unwritable");
    writeFile(dir + "/file", "not a directory");
    const std::string bad = dir + "/file/cache"; // under a regular file: fails even for root
    osg::ref_ptr<FilterCache> cache = new FilterCache(bad);
    try
    {
        cache->checkWritable();
        FAIL() << "no exception";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
    osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(gaussian(1.0f).get(), cache.get());
    osg::ref_ptr<osg::Image> img = testImage(8, 8);
    osg::ref_ptr<osg::Image> pyramid = mf->filterImage(*img, ImageBorder());
    EXPECT_THROW(cache->store(FilterCache::makeKey(*img, ImageBorder(), *mf->getFilter()), *pyramid),
                 std::runtime_error);
    MipmapFilter::Result r;
    osg::ref_ptr<osg::Image> out = mf->filterImage(*img, ImageBorder(), &r);
    ASSERT_TRUE(out.valid());
    EXPECT_TRUE(out->isMipmap());
    EXPECT_FALSE(r.stored);
    EXPECT_NE(r.storeError.find("cannot write"), std::string::npos) << r.storeError;
    EXPECT_EQ(r.source, MipmapFilter::CPU);
}

TEST(FilterCache, DefaultDirectoryFromEnvironment)
{
    {
        ScopedEnv a("OSGLOA_FILTER_CACHE", "/tmp/x-cache");
        ScopedEnv b("XDG_CACHE_HOME", "/tmp/xdg");
        EXPECT_EQ(FilterCache::defaultDirectory(), "/tmp/x-cache");
        EXPECT_EQ(osg::ref_ptr<FilterCache>(new FilterCache)->getDirectory(), "/tmp/x-cache");
    }
    {
        ScopedEnv a("OSGLOA_FILTER_CACHE", nullptr);
        ScopedEnv b("XDG_CACHE_HOME", "/tmp/xdg");
        EXPECT_EQ(FilterCache::defaultDirectory(), "/tmp/xdg/osgLoA/filters");
    }
    {
        ScopedEnv a("OSGLOA_FILTER_CACHE", "");
        ScopedEnv b("XDG_CACHE_HOME", "relative/ignored"); // the XDG spec: absolute paths only
        ScopedEnv c("HOME", "/home/someone");
        EXPECT_EQ(FilterCache::defaultDirectory(), "/home/someone/.cache/osgLoA/filters");
    }
    {
        ScopedEnv a("OSGLOA_FILTER_CACHE", nullptr);
        ScopedEnv b("XDG_CACHE_HOME", nullptr);
        ScopedEnv c("HOME", nullptr);
        EXPECT_EQ(FilterCache::defaultDirectory(), "");
        EXPECT_THROW(osg::ref_ptr<FilterCache>(new FilterCache), std::runtime_error);
    }
    EXPECT_EQ(osg::ref_ptr<FilterCache>(new FilterCache("/tmp/y/"))->getDirectory(), "/tmp/y");
}
