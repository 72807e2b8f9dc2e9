// The spectral-residual saliency model (Hou & Zhang 2007; osgLoA::SpectralResidualSaliency), the
// measure of paper 004 Figure 10: against OpenCV's implementation of the same published model
// (cv::saliency::StaticSaliencySpectralResidual, test-only) on a synthetic scene and on real
// photographs (scikit-image's sample images, a Debian package), and the mass share of a map
// inside a region against hand-computed values.
#include <osgLoA/util/SpectralResidualSaliency>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace osgLoA;
using SRS = SpectralResidualSaliency;

namespace
{
/** An RGB image of w x h: noise of amplitude 20 around grey 128, and a bright 12 x 12 square at
 *  (sx, sy). */
osg::ref_ptr<osg::Image> synthetic(int w, int h, int sx, int sy)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, GL_RGB, GL_UNSIGNED_BYTE);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> noise(-20, 20);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            unsigned char* p = img->data(x, y);
            const bool square = x >= sx && x < sx + 12 && y >= sy && y < sy + 12;
            const int v = square ? 250 : 128 + noise(rng);
            p[0] = p[1] = p[2] = static_cast<unsigned char>(v);
        }
    return img;
}

/** OpenCV's map of the same image, averaged to 64 x 64 cells (row 0 = image row 0). */
std::vector<float> openCvMap(const osg::Image& image)
{
    const int w = image.s(), h = image.t(), c = image.getPixelFormat() == GL_RGBA ? 4 : 3;
    cv::Mat bgr(h, w, CV_8UC3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const unsigned char* p = image.data(x, y);
            bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(p[2], p[1], p[0]);
        }
    (void)c;
    cv::Ptr<cv::saliency::StaticSaliencySpectralResidual> s =
        cv::saliency::StaticSaliencySpectralResidual::create();
    cv::Mat map;
    EXPECT_TRUE(s->computeSaliency(bgr, map));
    cv::Mat small;
    cv::resize(map, small, cv::Size(SRS::kSize, SRS::kSize), 0, 0, cv::INTER_AREA);
    std::vector<float> out;
    for (int y = 0; y < SRS::kSize; ++y)
        for (int x = 0; x < SRS::kSize; ++x)
            out.push_back(small.at<float>(y, x));
    return out;
}

double correlation(const std::vector<float>& a, const std::vector<float>& b)
{
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        ma += a[i], mb += b[i];
    ma /= double(a.size()), mb /= double(b.size());
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
}
} // namespace

TEST(SpectralResidualSaliencyOpenCVTest, APopOutSquareHoldsTheMass)
{
    // A 12 x 12 square in a 256 x 256 noise field: 0.22 % of the image.
    osg::ref_ptr<osg::Image> img = synthetic(256, 256, 160, 60);
    const std::vector<float> map = SRS::compute(*img);
    ASSERT_EQ(map.size(), std::size_t(64 * 64));
    std::vector<unsigned char> near(256 * 256, 0);
    for (int y = 44; y < 88; ++y) // the square grown by 16 px (the map is 4 px a cell, blurred)
        for (int x = 144; x < 188; ++x)
            near[std::size_t(y) * 256 + std::size_t(x)] = 1;
    const double share = SRS::massInside(map, near, 256, 256);
    std::cout << "saliency: " << 100 * share
              << " % of the mass within 16 px of the square (2.95 % of the area)\n";
    EXPECT_GT(share, 0.25);
    // The maximum lies on the square's cell region.
    const auto it = std::max_element(map.begin(), map.end());
    const int cell = int(it - map.begin()), cx = cell % 64, cy = cell / 64;
    EXPECT_NEAR(cx, 41, 4);
    EXPECT_NEAR(cy, 16, 4);
    EXPECT_GT(correlation(map, openCvMap(*img)), 0.9);
}

TEST(SpectralResidualSaliencyOpenCVTest, AgreesWithOpenCVOnRealPhotographs)
{
    const std::string dir = std::string(LOA_SOURCE_DIR) + "/data/cache/python3-skimage/";
    if (!osgDB::fileExists(dir + "astronaut.png"))
        GTEST_SKIP() << dir << " is absent: run scripts/fetch-test-data";
    for (const char* name : {"astronaut.png", "chelsea.png", "coffee.png", "rocket.jpg"})
    {
        osg::ref_ptr<osg::Image> img = osgDB::readRefImageFile(dir + name);
        ASSERT_TRUE(img.valid()) << name;
        img->flipVertical(); // rows top first, as OpenCV has them (both maps then match row for row)
        const std::vector<float> ours = SRS::compute(*img), theirs = openCvMap(*img);
        const double r = correlation(ours, theirs);
        std::cout << "saliency " << name << ": correlation with OpenCV's map " << r << "\n";
        // OpenCV resamples to 64 x 64 bilinearly, we average the cells: the maps agree closely.
        EXPECT_GT(r, 0.8) << name;
    }
}

TEST(SpectralResidualSaliencyOpenCVTest, MassInsideByHand)
{
    // A map with all its mass in cell (10, 20): inside when the mask covers that cell's pixels.
    std::vector<float> map(64 * 64, 0.0f);
    map[20 * 64 + 10] = 1.0f;
    std::vector<unsigned char> mask(128 * 128, 0);
    EXPECT_DOUBLE_EQ(SRS::massInside(map, mask, 128, 128), 0.0);
    // The cell spans pixels x 20..21, y 40..41: cover one of its four.
    mask[40 * 128 + 20] = 1;
    EXPECT_DOUBLE_EQ(SRS::massInside(map, mask, 128, 128), 0.25);
    // Two equal cells, one fully inside.
    map[0] = 1.0f;
    mask[0] = mask[1] = mask[128] = mask[129] = 1;
    EXPECT_DOUBLE_EQ(SRS::massInside(map, mask, 128, 128), (1.0 + 0.25) / 2.0);
    EXPECT_THROW(SRS::massInside(map, mask, 64, 64), std::invalid_argument);
    osg::ref_ptr<osg::Image> grey = new osg::Image;
    grey->allocateImage(8, 8, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
    EXPECT_THROW(SRS::compute(*grey), std::invalid_argument);
}
