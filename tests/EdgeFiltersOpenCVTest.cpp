// The edge filters' CPU references against OpenCV: SobelFilter's magnitude against cv::Sobel
// (ksize 3) on cv::cvtColor's float luminance, and CannyFilter against cv::Canny (aperture 3,
// L2gradient = true) on 8-bit images. cv::Canny works on unnormalized Sobel magnitudes of
// 0..255 values: our normalized thresholds t map to 4 * 255 * t. Borders: clamp is
// BORDER_REPLICATE, mirror (GL_MIRRORED_REPEAT: ... 1 0 | 0 1 ...) is BORDER_REFLECT.
#include <osgLoA/filtering/CannyFilter>
#include <osgLoA/filtering/SobelFilter>

#include "support/TestSupport.h"

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace osgLoA;

namespace
{
std::vector<std::pair<std::string, FilterImage>> crops()
{
    std::vector<std::pair<std::string, FilterImage>> out;
    for (const auto& [name, x, y] : std::vector<std::tuple<std::string, int, int>>{
             {"astronaut.png", 180, 60}, {"chelsea.png", 120, 40}, {"camera.png", 200, 100}})
    {
        FilterImage img = loatest::photoCrop(name, x, y, 96, 80);
        if (img.empty())
            std::cout << name << " not found: case skipped" << std::endl;
        else
            out.push_back({name, img});
    }
    return out;
}

/** The RGB values as CV_32FC3 (channel order R, G, B). */
cv::Mat toMat32(const FilterImage& img)
{
    cv::Mat m(img.height(), img.width(), CV_32FC3);
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
            for (int c = 0; c < 3; ++c)
                m.at<cv::Vec3f>(y, x)[c] = img.texel(x, y)[c];
    return m;
}

/** The edge map (1 at edges) of our edge image (0 at edges). */
cv::Mat edgeMap(const FilterImage& edges)
{
    cv::Mat m(edges.height(), edges.width(), CV_8U);
    for (int y = 0; y < edges.height(); ++y)
        for (int x = 0; x < edges.width(); ++x)
            m.at<unsigned char>(y, x) = edges.texel(x, y)[0] == 0.0f ? 255 : 0;
    return m;
}
} // namespace

TEST(EdgeFiltersOpenCVTest, SobelMagnitudeMatchesCvSobel)
{
    const auto images = crops();
    if (images.empty()) GTEST_SKIP() << "no photograph";
    for (const auto& [name, img] : images)
        for (const auto& [mode, cvBorder] : {std::make_pair(WrapMode::Clamp, int(cv::BORDER_REPLICATE)),
                                             std::make_pair(WrapMode::Mirror, int(cv::BORDER_REFLECT))})
        {
            cv::Mat grey, gx, gy;
            cv::cvtColor(toMat32(img), grey, cv::COLOR_RGB2GRAY); // 0.299 R + 0.587 G + 0.114 B
            cv::Sobel(grey, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cvBorder);
            cv::Sobel(grey, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cvBorder);
            const FilterImage ours =
                osg::ref_ptr<SobelFilter>(new SobelFilter)->apply(img, ImageBorder(mode, mode));
            float worst = 0;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x)
                {
                    const float a = gx.at<float>(y, x), b = gy.at<float>(y, x);
                    worst = std::max(worst, std::fabs(std::sqrt(a * a + b * b) / 4.0f - ours.get(x, y)[0]));
                }
            std::cout << "sobel vs cv::Sobel " << name << " " << ImageBorder::name(mode) << ": max |M diff| "
                      << worst << std::endl;
            // Same kernels and borders, float sums in another order: rounding only.
            EXPECT_LE(worst, 1e-5f) << name;
        }
}

