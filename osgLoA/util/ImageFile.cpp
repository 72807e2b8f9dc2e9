#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>

#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace osgLoA
{

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

void ImageFile::write(const std::string& path, const osg::Image& image)
{
    if (image.getDataType() != GL_UNSIGNED_BYTE || !image.data())
        throw std::runtime_error("cannot write '" + path + "': only 8-bit images are written");
    int channels = 0;
    switch (image.getPixelFormat())
    {
    case GL_LUMINANCE:
    case GL_RED:
        channels = 1;
        break;
    case GL_RGB:
        channels = 3;
        break;
    case GL_RGBA:
        channels = 4;
        break;
    default:
        throw std::runtime_error("cannot write '" + path + "': unsupported pixel format");
    }
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
}

} // namespace osgLoA
