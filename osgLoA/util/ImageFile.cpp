#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>

#ifdef OSGLOA_WITH_OPENIMAGEIO
#include <OpenImageIO/imageio.h>
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
osg::ref_ptr<osg::Image> ImageFile::read(const std::string& path)
{
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1)
        throw std::runtime_error("image '" + path + "' is empty");
    const int channels = spec.nchannels >= 4 ? 4 : 3;
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(spec.width, spec.height, 1, channels == 4 ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE);
    const OIIO::stride_t row = static_cast<OIIO::stride_t>(image->getRowStepInBytes());
    // Read with a negative row stride into the last row: OSG's origin is bottom-left.
    unsigned char* last = image->data(0, spec.height - 1);
    const int chend = std::min(spec.nchannels, channels);
    if (!in->read_image(0, 0, 0, chend, OIIO::TypeDesc::UINT8, last, channels, -row))
        throw std::runtime_error("cannot read image '" + path + "': " + in->geterror());
    if (chend < channels) // grey or grey+alpha: replicate into RGB
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x)
            {
                unsigned char* p = image->data(x, y);
                if (chend == 1)
                    p[1] = p[2] = p[0];
                else if (chend == 2)
                    p[2] = p[1] = p[0];
            }
    in->close();
    return image;
}

#else
// Built without OpenImageIO (OSGLOA_WITH_OPENIMAGEIO=OFF, scripts/device-bench): the formats of
// OSG's own image plugins (osgdb_png, osgdb_jpeg, ...), converted to 8-bit RGB(A) as above.
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
    AtomicFile::write(path,
                      [&](const std::string& temp)
                      {
                          auto out = OIIO::ImageOutput::create(temp);
                          if (!out)
                              throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());
                          OIIO::ImageSpec spec(image.s(), image.t(), channels, OIIO::TypeDesc::UINT8);
                          if (!out->open(temp, spec))
                              throw std::runtime_error("cannot write '" + path + "': " + out->geterror());
                          const OIIO::stride_t row = static_cast<OIIO::stride_t>(image.getRowStepInBytes());
                          const unsigned char* last = image.data(0, image.t() - 1);
                          const bool ok =
                              out->write_image(OIIO::TypeDesc::UINT8, last, channels, -row) && out->close();
                          return ok;
                      });
#else
    AtomicFile::write(path, [&](const std::string& temp) { return osgDB::writeImageFile(image, temp); });
    (void)channels;
#endif
}

} // namespace osgLoA
