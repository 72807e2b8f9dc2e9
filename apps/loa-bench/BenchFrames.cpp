// loa-bench: the checks of the frames a case times ("a benchmark row whose frame is wrong is a
// bug, not a number") and the frames kept to look at.
#include "BenchCase.h"

#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

void keepFrame(const osg::Image& frame, const std::string& name)
{
    osgDB::makeDirectory("out/bench-frames");
    osgLoA::ImageFile::write("out/bench-frames/" + name + ".png", frame);
}

std::string checkFrame(const osg::Image& frame, const osg::Image& reference, const osg::Vec4& clear)
{
    if (frame.s() != reference.s() || frame.t() != reference.t()) return "size differs from the reference";
    const int w = frame.s(), h = frame.t();
    const int cr = int(std::lround(clear.r() * 255.0f)), cg = int(std::lround(clear.g() * 255.0f)),
              cb = int(std::lround(clear.b() * 255.0f));
    auto isClear = [&](const unsigned char* p)
    { return std::abs(p[0] - cr) <= 1 && std::abs(p[1] - cg) <= 1 && std::abs(p[2] - cb) <= 1; };
    auto isBlack = [](const unsigned char* p) { return p[0] < 4 && p[1] < 4 && p[2] < 4; };
    // Black only counts where the reference is not dark itself: a style may darken a surface that
    // is nearly black already (depth unsharp masking in the window recesses of a back-lit facade,
    // opencity-block's street view), which is not a wrong frame.
    auto isDark = [](const unsigned char* p) { return p[0] < 32 && p[1] < 32 && p[2] < 32; };
    std::vector<unsigned char> covered[2];
    const osg::Image* images[2] = {&frame, &reference};
    long long blackOnContent = 0;
    for (int i = 0; i < 2; ++i)
    {
        covered[i].assign(std::size_t(w) * h, 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                covered[i][std::size_t(y) * w + x] = isClear(images[i]->data(x, y)) ? 0 : 1;
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            blackOnContent += isBlack(frame.data(x, y)) && !isDark(reference.data(x, y)) ? 1 : 0;
    // Pixels covered in one image with nothing covered within one pixel in the other: the
    // silhouettes may move by a pixel (styles' image-space edges lie one pixel outside them; the
    // fixed function's coverage of alpha-blended fringes depends on its drawing order).
    auto unmatched = [&](const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
    {
        long long n = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
            {
                if (!a[std::size_t(y) * w + x]) continue;
                bool near = false;
                for (int dy = -1; dy <= 1 && !near; ++dy)
                    for (int dx = -1; dx <= 1 && !near; ++dx)
                    {
                        const int u = x + dx, v = y + dy;
                        near = u >= 0 && v >= 0 && u < w && v < h && b[std::size_t(v) * w + u];
                    }
                n += near ? 0 : 1;
            }
        return n;
    };
    const long long extra = unmatched(covered[0], covered[1]), lost = unmatched(covered[1], covered[0]);
    const double bar = 0.002 * double(w) * h;
    std::ostringstream why;
    if (double(lost) > bar) why << lost << " px of the reference's content missing";
    if (double(extra) > bar)
        why << (why.str().empty() ? "" : "; ") << extra
            << " px covered where the reference shows the background";
    if (double(blackOnContent) > bar)
        why << (why.str().empty() ? "" : "; ") << blackOnContent
            << " black px where the reference is not dark";
    return why.str();
}

std::string checkBlocks(const osg::Image& frame, const osg::Image& reference)
{
    if (frame.s() != reference.s() || frame.t() != reference.t()) return "size differs from the reference";
    auto isBlack = [](const unsigned char* p) { return p[0] < 4 && p[1] < 4 && p[2] < 4; };
    const int tile = 16;
    int blackTiles = 0;
    for (int ty = 0; ty + tile <= frame.t(); ty += tile)
        for (int tx = 0; tx + tile <= frame.s(); tx += tile)
        {
            bool frameBlack = true, referenceBlack = true;
            for (int y = ty; y < ty + tile && (frameBlack || referenceBlack); ++y)
                for (int x = tx; x < tx + tile; ++x)
                {
                    frameBlack = frameBlack && isBlack(frame.data(x, y));
                    referenceBlack = referenceBlack && isBlack(reference.data(x, y));
                }
            if (frameBlack && !referenceBlack) ++blackTiles;
        }
    const unsigned char* first = frame.data(0, 0);
    bool uniform = true;
    for (int y = 0; y < frame.t() && uniform; ++y)
        for (int x = 0; x < frame.s() && uniform; ++x)
        {
            const unsigned char* p = frame.data(x, y);
            uniform = std::abs(p[0] - first[0]) <= 2 && std::abs(p[1] - first[1]) <= 2 &&
                      std::abs(p[2] - first[2]) <= 2;
        }
    std::ostringstream why;
    if (uniform) why << "the frame is one colour";
    if (blackTiles > 0)
        why << (why.str().empty() ? "" : "; ") << blackTiles << " black " << tile << "x" << tile
            << " block(s) where the reference has content";
    return why.str();
}
