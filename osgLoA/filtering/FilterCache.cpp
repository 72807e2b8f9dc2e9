/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterCache>

#include "../util/ByteOrder.h"

#include <osg/Notify>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <functional>
#include <sstream>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

namespace osgLoA
{

namespace
{
const char kMagic[8] = {'o', 's', 'g', 'L', 'o', 'A', 'F', 'C'};
constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;
constexpr std::uint64_t kMurmurM = 0xc6a4a7935bd1e995ull;
constexpr int kMurmurR = 47;

/** FNV-1a 64 over bytes (Fowler, Noll, Vo). */
std::uint64_t fnv1a(std::uint64_t h, const unsigned char* p, std::size_t n)
{
    for (std::size_t i = 0; i < n; ++i)
    {
        h ^= p[i];
        h *= kFnvPrime;
    }
    return h;
}

/** The two 64-bit hashes of a byte stream fed in pieces: FNV-1a over bytes, and a
 *  MurmurHash64A-style hash over little-endian 8-byte words (the tail zero-padded; the length
 *  mixed in at the end). The two share no structure, so a pair of inputs that collides in one
 *  is no more likely to collide in the other. */
class Hasher
{
public:
    void update(const void* data, std::size_t n)
    {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        _fnv = fnv1a(_fnv, p, n);
        _length += n;
        while (n > 0 && _carried > 0 && _carried < 8)
        {
            _carry[_carried++] = *p++;
            --n;
            if (_carried == 8)
            {
                word(_carry);
                _carried = 0;
            }
        }
        for (; n >= 8; n -= 8, p += 8)
            word(p);
        for (; n > 0; --n)
            _carry[_carried++] = *p++;
    }
    template <class T> void value(T v)
    {
        unsigned char b[sizeof(T)];
        for (std::size_t i = 0; i < sizeof(T); ++i)
            b[i] = static_cast<unsigned char>((std::uint64_t(v) >> (8 * i)) & 0xffu);
        update(b, sizeof b);
    }
    void text(const std::string& s)
    {
        value<std::uint64_t>(s.size());
        update(s.data(), s.size());
    }
    FilterCacheKey finish()
    {
        if (_carried > 0)
        {
            unsigned char last[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            std::memcpy(last, _carry, _carried);
            word(last);
            _carried = 0;
        }
        std::uint64_t h = _murmur ^ (std::uint64_t(_length) * kMurmurM);
        h ^= h >> kMurmurR;
        h *= kMurmurM;
        h ^= h >> kMurmurR;
        FilterCacheKey k;
        k.high = _fnv;
        k.low = h;
        return k;
    }

private:
    void word(const unsigned char* p)
    {
        std::uint64_t k = 0;
        for (int i = 7; i >= 0; --i)
            k = (k << 8) | p[i];
        k *= kMurmurM;
        k ^= k >> kMurmurR;
        k *= kMurmurM;
        _murmur ^= k;
        _murmur *= kMurmurM;
    }
    std::uint64_t _fnv = kFnvOffset;
    std::uint64_t _murmur = 0x9e3779b97f4a7c15ull; // seed
    std::uint64_t _length = 0;
    unsigned char _carry[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    std::size_t _carried = 0;
};

int levelCountFor(int w, int h)
{
    int n = 1;
    while (w > 1 || h > 1)
    {
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
        ++n;
    }
    return n;
}

/** Checks that image is an RGBA8 pyramid down to 1x1; throws std::invalid_argument. */
void checkPyramid(const osg::Image& image)
{
    if (!image.data() || image.s() <= 0 || image.t() <= 0 || image.r() != 1)
        throw std::invalid_argument("FilterCache: the pyramid image is empty or 3D");
    if (image.getPixelFormat() != GL_RGBA || image.getDataType() != GL_UNSIGNED_BYTE)
        throw std::invalid_argument("FilterCache: the pyramid image is not GL_RGBA / GL_UNSIGNED_BYTE");
    const int n = levelCountFor(image.s(), image.t());
    if (int(image.getNumMipmapLevels()) != n)
        throw std::invalid_argument("FilterCache: the pyramid image has " +
                                    std::to_string(image.getNumMipmapLevels()) + " levels; a " +
                                    std::to_string(image.s()) + "x" + std::to_string(image.t()) +
                                    " pyramid has " + std::to_string(n));
}

bool makeDirectories(const std::string& dir, std::string& why)
{
    if (dir.empty()) return true;
    struct stat st;
    if (::stat(dir.c_str(), &st) == 0)
    {
        if (S_ISDIR(st.st_mode)) return true;
        why = "'" + dir + "' exists and is not a directory";
        return false;
    }
    const std::size_t slash = dir.find_last_of('/');
    if (slash != std::string::npos && slash > 0 && !makeDirectories(dir.substr(0, slash), why)) return false;
    if (::mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST)
    {
        why = "cannot create directory '" + dir + "': " + std::strerror(errno);
        return false;
    }
    return true;
}

/** Writes bytes to path through a temporary file beside it and rename(2). */
void writeAtomically(const std::string& path, const std::string& bytes)
{
    static std::atomic<unsigned long> counter{0};
    const std::size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash);
    std::string why;
    if (!makeDirectories(dir, why))
        throw std::runtime_error("FilterCache: cannot write '" + path + "': " + why);
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    std::ostringstream temp;
    temp << (dir.empty() ? std::string() : dir + "/") << "." << base << ".tmp-" << ::getpid() << "-"
         << std::hash<std::thread::id>()(std::this_thread::get_id()) % 1000000007ul << "-" << counter++;
    const std::string tempPath = temp.str();
    const int fd = ::open(tempPath.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_TRUNC, 0666);
    if (fd < 0) throw std::runtime_error("FilterCache: cannot write '" + path + "': " + std::strerror(errno));
    std::size_t done = 0;
    int error = 0;
    while (done < bytes.size())
    {
        const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (w < 0)
        {
            if (errno == EINTR) continue;
            error = errno;
            break;
        }
        done += std::size_t(w);
    }
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error == 0 && std::rename(tempPath.c_str(), path.c_str()) != 0) error = errno;
    if (error != 0)
    {
        std::remove(tempPath.c_str());
        throw std::runtime_error("FilterCache: cannot write '" + path + "': " + std::strerror(error));
    }
}
} // namespace

std::string FilterCacheKey::hex() const
{
    char b[33];
    std::snprintf(b, sizeof b, "%016llx%016llx", static_cast<unsigned long long>(high),
                  static_cast<unsigned long long>(low));
    return b;
}

FilterCache::FilterCache(const std::string& directory)
    : _directory(directory.empty() ? defaultDirectory() : directory)
{
    if (_directory.empty())
        throw std::runtime_error(
            "FilterCache: no cache directory: set OSGLOA_FILTER_CACHE, XDG_CACHE_HOME or HOME");
    while (_directory.size() > 1 && _directory.back() == '/')
        _directory.pop_back();
}

std::string FilterCache::defaultDirectory()
{
    const char* explicitDir = std::getenv("OSGLOA_FILTER_CACHE");
    if (explicitDir && *explicitDir) return explicitDir;
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    if (xdg && xdg[0] == '/') return std::string(xdg) + "/osgLoA/filters";
    const char* home = std::getenv("HOME");
    if (home && *home) return std::string(home) + "/.cache/osgLoA/filters";
    return std::string();
}

FilterCacheKey FilterCache::hash128(const void* data, std::size_t size)
{
    Hasher h;
    h.update(data, size);
    return h.finish();
}

FilterCacheKey FilterCache::imageHash(const osg::Image& image)
{
    if (!image.data() || image.s() <= 0 || image.t() <= 0 || image.r() <= 0)
        throw std::invalid_argument("FilterCache: image '" + image.getFileName() + "' has no data (" +
                                    std::to_string(image.s()) + "x" + std::to_string(image.t()) + ")");
    Hasher h;
    h.text("osgLoA image");
    h.value<std::int32_t>(image.s());
    h.value<std::int32_t>(image.t());
    h.value<std::int32_t>(image.r());
    h.value<std::uint32_t>(image.getPixelFormat());
    h.value<std::uint32_t>(image.getDataType());
    if (image.isCompressed())
        h.update(image.data(), image.getImageSizeInBytes());
    else
    {
        const std::size_t rowBytes =
            (std::size_t(image.s()) *
                 osg::Image::computePixelSizeInBits(image.getPixelFormat(), image.getDataType()) +
             7) /
            8;
        if (rowBytes == 0)
            throw std::invalid_argument("FilterCache: image '" + image.getFileName() +
                                        "' has a pixel format without a size");
        for (int r = 0; r < image.r(); ++r)
            for (int t = 0; t < image.t(); ++t)
                h.update(image.data(0, t, r), rowBytes);
    }
    return h.finish();
}

FilterCacheKey FilterCache::makeKey(const FilterCacheKey& image, const ImageBorder& border,
                                    const std::string& filterParameters)
{
    Hasher h;
    h.text("osgLoA FilterCache");
    h.value<std::uint32_t>(FORMAT_VERSION);
    h.value<std::uint64_t>(image.high);
    h.value<std::uint64_t>(image.low);
    h.value<std::uint8_t>(static_cast<std::uint8_t>(border.s));
    h.value<std::uint8_t>(static_cast<std::uint8_t>(border.t));
    h.text(filterParameters);
    return h.finish();
}

std::string FilterCache::pathOf(const FilterCacheKey& key) const
{
    const std::string hex = key.hex();
    return _directory + "/" + hex.substr(0, 2) + "/" + hex + ".loafc";
}

std::string FilterCache::encode(const FilterCacheKey& key, const osg::Image& pyramid)
{
    checkPyramid(pyramid);
    const int n = int(pyramid.getNumMipmapLevels());
    std::string out;
    std::size_t payload = 0;
    {
        int w = pyramid.s(), h = pyramid.t();
        for (int k = 0; k < n; ++k)
        {
            payload += std::size_t(w) * std::size_t(h) * 4;
            w = std::max(1, w / 2);
            h = std::max(1, h / 2);
        }
    }
    out.reserve(48 + 8 * std::size_t(n) + payload);
    out.append(kMagic, 8);
    detail::putLE(out, FORMAT_VERSION, 4);
    detail::putLE(out, std::uint32_t(n), 4);
    detail::putLE(out, key.high, 8);
    detail::putLE(out, key.low, 8);
    int w = pyramid.s(), h = pyramid.t();
    for (int k = 0; k < n; ++k)
    {
        detail::putLE(out, std::uint32_t(w), 4);
        detail::putLE(out, std::uint32_t(h), 4);
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    detail::putLE(out, payload, 8);
    w = pyramid.s(), h = pyramid.t();
    for (int k = 0; k < n; ++k)
    {
        const unsigned char* level = pyramid.getMipmapData(unsigned(k));
        const std::size_t step =
            osg::Image::computeRowWidthInBytes(w, GL_RGBA, GL_UNSIGNED_BYTE, pyramid.getPacking());
        for (int y = 0; y < h; ++y)
            out.append(reinterpret_cast<const char*>(level + std::size_t(y) * step), std::size_t(w) * 4);
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    detail::putLE(out, fnv1a(kFnvOffset, reinterpret_cast<const unsigned char*>(out.data()), out.size()), 8);
    return out;
}

osg::ref_ptr<osg::Image> FilterCache::decode(const std::string& bytes, const FilterCacheKey& key,
                                             std::string& why)
{
    if (bytes.size() < 48)
    {
        why = "truncated (" + std::to_string(bytes.size()) + " bytes)";
        return nullptr;
    }
    if (std::memcmp(bytes.data(), kMagic, 8) != 0)
    {
        why = "not a filter cache file (bad magic)";
        return nullptr;
    }
    const std::uint64_t version = detail::getLE(bytes, 8, 4);
    if (version != FORMAT_VERSION)
    {
        why = "format version " + std::to_string(version) + " (this build reads " +
              std::to_string(FORMAT_VERSION) + ")";
        return nullptr;
    }
    const std::uint64_t n = detail::getLE(bytes, 12, 4);
    if (n < 1 || n > std::uint64_t(MAX_LEVELS))
    {
        why = "implausible level count " + std::to_string(n);
        return nullptr;
    }
    FilterCacheKey stored;
    stored.high = detail::getLE(bytes, 16, 8);
    stored.low = detail::getLE(bytes, 24, 8);
    const std::size_t header = 32 + 8 * std::size_t(n) + 8;
    if (bytes.size() < header + 8)
    {
        why = "truncated (" + std::to_string(bytes.size()) + " bytes)";
        return nullptr;
    }
    const std::uint64_t width = detail::getLE(bytes, 32, 4), height = detail::getLE(bytes, 36, 4);
    if (width < 1 || height < 1 || width > std::uint64_t(FilterImage::maxDimension()) ||
        height > std::uint64_t(FilterImage::maxDimension()) ||
        std::uint64_t(levelCountFor(int(width), int(height))) != n)
    {
        why = "implausible size " + std::to_string(width) + "x" + std::to_string(height) + " with " +
              std::to_string(n) + " levels";
        return nullptr;
    }
    std::uint64_t payload = 0;
    {
        std::uint64_t w = width, h = height;
        for (std::uint64_t k = 0; k < n; ++k)
        {
            if (detail::getLE(bytes, 32 + 8 * std::size_t(k), 4) != w ||
                detail::getLE(bytes, 36 + 8 * std::size_t(k), 4) != h)
            {
                why = "level " + std::to_string(k) + " has the wrong size";
                return nullptr;
            }
            payload += w * h * 4;
            w = std::max<std::uint64_t>(1, w / 2);
            h = std::max<std::uint64_t>(1, h / 2);
        }
    }
    if (payload > 0xffffffffull)
    {
        why = "pyramid larger than osg::Image's 32-bit mipmap offsets allow";
        return nullptr;
    }
    if (detail::getLE(bytes, header - 8, 8) != payload)
    {
        why = "payload size field does not match the level sizes";
        return nullptr;
    }
    if (bytes.size() != header + payload + 8)
    {
        why = (bytes.size() < header + payload + 8 ? "truncated (" : "trailing bytes (") +
              std::to_string(bytes.size()) + " bytes, expected " + std::to_string(header + payload + 8) + ")";
        return nullptr;
    }
    const std::uint64_t sum =
        fnv1a(kFnvOffset, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size() - 8);
    if (sum != detail::getLE(bytes, bytes.size() - 8, 8))
    {
        why = "checksum mismatch";
        return nullptr;
    }
    if (stored != key)
    {
        why = "the file holds key " + stored.hex();
        return nullptr;
    }
    unsigned char* data = new unsigned char[payload];
    std::memcpy(data, bytes.data() + header, payload);
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->setImage(int(width), int(height), 1, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, data,
                    osg::Image::USE_NEW_DELETE, 1);
    osg::Image::MipmapDataType offsets;
    std::uint64_t offset = 0, w = width, h = height;
    for (std::uint64_t k = 1; k < n; ++k)
    {
        offset += w * h * 4;
        offsets.push_back(static_cast<unsigned int>(offset));
        w = std::max<std::uint64_t>(1, w / 2);
        h = std::max<std::uint64_t>(1, h / 2);
    }
    image->setMipmapLevels(offsets);
    return image;
}

osg::ref_ptr<osg::Image> FilterCache::load(const FilterCacheKey& key)
{
    const std::string path = pathOf(key);
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        ++_misses;
        return nullptr;
    }
    std::ostringstream buffer;
    buffer << in.rdbuf();
    std::string why;
    osg::ref_ptr<osg::Image> image;
    if (in.bad())
        why = "read error";
    else
        image = decode(buffer.str(), key, why);
    if (!image)
    {
        ++_misses;
        ++_corrupt;
        OSG_WARN << "osgLoA::FilterCache: ignoring cache file '" << path << "': " << why
                 << "; the pyramid is filtered again and the file rewritten" << std::endl;
        return nullptr;
    }
    ++_hits;
    return image;
}

void FilterCache::store(const FilterCacheKey& key, const osg::Image& pyramid)
{
    const std::string bytes = encode(key, pyramid);
    writeAtomically(pathOf(key), bytes);
    ++_stores;
}

void FilterCache::checkWritable() const
{
    std::string why;
    if (!makeDirectories(_directory, why))
        throw std::runtime_error("filter cache directory '" + _directory + "' is not usable: " + why);
    const std::string probe = _directory + "/.probe-" + std::to_string(::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (fd < 0)
        throw std::runtime_error("filter cache directory '" + _directory +
                                 "' is not writable: " + std::strerror(errno));
    ::close(fd);
    std::remove(probe.c_str());
}

void FilterCache::resetCounters()
{
    _hits = 0;
    _misses = 0;
    _corrupt = 0;
    _stores = 0;
}

} // namespace osgLoA
