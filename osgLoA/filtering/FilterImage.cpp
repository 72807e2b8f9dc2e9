/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterImage>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace osgLoA
{

ImageBorder ImageBorder::of(const osg::Texture& texture)
{
    return ImageBorder(fromGL(texture.getWrap(osg::Texture::WRAP_S)),
                       fromGL(texture.getWrap(osg::Texture::WRAP_T)));
}

WrapMode ImageBorder::fromGL(osg::Texture::WrapMode mode)
{
    switch (mode)
    {
    case osg::Texture::REPEAT:
        return WrapMode::Repeat;
    case osg::Texture::MIRROR:
        return WrapMode::Mirror;
    default:
        return WrapMode::Clamp;
    }
}

const char* ImageBorder::name(WrapMode mode)
{
    switch (mode)
    {
    case WrapMode::Repeat:
        return "repeat";
    case WrapMode::Mirror:
        return "mirror";
    default:
        return "clamp";
    }
}

int wrapIndex(int i, int n, WrapMode mode)
{
    if (i >= 0 && i < n) return i;
    switch (mode)
    {
    case WrapMode::Repeat:
    {
        int r = i % n;
        return r < 0 ? r + n : r;
    }
    case WrapMode::Mirror:
    {
        const int period = 2 * n;
        int r = i % period;
        if (r < 0) r += period;
        return r < n ? r : period - 1 - r;
    }
    default:
        return i < 0 ? 0 : n - 1;
    }
}

FilterImage::FilterImage(int width, int height, const osg::Vec4f& fill)
{
    if (width < 0 || height < 0 || width > maxDimension() || height > maxDimension())
        throw std::invalid_argument("FilterImage: size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is outside 0.." +
                                    std::to_string(maxDimension()));
    _width = width;
    _height = height;
    _data.resize(texelCount() * 4);
    for (std::size_t i = 0; i < texelCount(); ++i)
        for (int c = 0; c < 4; ++c)
            _data[i * 4 + c] = fill[c];
}

osg::Vec4f FilterImage::sampleBilinear(float x, float y, const ImageBorder& border) const
{
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const osg::Vec4f a = fetch(x0, y0, border), b = fetch(x0 + 1, y0, border);
    const osg::Vec4f c = fetch(x0, y0 + 1, border), d = fetch(x0 + 1, y0 + 1, border);
    return (a * (1 - ax) + b * ax) * (1 - ay) + (c * (1 - ax) + d * ax) * ay;
}

namespace
{
float componentValue(const osg::Image& image, const unsigned char* p, int component)
{
    switch (image.getDataType())
    {
    case GL_UNSIGNED_BYTE:
        return p[component] / 255.0f;
    case GL_UNSIGNED_SHORT:
        return reinterpret_cast<const unsigned short*>(p)[component] / 65535.0f;
    case GL_FLOAT:
        return reinterpret_cast<const float*>(p)[component];
    default:
        throw std::invalid_argument("FilterImage: unsupported image data type 0x" +
                                    [](unsigned v)
                                    {
                                        char b[16];
                                        std::snprintf(b, sizeof b, "%x", v);
                                        return std::string(b);
                                    }(image.getDataType()));
    }
}
} // namespace

FilterImage FilterImage::fromImage(const osg::Image& image)
{
    if (image.s() <= 0 || image.t() <= 0 || !image.data())
        throw std::invalid_argument("FilterImage: image '" + image.getFileName() + "' is empty (" +
                                    std::to_string(image.s()) + "x" + std::to_string(image.t()) + ")");
    if (image.r() != 1) throw std::invalid_argument("FilterImage: image '" + image.getFileName() + "' is 3D");
    const GLenum format = image.getPixelFormat();
    if (image.isCompressed())
    {
        if (!isS3TC(format))
        {
            char b[64];
            std::snprintf(b, sizeof b, "compressed pixel format 0x%x (only S3TC/DXT is decoded)",
                          unsigned(format));
            throw std::invalid_argument("FilterImage: image '" + image.getFileName() + "': " + b);
        }
        FilterImage out(image.s(), image.t());
        const bool alpha = format != GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
        for (int y = 0; y < image.t(); ++y)
            for (int x = 0; x < image.s(); ++x)
            {
                const osg::Vec4 c = image.getColor(unsigned(x), unsigned(y));
                float* q = out.texel(x, y);
                q[0] = c.r(), q[1] = c.g(), q[2] = c.b(), q[3] = alpha ? c.a() : 1.0f;
            }
        return out;
    }
    int channels = 0;
    int map[4] = {0, 0, 0, -1}; // source component of R, G, B, A (-1: alpha = 1)
    switch (format)
    {
    case GL_LUMINANCE:
    case GL_RED:
    case GL_ALPHA:
        channels = 1;
        break;
    case GL_LUMINANCE_ALPHA:
        channels = 2;
        map[3] = 1;
        break;
    case GL_RG:
        channels = 2;
        map[1] = 1;
        map[2] = -2; // blue = 0
        break;
    case GL_RGB:
        channels = 3;
        map[0] = 0, map[1] = 1, map[2] = 2;
        break;
    case GL_RGBA:
        channels = 4;
        map[0] = 0, map[1] = 1, map[2] = 2, map[3] = 3;
        break;
    case GL_BGR:
        channels = 3;
        map[0] = 2, map[1] = 1, map[2] = 0;
        break;
    case GL_BGRA:
        channels = 4;
        map[0] = 2, map[1] = 1, map[2] = 0, map[3] = 3;
        break;
    default:
    {
        char b[64];
        std::snprintf(b, sizeof b, "unsupported pixel format 0x%x", unsigned(format));
        throw std::invalid_argument("FilterImage: image '" + image.getFileName() + "': " + b);
    }
    }
    (void)channels;
    FilterImage out(image.s(), image.t());
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x)
        {
            const unsigned char* p = image.data(x, y);
            float* q = out.texel(x, y);
            for (int c = 0; c < 4; ++c)
                q[c] = map[c] >= 0 ? componentValue(image, p, map[c]) : (map[c] == -2 ? 0.0f : 1.0f);
            if (format == GL_ALPHA) q[0] = q[1] = q[2] = 1.0f, q[3] = componentValue(image, p, 0);
        }
    return out;
}

