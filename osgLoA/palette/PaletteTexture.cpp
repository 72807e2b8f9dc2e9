/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterCache>
#include <osgLoA/palette/PaletteTexture>

#include "../util/ByteOrder.h"
#include <osgLoA/util/AtomicFile>

#include <osg/Notify>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
const char kMagic[8] = {'o', 's', 'g', 'L', 'o', 'A', 'P', 'T'};
constexpr unsigned kMaxSide = 65535;

void putHash(std::string& s, const FilterCacheKey& k)
{
    detail::putLE(s, k.high, 8);
    detail::putLE(s, k.low, 8);
}
FilterCacheKey hashOf(const std::string& bytes, std::size_t size)
{
    return FilterCache::hash128(bytes.data(), size);
}
unsigned char encode8(float v)
{
    return static_cast<unsigned char>(std::lround(std::min(std::max(v, 0.0f), 1.0f) * 255.0f));
}
} // namespace

std::vector<osg::Vec3d> PaletteTexture::sortedLevel(const PaletteHierarchy& hierarchy, unsigned k)
{
    std::vector<osg::Vec3d> lab = hierarchy.paletteLab(k);
    std::stable_sort(lab.begin(), lab.end(),
                     [](const osg::Vec3d& p, const osg::Vec3d& q)
                     {
                         if (p.x() != q.x()) return p.x() < q.x();
                         if (p.y() != q.y()) return p.y() < q.y();
                         return p.z() < q.z();
                     });
    return lab;
}

