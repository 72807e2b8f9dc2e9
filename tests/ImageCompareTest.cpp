// The golden-image comparison helper, against hand-computed differences.
#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/ImageFile>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

using namespace osgLoA;

namespace
{
osg::ref_ptr<osg::Image> image(int w, int h, GLenum format, std::initializer_list<int> values)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, format, GL_UNSIGNED_BYTE);
    unsigned char* p = img->data();
    for (int v : values)
        *p++ = static_cast<unsigned char>(v);
    return img;
}
} // namespace

TEST(ImageCompareTest, HandComputedDifferences)
{
    // 2x1 RGB. Pixel 0 differs by (1, 2, 3), pixel 1 by (0, 0, 20).
    auto a = image(2, 1, GL_RGB, {10, 10, 10, 50, 50, 50});
    auto b = image(2, 1, GL_RGB, {11, 12, 13, 50, 50, 70});
    const auto c = ImageComparison::compare(*a, *b, 5);
    EXPECT_TRUE(c.sizesMatch);
    EXPECT_EQ(c.maxDifference, 20);
    EXPECT_DOUBLE_EQ(c.meanDifference, (1 + 2 + 3 + 20) / 6.0);
    EXPECT_EQ(c.failingPixels, 1u); // only pixel 1 exceeds 5
    EXPECT_DOUBLE_EQ(c.failingFraction, 0.5);
    EXPECT_EQ(c.difference->data(1, 0)[2], 80); // 20 x 4
}

TEST(ImageCompareTest, AlphaIsIgnoredAndFormatsMix)
{
    auto a = image(1, 1, GL_RGBA, {1, 2, 3, 0});
    auto b = image(1, 1, GL_RGB, {1, 2, 3});
    const auto c = ImageComparison::compare(*a, *b, 0);
    EXPECT_EQ(c.maxDifference, 0);
    EXPECT_EQ(c.failingPixels, 0u);
}

TEST(ImageCompareTest, DifferentSizesFailCompletely)
{
    auto a = image(2, 1, GL_RGB, {0, 0, 0, 0, 0, 0});
    auto b = image(1, 2, GL_RGB, {0, 0, 0, 0, 0, 0});
    const auto c = ImageComparison::compare(*a, *b, 255);
    EXPECT_FALSE(c.sizesMatch);
    EXPECT_DOUBLE_EQ(c.failingFraction, 1.0);
}

TEST(ImageCompareTest, PngRoundTripKeepsPixelsAndOrientation)
{
    const std::string dir = loatest::freshDirectory("ImageFile");
    auto a = image(2, 2, GL_RGB, {255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9}); // row 0 is the bottom
    ImageFile::write(dir + "/x.png", *a);
    auto b = ImageFile::read(dir + "/x.png");
    ASSERT_EQ(b->s(), 2);
    ASSERT_EQ(b->t(), 2);
    EXPECT_EQ(ImageComparison::compare(*a, *b, 0).maxDifference, 0);
    EXPECT_THROW(ImageFile::read(dir + "/missing.png"), std::runtime_error);
}