bool FilterImage::isS3TC(GLenum pixelFormat)
{
    return pixelFormat == GL_COMPRESSED_RGB_S3TC_DXT1_EXT || pixelFormat == GL_COMPRESSED_RGBA_S3TC_DXT1_EXT ||
           pixelFormat == GL_COMPRESSED_RGBA_S3TC_DXT3_EXT || pixelFormat == GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
}

osg::ref_ptr<const osg::Image> FilterImage::toRGB8(const osg::Image& image)
{
    const GLenum format = image.getPixelFormat();
    if (!image.isCompressed() && image.getDataType() == GL_UNSIGNED_BYTE && image.r() == 1 && image.data() &&
        (format == GL_RGB || format == GL_RGBA))
        return &image;
    const FilterImage f = fromImage(image);
    const bool opaque = format == GL_RGB || format == GL_BGR || format == GL_LUMINANCE ||
                        format == GL_RED || format == GL_RG || format == GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
    osg::ref_ptr<osg::Image> out = new osg::Image;
    out->allocateImage(f.width(), f.height(), 1, opaque ? GL_RGB : GL_RGBA, GL_UNSIGNED_BYTE, 1);
    out->setInternalTextureFormat(opaque ? GL_RGB8 : GL_RGBA8);
    out->setFileName(image.getFileName());
    out->setName(image.getName());
    const int n = opaque ? 3 : 4;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x)
        {
            const float* p = f.texel(x, y);
            unsigned char* q = out->data(x, y);
            for (int c = 0; c < n; ++c)
                q[c] = (unsigned char)std::lround(std::min(1.0f, std::max(0.0f, p[c])) * 255.0f);
        }
    return out;
}

osg::ref_ptr<osg::Image> FilterImage::toImage(GLenum dataType) const
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    if (dataType == GL_FLOAT)
    {
        image->allocateImage(_width, _height, 1, GL_RGBA, GL_FLOAT);
        image->setInternalTextureFormat(GL_RGBA32F_ARB);
        std::copy(_data.begin(), _data.end(), reinterpret_cast<float*>(image->data()));
        return image;
    }
    if (dataType != GL_UNSIGNED_BYTE)
        throw std::invalid_argument("FilterImage::toImage: type must be GL_UNSIGNED_BYTE or GL_FLOAT");
    image->allocateImage(_width, _height, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    image->setInternalTextureFormat(GL_RGBA8);
    unsigned char* d = image->data();
    for (std::size_t i = 0; i < _data.size(); ++i)
        d[i] = (unsigned char)std::lround(std::min(1.0f, std::max(0.0f, _data[i])) * 255.0f);
    return image;
}

