// osgLoA::ImageFile as built with OSGLOA_WITH_OPENIMAGEIO=OFF (scripts/device-bench): PNGs through
// OSG's osgdb_png plugin. This executable compiles ImageFile.cpp and AtomicFile.cpp itself, without
// libosgLoA (which holds the OpenImageIO version of the same functions), and checks the result
// against OpenImageIO, linked here directly as the independent reader and writer.
#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using osgLoA::ImageFile;

namespace
{
std::string outputDir()
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/ImageFileWithoutOpenImageIO";
    osgDB::makeDirectory(dir);
    return dir;
}

/** A w x h image whose every pixel is distinct: (x, y, x + 2y) in osg's bottom-left rows. */
osg::ref_ptr<osg::Image> pattern(int w, int h, GLenum format)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(w, h, 1, format, GL_UNSIGNED_BYTE);
    const unsigned n = osg::Image::computeNumComponents(format);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (unsigned c = 0; c < n; ++c)
                image->data(x, y)[c] = static_cast<unsigned char>(c == 0   ? x
                                                                  : c == 1 ? y
                                                                  : c == 2 ? x + 2 * y
                                                                           : 200);
    return image;
}
} // namespace

TEST(ImageFileWithoutOpenImageIOTest, RgbAndRgbaRoundTripAndOpenImageIOAgreesOnTheRows)
{
    for (GLenum format : {GLenum(GL_RGB), GLenum(GL_RGBA)})
    {
        const int w = 37, h = 21; // odd sizes: rows are not 4-byte multiples
        osg::ref_ptr<osg::Image> original = pattern(w, h, format);
        const std::string path = outputDir() + (format == GL_RGB ? "/rgb.png" : "/rgba.png");
        ImageFile::write(path, *original);
        osg::ref_ptr<osg::Image> back = ImageFile::read(path);
        ASSERT_EQ(back->s(), w);
        ASSERT_EQ(back->t(), h);
        ASSERT_EQ(back->getPixelFormat(), format);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_EQ(0, std::memcmp(back->data(x, y), original->data(x, y),
                                         osg::Image::computeNumComponents(format)))
                    << x << "," << y;
        // OpenImageIO reads the file top row first: its first row is osg's last (y = h - 1).
        // (oiio:UnassociatedAlpha: the values as stored, not multiplied by alpha.)
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        auto in = OIIO::ImageInput::open(path, &config);
        ASSERT_TRUE(in);
        std::vector<unsigned char> top(std::size_t(w) * in->spec().nchannels);
        ASSERT_TRUE(in->read_scanline(0, 0, OIIO::TypeDesc::UINT8, top.data()));
        EXPECT_EQ(top[0], 0);     // x = 0
        EXPECT_EQ(top[1], h - 1); // y = h - 1
    }
}

TEST(ImageFileWithoutOpenImageIOTest, GreyIsReadAsRgbAndAFileOpenImageIOWroteReadsTheSame)
{
    // A grey and a grey+alpha PNG written by OpenImageIO, top row first.
    const int w = 5, h = 3;
    for (int channels : {1, 2})
    {
        const std::string path = outputDir() + "/grey" + std::to_string(channels) + ".png";
        std::vector<unsigned char> pixels(std::size_t(w) * h * channels);
        for (int row = 0; row < h; ++row)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < channels; ++c)
                    pixels[(std::size_t(row) * w + x) * channels + c] =
                        static_cast<unsigned char>(c == 0 ? 10 * row + x : 99);
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
        if (channels == 2) spec.alpha_channel = 1;
        spec.attribute("oiio:UnassociatedAlpha", 1); // write the values as given, not divided by alpha
        ASSERT_TRUE(out->open(path, spec));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
        ASSERT_TRUE(out->close());

        osg::ref_ptr<osg::Image> image = ImageFile::read(path);
        ASSERT_EQ(image->getPixelFormat(), GLenum(channels == 2 ? GL_RGBA : GL_RGB)) << channels;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
            {
                const unsigned char grey = static_cast<unsigned char>(10 * (h - 1 - y) + x); // file row h-1-y
                const unsigned char* p = image->data(x, y);
                EXPECT_EQ(p[0], grey) << x << "," << y << " of " << channels << " channels";
                EXPECT_EQ(p[1], grey);
                EXPECT_EQ(p[2], grey);
                if (channels == 2)
                {
                    EXPECT_EQ(p[3], 99);
                }
            }
    }
}

TEST(ImageFileWithoutOpenImageIOTest, ErrorsNameTheFileAndTheBuild)
{
    const std::string missing = outputDir() + "/missing.png";
    std::remove(missing.c_str());
    try
    {
        ImageFile::read(missing);
        FAIL() << "no error";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("without OpenImageIO"), std::string::npos) << e.what();
    }
    osg::ref_ptr<osg::Image> floats = new osg::Image;
    floats->allocateImage(2, 2, 1, GL_RGB, GL_FLOAT);
    EXPECT_THROW(ImageFile::write(outputDir() + "/float.png", *floats), std::runtime_error);
}
