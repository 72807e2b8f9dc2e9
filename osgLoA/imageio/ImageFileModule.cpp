/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
// libosgLoA_imageio: osgLoA::ImageFile's OpenImageIO reader and writer, in a module of their own
// that libosgLoA loads on the first image it reads or writes (ImageFile.cpp). OpenImageIO pulls in
// about 260 shared libraries, whose loading and initialization cost 0.4 s per process: linked
// into libosgLoA, every tool and test paid it at start, images or not.
#include <osg/Image>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <string>

extern "C" __attribute__((visibility("default"))) bool
osgLoA_imageio_read(const char* path, osg::Image* image, std::string* error)
{
    auto in = OIIO::ImageInput::open(path);
    if (!in)
    {
        *error = OIIO::geterror();
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1)
    {
        *error = "the image is empty";
        return false;
    }
    const int channels = spec.nchannels >= 4 ? 4 : 3;
    image->allocateImage(spec.width, spec.height, 1, channels == 4 ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE);
    const OIIO::stride_t row = static_cast<OIIO::stride_t>(image->getRowStepInBytes());
    // Read with a negative row stride into the last row: OSG's origin is bottom-left.
    unsigned char* last = image->data(0, spec.height - 1);
    const int chend = std::min(spec.nchannels, channels);
    if (!in->read_image(0, 0, 0, chend, OIIO::TypeDesc::UINT8, last, channels, -row))
    {
        *error = in->geterror();
        return false;
    }
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
    return true;
}

extern "C" __attribute__((visibility("default"))) bool
osgLoA_imageio_write(const char* path, const osg::Image* image, int channels, std::string* error)
{
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
    {
        *error = OIIO::geterror();
        return false;
    }
    OIIO::ImageSpec spec(image->s(), image->t(), channels, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec))
    {
        *error = out->geterror();
        return false;
    }
    const OIIO::stride_t row = static_cast<OIIO::stride_t>(image->getRowStepInBytes());
    const unsigned char* last = image->data(0, image->t() - 1);
    if (!out->write_image(OIIO::TypeDesc::UINT8, last, channels, -row) || !out->close())
    {
        *error = out->geterror();
        return false;
    }
    return true;
}