void FilterImage::quantize8()
{
    for (float& v : _data)
        v = std::round(std::min(1.0f, std::max(0.0f, v)) * 255.0f) / 255.0f;
}

namespace
{
/** The area weights of the input cells [0, n) that output cell j of m covers (footprint
 *  [j*n/m, (j+1)*n/m)). */
void footprint(int j, int n, int m, int& first, int& last, std::vector<float>& weights)
{
    const double a = double(j) * n / m, b = double(j + 1) * n / m;
    first = int(std::floor(a));
    last = std::min(n - 1, int(std::ceil(b)) - 1);
    weights.clear();
    for (int i = first; i <= last; ++i)
        weights.push_back(float((std::min(b, double(i + 1)) - std::max(a, double(i))) / (b - a)));
}
} // namespace

FilterImage FilterImage::downsample() const
{
    const int w = std::max(1, _width / 2), h = std::max(1, _height / 2);
    FilterImage out(w, h);
    // Separable: rows first into a w x _height temporary, then columns.
    std::vector<float> tmp(std::size_t(w) * std::size_t(_height) * 4, 0.0f);
    std::vector<float> wts;
    for (int x = 0; x < w; ++x)
    {
        int f, l;
        footprint(x, _width, w, f, l, wts);
        for (int y = 0; y < _height; ++y)
        {
            float* q = &tmp[(std::size_t(y) * w + x) * 4];
            for (int i = f; i <= l; ++i)
            {
                const float* p = texel(i, y);
                for (int c = 0; c < 4; ++c)
                    q[c] += wts[i - f] * p[c];
            }
        }
    }
    for (int y = 0; y < h; ++y)
    {
        int f, l;
        footprint(y, _height, h, f, l, wts);
        for (int x = 0; x < w; ++x)
        {
            float* q = out.texel(x, y);
            for (int i = f; i <= l; ++i)
            {
                const float* p = &tmp[(std::size_t(i) * w + x) * 4];
                for (int c = 0; c < 4; ++c)
                    q[c] += wts[i - f] * p[c];
            }
        }
    }
    return out;
}

std::vector<FilterImage> FilterImage::mipPyramid() const
{
    std::vector<FilterImage> levels;
    levels.push_back(*this);
    while (levels.back().width() > 1 || levels.back().height() > 1)
        levels.push_back(levels.back().downsample());
    return levels;
}

namespace
{
void checkSameSize(const FilterImage& a, const FilterImage& b)
{
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("FilterImage: comparing images of different sizes " +
                                    std::to_string(a.width()) + "x" + std::to_string(a.height()) + " and " +
                                    std::to_string(b.width()) + "x" + std::to_string(b.height()));
}
} // namespace

float FilterImage::maxAbsDifference(const FilterImage& a, const FilterImage& b, bool alpha)
{
    checkSameSize(a, b);
    float m = 0;
    const int channels = alpha ? 4 : 3;
    for (std::size_t i = 0; i < a.texelCount(); ++i)
        for (int c = 0; c < channels; ++c)
            m = std::max(m, std::fabs(a._data[i * 4 + c] - b._data[i * 4 + c]));
    return m;
}

double FilterImage::meanAbsDifference(const FilterImage& a, const FilterImage& b)
{
    checkSameSize(a, b);
    double s = 0;
    for (std::size_t i = 0; i < a.texelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            s += std::fabs(double(a._data[i * 4 + c]) - b._data[i * 4 + c]);
    return a.texelCount() ? s / double(a.texelCount() * 3) : 0.0;
}

double FilterImage::rmsDifference(const FilterImage& a, const FilterImage& b)
{
    checkSameSize(a, b);
    double s = 0;
    for (std::size_t i = 0; i < a.texelCount(); ++i)
        for (int c = 0; c < 3; ++c)
        {
            const double d = double(a._data[i * 4 + c]) - b._data[i * 4 + c];
            s += d * d;
        }
    return a.texelCount() ? std::sqrt(s / double(a.texelCount() * 3)) : 0.0;
}

} // namespace osgLoA
