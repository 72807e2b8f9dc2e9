// loa-sheet: images tiled row by row with white gaps, alpha over white, atomic PNG output, and
// its errors (sizes that differ, a missing image, bad arguments) with their exit status.
#include "support/TestSupport.h"

#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

namespace
{
std::string sheet()
{
    return std::string("'") + LOA_SHEET_EXE + "'";
}

std::string solid(const std::string& path, int w, int h, unsigned char r, unsigned char g, unsigned char b,
                  unsigned char a = 255)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int i = 0; i < w * h; ++i)
    {
        unsigned char* p = image->data() + 4 * i;
        p[0] = r, p[1] = g, p[2] = b, p[3] = a;
    }
    osgLoA::ImageFile::write(path, *image);
    return path;
}

/** The sheet's pixel (x, y from the top left) as 0xRRGGBB. */
unsigned pixel(const osg::Image& image, int x, int yFromTop)
{
    const unsigned char* p = image.data(x, image.t() - 1 - yFromTop);
    return unsigned(p[0]) << 16 | unsigned(p[1]) << 8 | p[2];
}
} // namespace

TEST(LoaSheetTest, TilesRowByRowWithWhiteGaps)
{
    const std::string dir = loatest::freshDirectory("LoaSheetTest");
    const std::string red = solid(dir + "/red.png", 4, 2, 255, 0, 0);
    const std::string blue = solid(dir + "/blue.png", 4, 2, 0, 0, 255);
    const std::string half = solid(dir + "/half.png", 4, 2, 0, 0, 0, 128); // black, half transparent
    std::string out;
    ASSERT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png' '" + red + "' '" + blue + "' '" + half +
                               "' --columns 2 --gap 1",
                           out),
              0)
        << out;
    EXPECT_NE(out.find("9x5, 3 images, 2 a row"), std::string::npos) << out;
    osg::ref_ptr<osg::Image> s = osgLoA::ImageFile::read(dir + "/s.png");
    ASSERT_EQ(s->s(), 9); // 2 x 4 + 1 gap
    ASSERT_EQ(s->t(), 5); // 2 x 2 + 1 gap
    EXPECT_EQ(pixel(*s, 0, 0), 0xff0000u);
    EXPECT_EQ(pixel(*s, 3, 1), 0xff0000u);
    EXPECT_EQ(pixel(*s, 4, 0), 0xffffffu); // gap
    EXPECT_EQ(pixel(*s, 5, 0), 0x0000ffu);
    EXPECT_EQ(pixel(*s, 8, 1), 0x0000ffu);
    EXPECT_EQ(pixel(*s, 0, 2), 0xffffffu); // gap row
    EXPECT_EQ(pixel(*s, 0, 3), 0x7f7f7fu); // black at alpha 128 over white: 255 * 127 / 255
    EXPECT_EQ(pixel(*s, 5, 4), 0xffffffu); // no fourth image: white
}

TEST(LoaSheetTest, ErrorsAreClearWithTheirExitStatus)
{
    const std::string dir = loatest::freshDirectory("LoaSheetTestErrors");
    const std::string a = solid(dir + "/a.png", 4, 2, 1, 2, 3);
    const std::string b = solid(dir + "/b.png", 3, 2, 1, 2, 3);
    std::string out;
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png' '" + a + "' '" + b + "'", out), 2) << out;
    EXPECT_NE(out.find("3x2"), std::string::npos) << out;
    EXPECT_NE(out.find("one size"), std::string::npos) << out;
    EXPECT_FALSE(osgDB::fileExists(dir + "/s.png"));
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png' '" + dir + "/missing.png'", out), 1) << out;
    EXPECT_NE(out.find("missing.png"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png'", out), 2) << out;
    EXPECT_NE(out.find("no IMAGE"), std::string::npos) << out;
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.jpg' '" + a + "'", out), 2) << out;
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png' '" + a + "' --columns 0", out), 2) << out;
    EXPECT_EQ(loatest::run(sheet() + " --out '" + dir + "/s.png' '" + a + "' --frobnicate", out), 2) << out;
}
