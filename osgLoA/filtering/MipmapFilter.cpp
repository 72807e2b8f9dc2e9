/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/MipmapFilter>

#include <osg/Notify>
#include <osg/ValueObject>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace osgLoA
{

namespace
{
std::string describe(const osg::Image& image)
{
    std::string name = !image.getFileName().empty() ? image.getFileName() : image.getName();
    return "image '" + (name.empty() ? std::string("(unnamed)") : name) + "'";
}

/** Rows [y0 - r, y1 + r) of a level, read through the T wrap mode. */
FilterImage cropRows(const FilterImage& level, int y0, int y1, int r, WrapMode wrapT)
{
    FilterImage crop(level.width(), y1 - y0 + 2 * r);
    const std::size_t rowFloats = std::size_t(level.width()) * 4;
    for (int y = 0; y < crop.height(); ++y)
    {
        const int source = wrapIndex(y0 - r + y, level.height(), wrapT);
        std::copy(level.texel(0, source), level.texel(0, source) + rowFloats, crop.texel(0, y));
    }
    return crop;
}
} // namespace

MipmapFilter::MipmapFilter(ImageFilter* filter, FilterCache* cache) : _filter(filter), _cache(cache) {}

int MipmapFilter::levelCount(int width, int height)
{
    int n = 1;
    while (width > 1 || height > 1)
    {
        width = std::max(1, width / 2);
        height = std::max(1, height / 2);
        ++n;
    }
    return n;
}

std::vector<FilterImage> MipmapFilter::filterLevelsCPU(const std::vector<FilterImage>& pyramid,
                                                       const ImageBorder& border) const
{
    const ImageFilter& filter = *_filter;
    const unsigned threads = _numThreads ? _numThreads : std::max(1u, std::thread::hardware_concurrency());
    const int radius = _splitLevels && threads > 1 ? filter.dependencyRadius() : -1;

    // Work items: whole levels, or strips [y0, y1) of rows of the larger levels.
    struct Task
    {
        std::size_t level;
        int y0, y1;
        bool whole;
    };
    std::vector<Task> tasks;
    for (std::size_t k = 0; k < pyramid.size(); ++k)
    {
        const int h = pyramid[k].height();
        int strips = 1;
        if (radius >= 0) strips = std::max(1, std::min(int(threads), h / std::max(16, 4 * radius)));
        if (strips == 1)
            tasks.push_back({k, 0, h, true});
        else
            for (int s = 0; s < strips; ++s)
                tasks.push_back(
                    {k, int(std::int64_t(h) * s / strips), int(std::int64_t(h) * (s + 1) / strips), false});
    }
    // Largest first, so that the small levels fill the gaps at the end.
    std::stable_sort(tasks.begin(), tasks.end(),
                     [&](const Task& a, const Task& b)
                     {
                         return std::size_t(a.y1 - a.y0) * std::size_t(pyramid[a.level].width()) >
                                std::size_t(b.y1 - b.y0) * std::size_t(pyramid[b.level].width());
                     });

    std::vector<FilterImage> out(pyramid.size());
    for (std::size_t k = 0; k < pyramid.size(); ++k)
        if (!std::any_of(tasks.begin(), tasks.end(), [k](const Task& t) { return t.level == k && t.whole; }))
            out[k] = FilterImage(pyramid[k].width(), pyramid[k].height());

    auto runTask = [&](const Task& t)
    {
        const FilterImage& level = pyramid[t.level];
        if (t.whole)
        {
            out[t.level] = filter.apply(level, border);
            return;
        }
        // The strip's rows depend on at most `radius` rows either side: filter them with that
        // halo (wrapped as the level wraps) and keep the middle.
        const FilterImage filtered = filter.apply(cropRows(level, t.y0, t.y1, radius, border.t),
                                                  ImageBorder(border.s, WrapMode::Clamp));
        FilterImage& dst = out[t.level];
        const std::size_t rowFloats = std::size_t(level.width()) * 4;
        for (int y = t.y0; y < t.y1; ++y)
            std::copy(filtered.texel(0, y - t.y0 + radius), filtered.texel(0, y - t.y0 + radius) + rowFloats,
                      dst.texel(0, y));
    };

    const unsigned workers = std::min<unsigned>(threads, unsigned(tasks.size()));
    if (workers <= 1)
    {
        for (const Task& t : tasks)
            runTask(t);
        return out;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto work = [&]
    {
        for (std::size_t i = next++; i < tasks.size(); i = next++)
        {
            try
            {
                runTask(tasks[i]);
            }
            catch (...)
            {
                std::lock_guard<std::mutex> lock(errorMutex);
                if (!error) error = std::current_exception();
                next = tasks.size();
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < workers; ++i)
        pool.emplace_back(work);
    work();
    for (std::thread& t : pool)
        t.join();
    if (error) std::rethrow_exception(error);
    return out;
}

std::vector<FilterImage> MipmapFilter::filterLevels(const FilterImage& image, const ImageBorder& border) const
{
    if (!_filter) throw std::invalid_argument("MipmapFilter: no filter set");
    if (image.empty())
        throw std::invalid_argument("MipmapFilter: the image is empty (" + std::to_string(image.width()) +
                                    "x" + std::to_string(image.height()) + ")");
    const std::vector<FilterImage> pyramid = image.mipPyramid();
    if (_engine.valid() && _filter->hasGpuImplementation()) return filterLevelsGPU(pyramid, border);
    return filterLevelsCPU(pyramid, border);
}

std::vector<FilterImage> MipmapFilter::filterLevelsGPU(const std::vector<FilterImage>& pyramid,
                                                       const ImageBorder& border) const
{
    // One atlas for the whole pyramid, so that one engine run (one dispatch per pass) filters
    // every level: level 0 at the origin, levels 1..n stacked in a column to its right. Each
    // level is a region with the texture's wrap modes (paper 000 Fig. 5's page table), so no
    // level reads its neighbours.
    GpuFilterEngine& engine = *_engine;
    std::vector<GpuFilterEngine::Region> regions(pyramid.size());
    int column = 0, width = pyramid[0].width(), height = pyramid[0].height();
    for (std::size_t k = 0; k < pyramid.size(); ++k)
    {
        GpuFilterEngine::Region& r = regions[k];
        r.width = pyramid[k].width();
        r.height = pyramid[k].height();
        r.border = border;
        if (k > 0)
        {
            r.x = pyramid[0].width();
            r.y = column;
            column += r.height;
            width = std::max(width, r.x + r.width);
            height = std::max(height, column);
        }
    }
    unsigned source = 0, destination = 0;
    try
    {
        source = engine.createAtlas(width, height);
        destination = engine.createAtlas(width, height);
    }
    catch (const GpuFilterError&)
    {
        // Larger than GL_MAX_TEXTURE_SIZE or than memory allows: one level at a time.
        if (source) engine.destroyAtlas(source);
        std::vector<FilterImage> out;
        out.reserve(pyramid.size());
        for (const FilterImage& level : pyramid)
            out.push_back(engine.filter(*_filter, level, border));
        return out;
    }
    try
    {
        for (std::size_t k = 0; k < pyramid.size(); ++k)
            engine.upload(source, regions[k], pyramid[k]);
        engine.run(*_filter, source, destination, regions);
        std::vector<FilterImage> out;
        out.reserve(pyramid.size());
        for (std::size_t k = 0; k < pyramid.size(); ++k)
            out.push_back(engine.download(destination, regions[k]));
        engine.destroyAtlas(source);
        engine.destroyAtlas(destination);
        return out;
    }
    catch (...)
    {
        engine.destroyAtlas(source);
        engine.destroyAtlas(destination);
        throw;
    }
}

osg::ref_ptr<osg::Image> MipmapFilter::toMipmappedImage(const std::vector<FilterImage>& levels)
{
    if (levels.empty() || levels[0].empty())
        throw std::invalid_argument("MipmapFilter::toMipmappedImage: no levels");
    const int n = levelCount(levels[0].width(), levels[0].height());
    if (int(levels.size()) != n)
        throw std::invalid_argument("MipmapFilter::toMipmappedImage: " + std::to_string(levels.size()) +
                                    " levels given; a " + std::to_string(levels[0].width()) + "x" +
                                    std::to_string(levels[0].height()) + " pyramid has " + std::to_string(n));
    std::size_t total = 0;
    {
        int w = levels[0].width(), h = levels[0].height();
        for (const FilterImage& l : levels)
        {
            if (l.width() != w || l.height() != h)
                throw std::invalid_argument("MipmapFilter::toMipmappedImage: level of size " +
                                            std::to_string(l.width()) + "x" + std::to_string(l.height()) +
                                            " where " + std::to_string(w) + "x" + std::to_string(h) +
                                            " belongs");
            total += std::size_t(w) * std::size_t(h) * 4;
            w = std::max(1, w / 2);
            h = std::max(1, h / 2);
        }
    }
    if (total > 0xffffffffull)
        throw std::invalid_argument("MipmapFilter: a " + std::to_string(levels[0].width()) + "x" +
                                    std::to_string(levels[0].height()) +
                                    " RGBA8 pyramid exceeds the 4 GiB osg::Image's mipmap offsets address");
    unsigned char* data = new unsigned char[total];
    osg::Image::MipmapDataType offsets;
    std::size_t at = 0;
    for (std::size_t k = 0; k < levels.size(); ++k)
    {
        if (k > 0) offsets.push_back(static_cast<unsigned int>(at));
        const std::vector<float>& v = levels[k].data();
        for (std::size_t i = 0; i < v.size(); ++i)
            data[at + i] =
                static_cast<unsigned char>(std::lround(std::min(1.0f, std::max(0.0f, v[i])) * 255.0f));
        at += v.size();
    }
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->setImage(levels[0].width(), levels[0].height(), 1, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, data,
                    osg::Image::USE_NEW_DELETE, 1);
    image->setMipmapLevels(offsets);
    image->setWriteHint(osg::Image::STORE_INLINE);
    return image;
}

std::vector<FilterImage> MipmapFilter::levelsOf(const osg::Image& image)
{
    std::vector<FilterImage> levels;
    if (!image.isMipmap())
    {
        levels.push_back(FilterImage::fromImage(image));
        return levels;
    }
    if (image.getPixelFormat() != GL_RGBA || image.getDataType() != GL_UNSIGNED_BYTE)
        throw std::invalid_argument("MipmapFilter::levelsOf: " + describe(image) +
                                    " with mipmaps is not GL_RGBA / GL_UNSIGNED_BYTE");
    int w = image.s(), h = image.t();
    for (unsigned k = 0; k < image.getNumMipmapLevels(); ++k)
    {
        FilterImage level(w, h);
        const unsigned char* p = image.getMipmapData(k);
        const std::size_t step =
            osg::Image::computeRowWidthInBytes(w, GL_RGBA, GL_UNSIGNED_BYTE, image.getPacking());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w * 4; ++x)
                level.texel(0, y)[x] = p[std::size_t(y) * step + std::size_t(x)] / 255.0f;
        levels.push_back(std::move(level));
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    return levels;
}

osg::ref_ptr<osg::Image> MipmapFilter::filterImage(const osg::Image& image, const ImageBorder& border,
                                                   Result* result) const
{
    const auto t0 = std::chrono::steady_clock::now();
    Result local;
    Result& r = result ? *result : local;
    r = Result();
    if (!_filter) throw std::invalid_argument("MipmapFilter: no filter set");
    if (image.s() <= 0 || image.t() <= 0 || !image.data())
        throw std::invalid_argument("MipmapFilter: " + describe(image) + " is empty (" +
                                    std::to_string(image.s()) + "x" + std::to_string(image.t()) + ")");
    if (image.s() > FilterImage::maxDimension() || image.t() > FilterImage::maxDimension())
        throw std::invalid_argument("MipmapFilter: " + describe(image) + " is " + std::to_string(image.s()) +
                                    "x" + std::to_string(image.t()) + ", above the limit of " +
                                    std::to_string(FilterImage::maxDimension()));
    if (image.r() != 1) throw std::invalid_argument("MipmapFilter: " + describe(image) + " is 3D");
    // Compressed images: FilterImage::fromImage decodes S3TC and names any other format.

    const std::string parameters = _filter->getParameterString();
    osg::ref_ptr<osg::Image> pyramid;
    if (_cache.valid())
    {
        r.key = FilterCache::makeKey(FilterCache::imageHash(image), border, parameters);
        pyramid = _cache->load(r.key);
        if (pyramid.valid()) r.source = CACHE;
    }
    if (!pyramid.valid())
    {
        FilterImage input;
        try
        {
            input = FilterImage::fromImage(image);
        }
        catch (const std::invalid_argument& e)
        {
            throw std::invalid_argument("MipmapFilter: " + describe(image) + ": " + e.what());
        }
        r.source = _engine.valid() && _filter->hasGpuImplementation() ? GPU : CPU;
        pyramid = toMipmappedImage(filterLevels(input, border));
        if (_cache.valid())
        {
            try
            {
                _cache->store(r.key, *pyramid);
                r.stored = true;
            }
            catch (const std::runtime_error& e)
            {
                r.storeError = e.what();
                if (!_warnedStore.exchange(true))
                    OSG_WARN << "osgLoA::MipmapFilter: " << e.what()
                             << "; continuing without storing filtered pyramids" << std::endl;
            }
        }
    }
    const std::string name = !image.getFileName().empty() ? image.getFileName() : image.getName();
    pyramid->setName(name);
    pyramid->setOrigin(image.getOrigin());
    pyramid->setWriteHint(osg::Image::STORE_INLINE);
    pyramid->setUserValue("osgLoA.filter", parameters);
    r.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return pyramid;
}

void MipmapFilter::applyPyramid(osg::Texture2D& texture, osg::Image* pyramid)
{
    texture.setImage(pyramid);
    texture.setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    texture.setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    texture.setUseHardwareMipMapGeneration(false);
    texture.setResizeNonPowerOfTwoHint(false);
    texture.setInternalFormatMode(osg::Texture::USE_IMAGE_DATA_FORMAT);
}

osg::ref_ptr<osg::Texture2D> MipmapFilter::filterTexture(const osg::Texture2D& texture, Result* result) const
{
    const osg::Image* image = texture.getImage();
    if (!image) throw std::invalid_argument("MipmapFilter: texture '" + texture.getName() + "' has no image");
    osg::ref_ptr<osg::Image> pyramid = filterImage(*image, ImageBorder::of(texture), result);
    osg::ref_ptr<osg::Texture2D> out = new osg::Texture2D(texture, osg::CopyOp::SHALLOW_COPY);
    applyPyramid(*out, pyramid.get());
    return out;
}

} // namespace osgLoA
