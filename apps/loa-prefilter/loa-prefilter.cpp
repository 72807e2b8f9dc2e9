// loa-prefilter: pre-filters every 2D texture of a model level by level (paper 000 Eq. 2; paper
// 004 §3.1: "the input textures are first converted to mip maps, and then processed for each
// level separately ... once per model") into the filter cache, and can write the model with
// the filtered textures.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"
#include "../common/ProgressBar.h"

#include <osgLoA/filtering/FilterCache>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/render/HeadlessContext>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/StateSetVisitor>

#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace
{
const char* kDescription =
    R"(Loads MODEL (any file osgDB reads: .osgb, .osgt, .obj, .cityjson, demo.loacity ...; several are
one scene), collects the image of every 2D texture, and filters each one level by level: the
image's mip pyramid (area-weighted 2x box downsampling to 1x1) is built and every level is
filtered separately, with the texture's wrap modes at its borders (paper 000 Eq. 2). The
filtered pyramids are stored in the filter cache, where MipmapFilter (and so loa-render and the
viewer) finds them; images already there are not filtered again. Textures with the same pixels
and wrap modes are one image. The work is spread over threads, and over machines with --shard.
)";
const char* kFooter =
    R"(Progress goes to stderr: a bar (images done/total, rate, ETA) when stderr is a terminal, one
line per image otherwise. Unreadable images (corrupt or missing files, 0x0 images, sizes above
--max-size, formats a filter cannot read: compressed other than S3TC/DXT, packed, 3D) are
reported by name and skipped. The last line counts the images filtered, found in the cache and
skipped.

exit status: 0 every image filtered or cached, 1 the model could not be read or has no 2D
texture, the cache could not be written or the export failed, 2 bad arguments, 3 no usable
EGL/OpenGL context (--gpu), 4 some images were skipped (the others are done).
)";

constexpr int kSkipped = 4;

struct Options
{
    std::vector<std::string> models;
    std::string model, filter, cache, exportPath, readerOptions;
    unsigned jobs = 0, shardIndex = 0, shardCount = 1, maxSize = 8192;
    bool gpu = false, haveShard = false;
};

void parseShard(const std::string& text, Options& o)
{
    const std::size_t slash = text.find('/');
    const auto digits = [](const std::string& s)
    { return !s.empty() && s.size() <= 6 && s.find_first_not_of("0123456789") == std::string::npos; };
    if (slash == std::string::npos || !digits(text.substr(0, slash)) || !digits(text.substr(slash + 1)))
        throw loa::UsageError("--shard '" + text + "' is not I/N (e.g. 0/4)");
    o.shardIndex = unsigned(std::stoul(text.substr(0, slash)));
    o.shardCount = unsigned(std::stoul(text.substr(slash + 1)));
    if (o.shardCount < 1) throw loa::UsageError("--shard '" + text + "': N must be at least 1");
    if (o.shardIndex >= o.shardCount)
        throw loa::UsageError("--shard '" + text + "': I must be in 0.." + std::to_string(o.shardCount - 1) +
                              " (shards are numbered from 0)");
    o.haveShard = true;
}

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl("loa-prefilter", "loa-prefilter MODEL... --filter NAME[:key=value,...] [options]",
                        kDescription);
    CLI::App& app = cl.app();
    loa::addModels(app, o.models, "the models whose textures to filter (one scene)");
    loa::addReaderOptions(app, o.readerOptions);
    app.add_option("--cache", o.cache,
                   "the filter cache directory (created if missing; default $OSGLOA_FILTER_CACHE, else "
                   "~/.cache/osgLoA/filters: where loa-render and the loa plugin look)")
        ->type_name("DIR")
        ->group(loa::kGroupOutput);
    app.add_option(
           "--export", o.exportPath,
           "write the model with the filtered textures (each image carrying its filtered mip levels) "
           "to FILE, atomically; FILE must be .osgb (which keeps the levels; the tool reads it back to "
           "check). Not with --shard")
        ->type_name("FILE.osgb")
        ->group(loa::kGroupOutput);
    app.add_option("--filter", o.filter,
                   "the filter: NAME or NAME:key=value,... or a chain A+B (--list-filters lists them; "
                   "parameters as docs/filtering.md)")
        ->type_name("SPEC");
    loa::addCount(app, "--jobs", o.jobs, 1, 1024, "worker threads (default: all cores)");
    app.add_option_function<std::string>(
           "--shard", [&o](const std::string& t) { parseShard(t, o); },
           "filter only shard I of N (I = 0..N-1): the images, sorted by their cache key, are dealt out in "
           "turn; shards 0/N .. N-1/N together do exactly what one run without --shard does")
        ->type_name("I/N");
    app.add_flag("--gpu", o.gpu, "filter on the GPU (headless EGL) when the filter has GPU passes");
    loa::addCount(app, "--max-size", o.maxSize, 1, unsigned(osgLoA::FilterImage::maxDimension()),
                  "skip images wider or taller than N texels (default 8192)");
    loa::addListFilters(app, "print the registered filters and exit");
    cl.footer(kFooter);
    cl.parse(argc, argv);
    o.model = loa::modelLabel(o.models);
    if (o.model.empty()) throw loa::UsageError("no MODEL given (see --help)");
    if (o.filter.empty()) throw loa::UsageError("--filter is required (see --list-filters)");
    if (!o.exportPath.empty())
    {
        if (osgDB::getLowerCaseFileExtension(o.exportPath) != "osgb")
            throw loa::UsageError("--export '" + o.exportPath +
                                  "' must name an .osgb file (the format that keeps the mip levels)");
        if (o.shardCount > 1)
            throw loa::UsageError("--export needs every image: run it without --shard (after the shards, "
                                  "the images come from the cache)");
    }
    return o;
}

