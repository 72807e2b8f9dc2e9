/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/palette/PaletteLookup>
#include <osgLoA/palette/WeightedColor>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace osgLoA
{

namespace
{
/** The Lab colours of the first k texels of row k - 1. */
std::vector<osg::Vec3f> rowLab(const osg::Image& palette, unsigned k)
{
    std::vector<osg::Vec3f> lab(k);
    const unsigned char* row = palette.data(0, int(k - 1));
    for (unsigned i = 0; i < k; ++i)
        lab[i] = WeightedColor::toLab(osg::Vec3f(row[4 * i], row[4 * i + 1], row[4 * i + 2]) / 255.0f);
    return lab;
}

unsigned nearest(const std::vector<osg::Vec3f>& row, const osg::Vec3f& lab)
{
    unsigned best = 0;
    double bestD = 0.0;
    for (unsigned i = 0; i < row.size(); ++i)
    {
        const osg::Vec3d d = osg::Vec3d(row[i]) - osg::Vec3d(lab);
        const double e = d * d;
        if (i == 0 || e < bestD)
        {
            best = i;
            bestD = e;
        }
    }
    return best;
}

void checkLevel(const osg::Image& palette, unsigned k)
{
    const unsigned K = PaletteLookup::checkPalette(palette);
    if (k < 1 || k > K)
        throw std::invalid_argument("k: " + std::to_string(k) + " is not in [1, " + std::to_string(K) + "]");
}
} // namespace

unsigned PaletteLookup::checkPalette(const osg::Image& palette)
{
    if (!palette.data() || palette.s() < 1 || palette.s() != palette.t() || palette.r() != 1 ||
        palette.getPixelFormat() != GL_RGBA || palette.getDataType() != GL_UNSIGNED_BYTE)
        throw std::invalid_argument(
            "palette: a palette texture is a square GL_RGBA / GL_UNSIGNED_BYTE image");
    return unsigned(palette.s());
}

unsigned PaletteLookup::closest(const osg::Image& palette, unsigned k, const osg::Vec3f& rgb)
{
    checkLevel(palette, k);
    return nearest(rowLab(palette, k), WeightedColor::toLab(rgb));
}

osg::Vec3f PaletteLookup::map(const osg::Image& palette, unsigned k, const osg::Vec3f& rgb)
{
    const unsigned i = closest(palette, k, rgb);
    const unsigned char* p = palette.data(int(i), int(k - 1));
    return osg::Vec3f(p[0], p[1], p[2]) / 255.0f;
}

osg::ref_ptr<osg::Image> PaletteLookup::segment(const osg::Image& texture, const osg::Image& palette,
                                                unsigned k)
{
    checkLevel(palette, k);
    const GLenum format = texture.getPixelFormat();
    const bool bgr = format == GL_BGR || format == GL_BGRA;
    if ((format != GL_RGB && format != GL_RGBA && !bgr) || texture.getDataType() != GL_UNSIGNED_BYTE ||
        texture.r() != 1 || !texture.data())
    {
        char b[64];
        std::snprintf(b, sizeof(b), "0x%x/0x%x", unsigned(format), unsigned(texture.getDataType()));
        throw std::invalid_argument(std::string("texture: format ") + b +
                                    " is not RGB8, RGBA8, BGR8 or BGRA8 of one 2D layer");
    }
    const int channels = (format == GL_RGB || format == GL_BGR) ? 3 : 4;
    const std::vector<osg::Vec3f> row = rowLab(palette, k);
    const unsigned char* paletteRow = palette.data(0, int(k - 1));
    osg::ref_ptr<osg::Image> out = new osg::Image;
    out->allocateImage(texture.s(), texture.t(), 1, format, GL_UNSIGNED_BYTE, 1);
    out->setInternalTextureFormat(texture.getInternalTextureFormat());
    std::unordered_map<unsigned, unsigned> seen;
    for (int y = 0; y < texture.t(); ++y)
        for (int x = 0; x < texture.s(); ++x)
        {
            const unsigned char* p = texture.data(x, y);
            unsigned char* q = out->data(x, y);
            const unsigned r = bgr ? p[2] : p[0], g = p[1], b = bgr ? p[0] : p[2];
            const unsigned key = (r << 16) | (g << 8) | b;
            auto it = seen.find(key);
            if (it == seen.end())
                it =
                    seen.emplace(key, nearest(row, WeightedColor::toLab(osg::Vec3f(r, g, b) / 255.0f))).first;
            const unsigned char* c = paletteRow + 4 * it->second;
            q[bgr ? 2 : 0] = c[0];
            q[1] = c[1];
            q[bgr ? 0 : 2] = c[2];
            if (channels == 4) q[3] = p[3];
        }
    return out;
}

} // namespace osgLoA
