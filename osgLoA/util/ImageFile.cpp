#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>

#ifdef OSGLOA_WITH_OPENIMAGEIO
#include "LazyModule.h"
#else
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>
#endif

#include <stdexcept>

namespace osgLoA
{

namespace
{
/** 8-bit channels of an image of this pixel format: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; 0 others. */
int channelsOf(GLenum format)
{
    switch (format)
    {
    case GL_LUMINANCE:
    case GL_RED:
        return 1;
    case GL_LUMINANCE_ALPHA:
        return 2;
    case GL_RGB:
        return 3;
    case GL_RGBA:
        return 4;
    default:
        return 0;
    }
}
} // namespace

#ifdef OSGLOA_WITH_OPENIMAGEIO
namespace
{
/** libosgLoA_imageio (osgLoA/imageio/ImageFileModule.cpp), loaded beside this library on the first
 *  image read or written: OpenImageIO's 260 libraries cost every process 0.4 s at start. */
struct ImageIOModule
{
    bool (*read)(const char*, osg::Image*, std::string*) = nullptr;
    bool (*write)(const char*, const osg::Image*, int, std::string*) = nullptr;
};

const ImageIOModule& imageIO()
{
    // Resolved once (a failed load throws here and is tried again on the next image).
    static const ImageIOModule m = []
    {
        ImageIOModule r;
        r.read = reinterpret_cast<bool (*)(const char*, osg::Image*, std::string*)>(
            lazyModuleSymbol("osgLoA_imageio", "osgLoA_imageio_read"));
        r.write = reinterpret_cast<bool (*)(const char*, const osg::Image*, int, std::string*)>(
            lazyModuleSymbol("osgLoA_imageio", "osgLoA_imageio_write"));
        return r;
    }();
    return m;
}
} // namespace

osg::ref_ptr<osg::Image> ImageFile::read(const std::string& path)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    std::string error;
    if (!imageIO().read(path.c_str(), image.get(), &error))
        throw std::runtime_error("cannot read image '" + path + "': " + error);
    return image;
}

#else
// Built without OpenImageIO (OSGLOA_WITH_OPENIMAGEIO=OFF, scripts/device-bench): the formats of
// OSG's own image plugins (osgdb_png, osgdb_jpeg, ...), converted to 8-bit RGB(A) as the
// OpenImageIO module converts them (grey replicated into RGB, alpha kept).
osg::ref_ptr<osg::Image> ImageFile::read(const std::string& path)
{
    osg::ref_ptr<osg::Image> in = osgDB::readRefImageFile(path);
    if (!in || !in->data())
        throw std::runtime_error("cannot read image '" + path +
                                 "' (osgLoA built without OpenImageIO: OSG's image plugins only)");
    if (in->s() < 1 || in->t() < 1) throw std::runtime_error("image '" + path + "' is empty");
    if (in->getDataType() != GL_UNSIGNED_BYTE)
        throw std::runtime_error("cannot read image '" + path + "': not 8 bits per channel");
    const int channels = channelsOf(in->getPixelFormat());
    if (!channels) throw std::runtime_error("cannot read image '" + path + "': unsupported pixel format");
    const int out = channels == 4 || channels == 2 ? 4 : 3;
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(in->s(), in->t(), 1, out == 4 ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE);
    for (int y = 0; y < in->t(); ++y)
        for (int x = 0; x < in->s(); ++x)
        {
            const unsigned char* p = in->data(x, y);
            unsigned char* q = image->data(x, y);
            const bool grey = channels <= 2;
            q[0] = p[0];
            q[1] = grey ? p[0] : p[1];
            q[2] = grey ? p[0] : p[2];
            if (out == 4) q[3] = channels == 2 ? p[1] : p[3];
        }
    return image;
}
#endif

void ImageFile::write(const std::string& path, const osg::Image& image)
{
    if (image.getDataType() != GL_UNSIGNED_BYTE || !image.data())
        throw std::runtime_error("cannot write '" + path + "': only 8-bit images are written");
    const int channels = channelsOf(image.getPixelFormat());
    if (channels == 0 || channels == 2) // grey + alpha is read (as RGBA), not written
        throw std::runtime_error("cannot write '" + path + "': unsupported pixel format");
#ifdef OSGLOA_WITH_OPENIMAGEIO
    const ImageIOModule& io = imageIO();
    AtomicFile::write(path,
                      [&](const std::string& temp)
                      {
                          std::string error;
                          if (!io.write(temp.c_str(), &image, channels, &error))
                              throw std::runtime_error("cannot write '" + path + "': " + error);
                          return true;
                      });
#else
    AtomicFile::write(path, [&](const std::string& temp) { return osgDB::writeImageFile(image, temp); });
    (void)channels;
#endif
}

} // namespace osgLoA