osg::ref_ptr<osg::Image> PaletteTexture::createImage(const PaletteHierarchy& hierarchy, unsigned maxLevels)
{
    if (maxLevels == 0) throw std::invalid_argument("maxLevels: 0; it must be at least 1");
    const unsigned n = hierarchy.numColors();
    if (n == 0) throw std::invalid_argument("hierarchy: it has no colours");
    if (hierarchy.merges().size() + 1 != n)
        throw std::invalid_argument("hierarchy: its tree is incomplete (" +
                                    std::to_string(hierarchy.merges().size()) + " merges for " +
                                    std::to_string(n) + " colours)");
    const unsigned K = std::min(std::min(n, maxLevels), kMaxSide);
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(int(K), int(K), 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    image->setInternalTextureFormat(GL_RGBA8);
    for (unsigned k = 1; k <= K; ++k)
    {
        const std::vector<osg::Vec3d> lab = sortedLevel(hierarchy, k);
        unsigned char* row = image->data(0, int(k - 1));
        for (unsigned x = 0; x < K; ++x)
        {
            const osg::Vec3f rgb = WeightedColor::fromLab(osg::Vec3f(lab[std::min(x, k - 1)]));
            row[4 * x + 0] = encode8(rgb[0]);
            row[4 * x + 1] = encode8(rgb[1]);
            row[4 * x + 2] = encode8(rgb[2]);
            row[4 * x + 3] = 255;
        }
    }
    return image;
}

std::string PaletteTexture::contentKey(const std::vector<WeightedColor>& colors,
                                       PaletteHierarchy::Linkage linkage, unsigned levels,
                                       const std::string& extra)
{
    std::string key = "osgLoA PaletteTexture";
    detail::putLE(key, FORMAT_VERSION, 4);
    detail::putLE(key, colors.size(), 8);
    for (const WeightedColor& c : colors)
    {
        for (int ch = 0; ch < 3; ++ch)
        {
            std::uint32_t bits;
            std::memcpy(&bits, c.rgb.ptr() + ch, 4);
            detail::putLE(key, bits, 4);
        }
        std::uint64_t bits;
        std::memcpy(&bits, &c.weight, 8);
        detail::putLE(key, bits, 8);
    }
    detail::putLE(key, std::uint32_t(linkage), 4);
    detail::putLE(key, levels, 4);
    detail::putLE(key, extra.size(), 8);
    key += extra;
    return key;
}

std::string PaletteTexture::cachePath(const std::string& dir, const std::string& key)
{
    const std::string name = FilterCache::hash128(key.data(), key.size()).hex() + ".loapal";
    return dir.empty() ? name : dir + "/" + name;
}

std::string PaletteTexture::encode(const std::string& key, const osg::Image& image)
{
    if (!image.data() || image.s() < 1 || image.s() != image.t() || image.r() != 1 ||
        unsigned(image.s()) > kMaxSide || image.getPixelFormat() != GL_RGBA ||
        image.getDataType() != GL_UNSIGNED_BYTE)
        throw std::invalid_argument(
            "image: a palette texture is a square GL_RGBA / GL_UNSIGNED_BYTE image of "
            "side 1.." +
            std::to_string(kMaxSide));
    const unsigned K = unsigned(image.s());
    std::string out(kMagic, 8);
    detail::putLE(out, FORMAT_VERSION, 4);
    detail::putLE(out, K, 4);
    putHash(out, FilterCache::hash128(key.data(), key.size()));
    for (unsigned t = 0; t < K; ++t)
        out.append(reinterpret_cast<const char*>(image.data(0, int(t))), std::size_t(K) * 4);
    putHash(out, hashOf(out, out.size()));
    return out;
}

osg::ref_ptr<osg::Image> PaletteTexture::decode(const std::string& bytes, const std::string& key,
                                                std::string& why)
{
    if (bytes.size() < 32 + 4 + 16)
    {
        why = "truncated (" + std::to_string(bytes.size()) + " bytes)";
        return nullptr;
    }
    if (std::memcmp(bytes.data(), kMagic, 8) != 0)
    {
        why = "not a palette texture file (bad magic)";
        return nullptr;
    }
    if (detail::getLE(bytes, 8, 4) != FORMAT_VERSION)
    {
        why = "format version " + std::to_string(detail::getLE(bytes, 8, 4));
        return nullptr;
    }
    const std::uint64_t K = detail::getLE(bytes, 12, 4);
    if (K < 1 || K > kMaxSide)
    {
        why = "implausible size " + std::to_string(K);
        return nullptr;
    }
    const std::uint64_t expected = 32 + 4 * K * K + 16;
    if (bytes.size() != expected)
    {
        why = "size " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(expected);
        return nullptr;
    }
    const FilterCacheKey sum = hashOf(bytes, bytes.size() - 16);
    if (detail::getLE(bytes, bytes.size() - 16, 8) != sum.high ||
        detail::getLE(bytes, bytes.size() - 8, 8) != sum.low)
    {
        why = "checksum mismatch";
        return nullptr;
    }
    const FilterCacheKey k = FilterCache::hash128(key.data(), key.size());
    if (detail::getLE(bytes, 16, 8) != k.high || detail::getLE(bytes, 24, 8) != k.low)
    {
        why = "the file is for another key";
        return nullptr;
    }
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(int(K), int(K), 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    image->setInternalTextureFormat(GL_RGBA8);
    std::memcpy(image->data(), bytes.data() + 32, std::size_t(4 * K * K));
    return image;
}

void PaletteTexture::saveCached(const std::string& dir, const std::string& key, const osg::Image& image)
{
    const std::string bytes = encode(key, image);
    AtomicFile::write(cachePath(dir, key),
                      [&](const std::string& temp)
                      {
                          std::ofstream out(temp, std::ios::binary | std::ios::trunc);
                          out.write(bytes.data(), std::streamsize(bytes.size()));
                          out.close();
                          return bool(out);
                      });
}

osg::ref_ptr<osg::Image> PaletteTexture::loadCached(const std::string& dir, const std::string& key)
{
    const std::string path = cachePath(dir, key);
    std::ifstream in(path, std::ios::binary);
    if (!in) return nullptr;
    std::ostringstream buffer;
    buffer << in.rdbuf();
    std::string why;
    osg::ref_ptr<osg::Image> image = in.bad() ? nullptr : decode(buffer.str(), key, why);
    if (!image)
        OSG_WARN << "osgLoA::PaletteTexture: ignoring cache file '" << path
                 << "': " << (why.empty() ? std::string("read error") : why) << std::endl;
    return image;
}

} // namespace osgLoA
