// osgLoA::ImageFile: PNG written and read back the same; OpenImageIO is loaded only when the
// first image is read or written (its ~260 shared libraries cost a process 0.4 s at start), from
// the module libosgLoA_imageio beside libosgLoA; GDAL is not loaded at start either.
#include "support/TestSupport.h"

#include <osgLoA/util/ImageFile>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

using namespace osgLoA;

namespace
{
bool mapped(const std::string& library)
{
    std::ifstream maps("/proc/self/maps");
    std::stringstream s;
    s << maps.rdbuf();
    return s.str().find(library) != std::string::npos;
}
} // namespace

// One test: the first image I/O of the process happens here.
TEST(ImageFileTest, OpenImageIOIsLoadedOnTheFirstImageAndImagesRoundTrip)
{
    EXPECT_FALSE(mapped("libOpenImageIO")) << "linked at start";
    EXPECT_FALSE(mapped("libosgLoA_imageio"));
    // GDAL likewise (libosgLoA_gdal, loaded by the first RegionFile::read; RegionFileTest reads).
    EXPECT_FALSE(mapped("libgdal")) << "linked at start";
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(5, 3, 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
        {
            unsigned char* p = image->data(x, y);
            p[0] = static_cast<unsigned char>(50 * x);
            p[1] = static_cast<unsigned char>(100 * y);
            p[2] = static_cast<unsigned char>(7 * x + 11 * y);
        }
    const std::string path = loatest::freshDirectory("ImageFileTest") + "/image.png";
    ImageFile::write(path, *image);
    EXPECT_TRUE(mapped("libosgLoA_imageio"));
    EXPECT_TRUE(mapped("libOpenImageIO"));
    osg::ref_ptr<osg::Image> back = ImageFile::read(path);
    ASSERT_EQ(back->s(), 5);
    ASSERT_EQ(back->t(), 3);
    ASSERT_EQ(back->getPixelFormat(), GLenum(GL_RGB));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(back->data(x, y)[c], image->data(x, y)[c]) << x << ", " << y << ", " << c;
    // A missing file: the module's reason, with the path.
    try
    {
        ImageFile::read(path + ".missing.png");
        FAIL() << "no exception";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("cannot read image '" + path + ".missing.png'"),
                  std::string::npos)
            << e.what();
    }
}