/** One distinct image (pixels + wrap modes) and the textures that use it. */
struct Unit
{
    osgLoA::FilterCacheKey key;
    std::string label;
    osg::ref_ptr<osg::Image> image;
    osgLoA::ImageBorder border;
    std::vector<osg::ref_ptr<osg::Texture2D>> textures;
    std::string problem; // non-empty: skipped before any work
};

int run(const Options& o)
{
    osg::ref_ptr<osgLoA::ImageFilter> filter;
    try
    {
        filter = osgLoA::FilterRegistry::create(o.filter);
    }
    catch (const std::invalid_argument& e)
    {
        throw loa::UsageError(std::string("--filter: ") + e.what());
    }
    const std::string parameters = filter->getParameterString();

    osg::ref_ptr<osgLoA::FilterCache> cache = new osgLoA::FilterCache(o.cache);
    cache->checkWritable();

    // An image file that cannot be read leaves an empty image carrying its name (reported below).
    osg::ref_ptr<osg::Node> scene = loa::loadModels(o.models, o.readerOptions, true);

    // Every distinct osg::Texture2D, in traversal order.
    std::vector<osg::ref_ptr<osg::Texture2D>> textures;
    std::set<osg::Texture*> seen;
    std::size_t otherTextures = 0;
    osgLoA::StateSetVisitor visitor(
        [&](osg::StateSet& ss)
        {
            for (const osg::StateSet::AttributeList& unit : ss.getTextureAttributeList())
                for (const auto& entry : unit)
                {
                    osg::Texture* t = dynamic_cast<osg::Texture*>(entry.second.first.get());
                    if (!t || !seen.insert(t).second) continue;
                    if (osg::Texture2D* t2 = dynamic_cast<osg::Texture2D*>(t))
                        textures.push_back(t2);
                    else
                        ++otherTextures;
                }
        });
    scene->accept(visitor);

    // A model without a 2D texture left (OSG drops textures whose files it cannot read in some
    // formats) has nothing to filter: that is a failure, not success with nothing done.
    if (textures.empty())
        throw std::runtime_error(
            "'" + o.model + "' has no 2D texture to filter" +
            (otherTextures ? " (" + std::to_string(otherTextures) + " other textures)" : "") +
            ": no textured geometry, or its texture files could not be read");

    // Distinct images: valid ones by cache key (pixels, wrap modes, filter), sorted by key;
    // unusable ones by name, after them.
    std::map<osgLoA::FilterCacheKey, Unit> byKey;
    std::vector<Unit> problems;
    for (std::size_t i = 0; i < textures.size(); ++i)
    {
        osg::Texture2D* t = textures[i].get();
        Unit u;
        u.label = loa::textureLabel(*t, i);
        u.image = t->getImage();
        u.border = osgLoA::ImageBorder::of(*t);
        u.textures.push_back(t);
        if (!u.image)
            u.problem = "has no image (its file could not be read?)";
        else if (u.image->s() <= 0 || u.image->t() <= 0 || !u.image->data())
            u.problem =
                "is empty (" + loa::imageSizeText(*u.image) + "): its file is missing, corrupt or unreadable";
        else if (unsigned(u.image->s()) > o.maxSize || unsigned(u.image->t()) > o.maxSize)
            u.problem =
                "is " + loa::imageSizeText(*u.image) + ", above --max-size " + std::to_string(o.maxSize);
        if (!u.problem.empty())
        {
            problems.push_back(u);
            continue;
        }
        u.key = osgLoA::FilterCache::makeKey(osgLoA::FilterCache::imageHash(*u.image), u.border, parameters);
        auto it = byKey.find(u.key);
        if (it == byKey.end())
            byKey.emplace(u.key, u);
        else
            it->second.textures.push_back(t);
    }
    std::stable_sort(problems.begin(), problems.end(),
                     [](const Unit& a, const Unit& b) { return a.label < b.label; });
    std::vector<Unit> all;
    for (auto& kv : byKey)
        all.push_back(kv.second);
    all.insert(all.end(), problems.begin(), problems.end());
    std::vector<Unit> units;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (i % o.shardCount == o.shardIndex) units.push_back(all[i]);

    // GPU: one context and engine, used from this thread only.
    osg::ref_ptr<osgLoA::HeadlessContext> context;
    osg::ref_ptr<osgLoA::GpuFilterEngine> engine;
    const bool onGpu = o.gpu && filter->hasGpuImplementation();
    if (o.gpu && !onGpu)
        std::cerr << "loa-prefilter: note: filter '" << filter->filterName()
                  << "' has no GPU implementation; filtering on the CPU\n";
    if (onGpu)
    {
        context = new osgLoA::HeadlessContext;
        if (!context->realize() || !context->makeCurrent())
            throw osgLoA::HeadlessContextError("cannot make the headless EGL context current");
        try
        {
            engine = new osgLoA::GpuFilterEngine(*context->getState());
        }
        catch (const osgLoA::GpuFilterError& e)
        {
            throw osgLoA::HeadlessContextError(e.what());
        }
    }

    const unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
    const unsigned workers = onGpu ? 1u : std::max(1u, std::min<unsigned>(jobs, unsigned(units.size())));
    osg::ref_ptr<osgLoA::MipmapFilter> mipmapFilter = new osgLoA::MipmapFilter(filter.get(), cache.get());
    mipmapFilter->setNumThreads(std::max(1u, jobs / workers));
    mipmapFilter->setEngine(engine.get());

    std::cerr << "loa-prefilter: " << o.model << ": " << textures.size() << " 2D textures, " << all.size()
              << " distinct images";
    if (otherTextures) std::cerr << " (" << otherTextures << " other textures ignored)";
    if (o.shardCount > 1)
        std::cerr << "; shard " << o.shardIndex << "/" << o.shardCount << ": " << units.size();
    std::cerr << "; " << parameters << " on "
              << (onGpu ? std::string("the GPU") : std::to_string(workers) + " thread(s)") << "\n";

    loa::ProgressBar progress("loa-prefilter", units.size(), "images");
    std::atomic<std::size_t> next{0}, filtered{0}, cached{0}, skipped{0}, storeFailures{0};
    std::vector<osg::ref_ptr<osg::Image>> results(units.size());
    auto work = [&]
    {
        for (std::size_t i = next++; i < units.size(); i = next++)
        {
            Unit& u = units[i];
            if (!u.problem.empty())
            {
                ++skipped;
                progress.done("skipped " + u.label + ": " + u.problem, true);
                continue;
            }
            try
            {
                osgLoA::MipmapFilter::Result r;
                osg::ref_ptr<osg::Image> pyramid = mipmapFilter->filterImage(*u.image, u.border, &r);
                if (!o.exportPath.empty()) results[i] = pyramid;
                char ms[32];
                std::snprintf(ms, sizeof ms, "%.0f ms", r.milliseconds);
                if (!r.storeError.empty())
                {
                    ++storeFailures;
                    progress.done("not stored " + u.label + ": " + r.storeError, true);
                }
                else if (r.source == osgLoA::MipmapFilter::CACHE)
                {
                    ++cached;
                    progress.done("cached " + u.label + " " + loa::imageSizeText(*u.image) + " (" + ms + ")",
                                  false);
                }
                else
                {
                    ++filtered;
                    progress.done(
                        "filtered " + u.label + " " + loa::imageSizeText(*u.image) + " (" + ms + ")", false);
                }
            }
            catch (const std::exception& e)
            {
                ++skipped;
                // "MipmapFilter: image 'LABEL': FilterImage: REASON" -> "LABEL: REASON"
                std::string why = e.what();
                const std::string quoted = "'" + u.label + "': ";
                const std::size_t at = why.find(quoted);
                if (at != std::string::npos) why = why.substr(at + quoted.size());
                if (why.compare(0, 13, "FilterImage: ") == 0) why = why.substr(13);
                progress.done("skipped " + u.label + ": " + why, true);
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < workers; ++i)
        pool.emplace_back(work);
    work();
    for (std::thread& t : pool)
        t.join();
    progress.finish();
    if (engine.valid()) engine->releaseGLObjects();

    if (!o.exportPath.empty())
    {
        std::size_t expected = 0;
        for (std::size_t i = 0; i < units.size(); ++i)
            if (results[i].valid())
                for (auto& t : units[i].textures)
                {
                    osgLoA::MipmapFilter::applyPyramid(*t, results[i].get());
                    if (results[i]->isMipmap()) ++expected;
                }
        osgLoA::AtomicFile::writeNode(o.exportPath, *scene);
        // Read it back: the levels must have survived.
        osg::ref_ptr<osg::Node> back = osgDB::readNodeFile(o.exportPath);
        if (!back) throw std::runtime_error("cannot read back '" + o.exportPath + "'");
        std::set<osg::Texture2D*> backTextures;
        osgLoA::StateSetVisitor count(
            [&](osg::StateSet& ss)
            {
                for (const osg::StateSet::AttributeList& unit : ss.getTextureAttributeList())
                    for (const auto& entry : unit)
                        if (osg::Texture2D* t = dynamic_cast<osg::Texture2D*>(entry.second.first.get()))
                            if (t->getImage() && t->getImage()->isMipmap()) backTextures.insert(t);
            });
        back->accept(count);
        if (backTextures.size() < expected)
            throw std::runtime_error("'" + o.exportPath +
                                     "' lost mip levels: " + std::to_string(backTextures.size()) + " of " +
                                     std::to_string(expected) + " filtered textures read back with levels");
        std::cerr << "loa-prefilter: wrote " << o.exportPath << " (" << expected
                  << " textures with filtered levels)\n";
    }

    std::cerr << "loa-prefilter: " << units.size() << " images: " << filtered << " filtered, " << cached
              << " cached, " << skipped << " skipped";
    if (storeFailures) std::cerr << ", " << storeFailures << " not stored";
    std::cerr << " in " << loa::durationText(progress.elapsed()) << "; cache " << cache->getDirectory()
              << "\n";
    if (storeFailures) return loa::kFailure;
    return skipped ? kSkipped : loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    Options o;
    return loa::runTool(
        "loa-prefilter", [&] { o = parse(argc, argv); }, [&] { return run(o); });
}