TEST(EdgeFiltersOpenCVTest, CannyWithoutSmoothingEqualsCvCannyOnGreyImages)
{
    // A grey 8-bit image (R = G = B = k / 255): our L is k again, so both run the same integer
    // Sobel, the same direction quantization (tan 22.5 deg as 13573 / 2^15), the same tie rule
    // and 8-connected hysteresis; cv::Canny treats magnitudes outside the image as 0, as we do
    // for clamp. Thresholds 4 * 255 * t with squares that are not integers (no threshold ties).
    // Expected: identical edge maps.
    const auto images = crops();
    if (images.empty()) GTEST_SKIP() << "no photograph";
    for (const auto& [name, colour] : images)
    {
        cv::Mat rgb8, grey8;
        toMat32(colour).convertTo(rgb8, CV_8UC3, 255.0);
        cv::cvtColor(rgb8, grey8, cv::COLOR_RGB2GRAY);
        FilterImage img(colour.width(), colour.height());
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x)
            {
                const float g = float(grey8.at<unsigned char>(y, x)) / 255.0f;
                img.set(x, y, osg::Vec4f(g, g, g, 1.0f));
            }
        osg::ref_ptr<CannyFilter> f = new CannyFilter;
        f->setSigma(0.0f);
        for (const auto& [low, high] : {std::make_pair(0.1f, 0.2f), std::make_pair(0.05f, 0.3f)})
        {
            f->setLow(low);
            f->setHigh(high);
            cv::Mat theirs;
            cv::Canny(grey8, theirs, 1020.0 * double(low), 1020.0 * double(high), 3, true);
            const cv::Mat ours = edgeMap(f->apply(img, ImageBorder()));
            const int differ = cv::countNonZero(ours != theirs);
            std::cout << "canny vs cv::Canny " << name << " sigma 0, " << low << "/" << high << ": "
                      << cv::countNonZero(theirs) << " edge texels, " << differ << " differ" << std::endl;
            EXPECT_EQ(differ, 0) << name;
            EXPECT_GT(cv::countNonZero(theirs), 100) << name;
        }
    }
}

TEST(EdgeFiltersOpenCVTest, CannyWithSmoothingAgreesWithGaussianBlurThenCvCanny)
{
    // Colour input, sigma 1: OpenCV's pipeline is cvtColor (float), GaussianBlur (ksize
    // 2 ceil(3 sigma) + 1 = 7, BORDER_REPLICATE), rounding to 8 bits (round half to even; ours
    // rounds half up) and cv::Canny. Differences come from float rounding in the blur where
    // 255 Ys lies within ~1e-5 of k + 0.5 (an 8-bit value off by one moves a magnitude by a few
    // units, which matters only where a neighbour comparison or threshold was that close:
    // NMS ties and thresholds). Bar: at most 0.5 % of the texels differ.
    const auto images = crops();
    if (images.empty()) GTEST_SKIP() << "no photograph";
    std::size_t total = 0, differ = 0;
    for (const auto& [name, img] : images)
    {
        cv::Mat grey, blurred, grey8, theirs;
        cv::cvtColor(toMat32(img), grey, cv::COLOR_RGB2GRAY);
        cv::GaussianBlur(grey, blurred, cv::Size(7, 7), 1.0, 1.0, cv::BORDER_REPLICATE);
        blurred.convertTo(grey8, CV_8U, 255.0);
        osg::ref_ptr<CannyFilter> f = new CannyFilter; // sigma 1
        f->setLow(0.04f); // the smoothed crops have weaker gradients: lower thresholds than the defaults
        f->setHigh(0.08f);
        cv::Canny(grey8, theirs, 1020.0 * double(f->getLow()), 1020.0 * double(f->getHigh()), 3, true);
        const cv::Mat ours = edgeMap(f->apply(img, ImageBorder()));
        const int d = cv::countNonZero(ours != theirs);
        std::cout << "canny vs GaussianBlur + cv::Canny " << name << " sigma 1: " << cv::countNonZero(theirs)
                  << " edge texels, " << d << " of " << ours.total() << " differ" << std::endl;
        EXPECT_GT(cv::countNonZero(theirs), 100) << name;
        total += ours.total();
        differ += std::size_t(d);
    }
    const double fraction = double(differ) / double(total);
    std::cout << "canny vs OpenCV, sigma 1: " << fraction * 100.0 << " % of texels differ" << std::endl;
    EXPECT_LE(fraction, 0.005);
}
