#include <osgLoA/util/ImageCompare>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{
namespace
{
int channelsOf(const osg::Image& img)
{
    if (img.getDataType() != GL_UNSIGNED_BYTE)
        throw std::invalid_argument("image comparison needs 8-bit images");
    switch (img.getPixelFormat())
    {
    case GL_RGB:
        return 3;
    case GL_RGBA:
        return 4;
    default:
        throw std::invalid_argument("image comparison needs RGB or RGBA images");
    }
}
} // namespace

ImageComparison ImageComparison::compare(const osg::Image& actual, const osg::Image& expected,
                                         int failThreshold)
{
    ImageComparison r;
    r.sizesMatch = actual.s() == expected.s() && actual.t() == expected.t();
    if (!r.sizesMatch)
    {
        r.maxDifference = 255;
        r.meanDifference = 255.0;
        r.failingFraction = 1.0;
        return r;
    }
    const int ca = channelsOf(actual), ce = channelsOf(expected);
    const int w = actual.s(), h = actual.t();
    r.difference = new osg::Image;
    r.difference->allocateImage(w, h, 1, GL_RGB, GL_UNSIGNED_BYTE);
    unsigned long long sum = 0;
    for (int y = 0; y < h; ++y)
    {
        const unsigned char* pa = actual.data(0, y);
        const unsigned char* pe = expected.data(0, y);
        unsigned char* pd = r.difference->data(0, y);
        for (int x = 0; x < w; ++x)
        {
            int pixelMax = 0;
            for (int c = 0; c < 3; ++c)
            {
                const int d = std::abs(int(pa[x * ca + c]) - int(pe[x * ce + c]));
                sum += static_cast<unsigned>(d);
                pixelMax = std::max(pixelMax, d);
                pd[x * 3 + c] = static_cast<unsigned char>(std::min(255, d * 4));
            }
            r.maxDifference = std::max(r.maxDifference, pixelMax);
            if (pixelMax > failThreshold) ++r.failingPixels;
        }
    }
    const double pixels = static_cast<double>(w) * h;
    r.meanDifference = pixels > 0 ? static_cast<double>(sum) / (pixels * 3.0) : 0.0;
    r.failingFraction = pixels > 0 ? static_cast<double>(r.failingPixels) / pixels : 0.0;
    return r;
}

std::string ImageComparison::summary() const
{
    if (!sizesMatch) return "image sizes differ";
    std::ostringstream o;
    o << "max difference " << maxDifference << "/255, mean " << meanDifference << "/255, failing pixels "
      << failingPixels << " (" << failingFraction * 100.0 << "%)";
    return o.str();
}

} // namespace osgLoA
