/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterImage>
#include <osgLoA/palette/PaletteLookup>
#include <osgLoA/palette/TextureHistogram>
#include <osgLoA/palette/TexturePalette>
#include <osgLoA/palette/WeightedColor>

#include "../compositing/RenderTarget.h"

#include <osg/Notify>

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace osgLoA
{

namespace
{
void putLE(std::string& s, std::uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; ++i)
        s.push_back(char((v >> (8 * i)) & 0xff));
}

std::vector<WeightedColor> tableOf(const osg::Image& texture, const std::vector<double>& weights)
{
    const std::vector<TextureHistogram::ColorEntry> table = TextureHistogram::colorTable(texture, weights);
    if (table.empty())
        throw std::invalid_argument("weights: every texel has weight 0; there is no colour to cluster");
    std::vector<WeightedColor> colors;
    colors.reserve(table.size());
    for (const auto& e : table)
        colors.push_back(WeightedColor(osg::Vec3f(e.r, e.g, e.b) / 255.0f, e.weight));
    return colors;
}

unsigned levelsFor(std::size_t n, unsigned maxLevels)
{
    if (maxLevels == 0) throw std::invalid_argument("maxLevels: 0; it must be at least 1");
    return unsigned(std::min<std::size_t>(std::min<std::size_t>(n, maxLevels), 65535));
}

std::string extraBytes(const osg::Image& source, const std::vector<double>& weights)
{
    // The texels as 8-bit RGB(A), what the colour table reads (compressed data has no rows).
    const osg::ref_ptr<const osg::Image> converted = FilterImage::toRGB8(source);
    const osg::Image& texture = *converted;
    std::string extra;
    putLE(extra, std::uint32_t(texture.s()), 4);
    putLE(extra, std::uint32_t(texture.t()), 4);
    putLE(extra, std::uint32_t(texture.getPixelFormat()), 4);
    const std::size_t rowBytes =
        std::size_t(texture.s()) * osg::Image::computeNumComponents(texture.getPixelFormat());
    for (int y = 0; y < texture.t(); ++y)
        extra.append(reinterpret_cast<const char*>(texture.data(0, y)), rowBytes);
    putLE(extra, weights.size(), 8);
    for (double w : weights)
    {
        std::uint64_t bits;
        std::memcpy(&bits, &w, 8);
        putLE(extra, bits, 8);
    }
    return extra;
}
} // namespace

TexturePalette::TexturePalette(const TexturePalette& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _levels(other._levels), _fromCache(other._fromCache)
{
    if (other._hierarchy.valid())
        _hierarchy = (copyop.getCopyFlags() & osg::CopyOp::DEEP_COPY_OBJECTS)
                         ? new PaletteHierarchy(*other._hierarchy, copyop)
                         : other._hierarchy.get();
    if (other._stored.valid()) _stored = copyop(other._stored.get());
}

osg::ref_ptr<TexturePalette> TexturePalette::build(const osg::Image& texture,
                                                   const std::vector<double>& weights,
                                                   PaletteHierarchy::Linkage linkage, unsigned maxLevels)
{
    if (maxLevels == 0) throw std::invalid_argument("maxLevels: 0; it must be at least 1");
    const std::vector<WeightedColor> colors = tableOf(texture, weights);
    osg::ref_ptr<TexturePalette> p = new TexturePalette;
    p->setName(texture.getFileName());
    p->setHierarchy(PaletteHierarchy::build(colors, linkage).get());
    p->setLevels(levelsFor(colors.size(), maxLevels));
    return p;
}

std::string TexturePalette::cacheKey(const osg::Image& texture, const std::vector<double>& weights,
                                     PaletteHierarchy::Linkage linkage, unsigned maxLevels)
{
    if (maxLevels == 0) throw std::invalid_argument("maxLevels: 0; it must be at least 1");
    const std::vector<WeightedColor> colors = tableOf(texture, weights);
    return PaletteTexture::contentKey(colors, linkage, levelsFor(colors.size(), maxLevels),
                                      extraBytes(texture, weights));
}

osg::ref_ptr<TexturePalette> TexturePalette::buildCached(const osg::Image& texture,
                                                         const std::vector<double>& weights,
                                                         PaletteHierarchy::Linkage linkage,
                                                         unsigned maxLevels, const std::string& cacheDir)
{
    if (cacheDir.empty()) return build(texture, weights, linkage, maxLevels);
    const std::string key = cacheKey(texture, weights, linkage, maxLevels);
    if (osg::ref_ptr<osg::Image> cached = PaletteTexture::loadCached(cacheDir, key))
    {
        osg::ref_ptr<TexturePalette> p = new TexturePalette;
        p->setName(texture.getFileName());
        p->setStoredImage(cached.get());
        p->_fromCache = true;
        return p;
    }
    osg::ref_ptr<TexturePalette> p = build(texture, weights, linkage, maxLevels);
    try
    {
        PaletteTexture::saveCached(cacheDir, key, *p->getPaletteImage());
    }
    catch (const std::exception& e)
    {
        OSG_WARN << "osgLoA::TexturePalette: could not cache the palette: " << e.what() << std::endl;
    }
    return p;
}

void TexturePalette::setHierarchy(PaletteHierarchy* h)
{
    _hierarchy = h;
    _image = nullptr;
    _lookup = nullptr;
}

void TexturePalette::setLevels(unsigned k)
{
    if (k > 65535) throw std::invalid_argument("levels: " + std::to_string(k) + " is above 65535");
    _levels = k;
    _image = nullptr;
    _lookup = nullptr;
}

void TexturePalette::setStoredImage(osg::Image* image)
{
    if (image) _levels = PaletteLookup::checkPalette(*image);
    _stored = image;
    _image = nullptr;
    _lookup = nullptr;
}

const osg::Image* TexturePalette::getPaletteImage() const
{
    if (_stored.valid()) return _stored.get();
    if (!_image.valid())
    {
        if (!_hierarchy.valid() || _levels == 0)
            throw std::logic_error("TexturePalette '" + getName() +
                                   "': no palette image and no hierarchy with levels");
        _image = PaletteTexture::createImage(*_hierarchy, _levels);
    }
    return _image.get();
}

osg::Texture2D* TexturePalette::getLookupTexture() const
{
    if (_lookup.valid()) return _lookup.get();
    const osg::Image& palette = *getPaletteImage();
    const int K = palette.s();
    osg::ref_ptr<osg::Image> lab = new osg::Image;
    lab->allocateImage(K, K, 1, GL_RGBA, GL_FLOAT, 1);
    lab->setInternalTextureFormat(GL_RGBA32F_ARB);
    for (int y = 0; y < K; ++y)
        for (int x = 0; x < K; ++x)
        {
            const unsigned char* p = palette.data(x, y);
            const osg::Vec3f c = WeightedColor::toLab(osg::Vec3f(p[0], p[1], p[2]) / 255.0f);
            float* q = reinterpret_cast<float*>(lab->data(x, y));
            q[0] = c[0];
            q[1] = c[1];
            q[2] = c[2];
            q[3] = 1.0f;
        }
    // Nearest, clamp-to-edge, no mipmaps: texelFetch reads the exact Lab values.
    osg::ref_ptr<osg::Texture2D> t = detail::createTargetTexture(GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT);
    t->setName("loa_paletteLookup " + getName());
    t->setImage(lab.get());
    _lookup = t;
    return _lookup.get();
}

} // namespace osgLoA
