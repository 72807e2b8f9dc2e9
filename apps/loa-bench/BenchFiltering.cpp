// loa-bench case "filtering": the analogue of paper 000's Table 1. The demo city along a fixed
// fly-through (a crane shot from the street camera up to the oblique camera), filtered by the
// anisotropic Kuwahara filter, in the four setups of the paper:
//   1 per-level filtering of whole needed mip levels, cached   (DeferredTexturing PER_LEVEL_CACHED)
//   2 per-fragment filtering, no cache                          (DeferredTexturing PER_FRAGMENT)
//   3 per-fragment filtering, cached                            (DeferredTexturing PER_FRAGMENT_CACHED)
//   4 filtering the rendered frame in a post-process stage      (PostProcessFiltering, Eq. 1)
// plus setup 3 under a progressive budget. Each run starts with empty caches (a new node) and a
// warm-up frame at the first pose whose filtering is not timed: the shader JIT of llvmpipe would
// otherwise dominate; the first timed frame then re-filters nothing in the cached setups, so
// each run's filtering of the path is timed except for the first pose (written in the reading).
// Frame times: glFinish-ended frames (OffscreenRenderer::renderTimedFrame).
// Accuracy: the last frame of each run against setup 1's last frame (Eq. 2 with every needed
// level filtered: what setups 2 and 3 must reproduce exactly and the post-process cannot),
// mean and max absolute difference in 8-bit units over RGB.
#include "BenchCase.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/filtering/DeferredTexturing>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/PostProcessFiltering>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
/** A filter specification without commas (the CSV's charts split on them): k=v;k=v. */
std::string noCommas(std::string s)
{
    for (char& c : s)
        if (c == ',') c = ';';
    return s;
}

/** Pose i of n along the fly-through: eye and centre eased from the street camera to the
 *  oblique one. */
osgLoA::CameraPose flyThrough(osg::Node& city, double aspect, unsigned i, unsigned n)
{
    const osgLoA::CameraPose a = osgLoA::CityCameras::compute("street", city, aspect);
    const osgLoA::CameraPose b = osgLoA::CityCameras::compute("oblique", city, aspect);
    const double t = n <= 1 ? 0.0 : double(i) / double(n - 1);
    const double s = t * t * (3 - 2 * t); // smoothstep: slow start and end
    osgLoA::CameraPose p = a;
    p.eye = a.eye * (1 - s) + b.eye * s;
    p.center = a.center * (1 - s) + b.center * s;
    p.up = osg::Vec3d(0, 0, 1);
    p.fovy = a.fovy * (1 - s) + b.fovy * s;
    return p;
}

std::pair<double, double> difference8(const osg::Image& a, const osg::Image& b)
{
    double sum = 0, mx = 0;
    const std::size_t n = std::size_t(a.s()) * std::size_t(a.t());
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
        {
            const double d = std::fabs(double(a.data()[i * 4 + std::size_t(c)]) -
                                       double(b.data()[i * 4 + std::size_t(c)]));
            sum += d;
            mx = std::max(mx, d);
        }
    return {sum / double(n * 3), mx};
}

struct Setup
{
    std::string name;
    int mode; // 1..3 deferred, 4 post-process
    unsigned budget;
};
} // namespace

std::vector<Row> filtering(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    const std::string spec = "akf";
    osg::ref_ptr<osgLoA::ImageFilter> filter = osgLoA::FilterRegistry::create(spec);
    const unsigned n = std::max(2u, frames);
    // Mode 0: the deferred pipeline without a filter; -1: forward rendering without a filter
    // (what the frame costs before any filtering).
    const std::vector<Setup> setups = {{"setup=1 per-level-cached", 1, 0},
                                       {"setup=2 per-fragment", 2, 0},
                                       {"setup=3 per-fragment-cached", 3, 0},
                                       {"setup=4 post-process", 4, 0},
                                       {"setup=3 cached+budget-65536", 3, 65536},
                                       {"unfiltered deferred", 0, 0},
                                       {"unfiltered forward", -1, 0}};
    const int sizes[3][2] = {{800, 600}, {1280, 720}, {1920, 1080}};
    for (const auto& sz : sizes)
    {
        osg::ref_ptr<osg::Image> reference;
        // Plain rendering at the fly-through's last pose: what each setup's last frame is
        // checked against (no black blocks where it has content).
        osg::ref_ptr<osg::Image> unfiltered;
        {
            auto plain = makeRenderer(sz[0], sz[1], 0, city.get(), "street");
            const osgLoA::CameraPose p = flyThrough(*city, double(sz[0]) / sz[1], n - 1, n);
            plain->setPerspective(p.fovy);
            plain->setViewMatrixAsLookAt(p.eye, p.center, p.up);
            unfiltered = plain->renderImage();
        }
        for (const Setup& setup : setups)
        {
            osg::ref_ptr<osg::Group> node;
            osg::ref_ptr<osgLoA::DeferredTexturing> deferred;
            osg::ref_ptr<osgLoA::PostProcessFiltering> post;
            if (setup.mode == -1)
                node = withPlainProgram(city.get());
            else if (setup.mode == 4)
            {
                post = new osgLoA::PostProcessFiltering;
                post->setFilter(filter.get());
                node = withPlainProgram(city.get());
                post->addChild(node.get());
                node = post;
            }
            else
            {
                deferred = new osgLoA::DeferredTexturing;
                if (setup.mode > 0)
                {
                    deferred->setFilter(filter.get());
                    deferred->setMode(osgLoA::DeferredTexturing::Mode(setup.mode));
                }
                deferred->setBudgetTexels(setup.budget);
                deferred->addChild(city.get());
                node = deferred;
            }
            auto r = makeRenderer(sz[0], sz[1], 0, node.get(), "street");
            renderer = r->getCapabilities().renderer;
            const double aspect = double(sz[0]) / sz[1];
            Row row;
            std::size_t filteredTexels = 0;
            double firstMs = 0;
            for (unsigned i = 0; i < n; ++i)
            {
                const osgLoA::CameraPose p = flyThrough(*city, aspect, i, n);
                r->setPerspective(p.fovy);
                r->setViewMatrixAsLookAt(p.eye, p.center, p.up);
                const double ms = r->renderTimedFrame();
                if (i > 0)
                    row.times.milliseconds.push_back(ms); // frame 0: warm-up (shader JIT)
                else
                    firstMs = ms;
                if (deferred && i > 0) filteredTexels += deferred->getStatistics().run.outputTexels;
            }
            osg::ref_ptr<osg::Image> last = r->renderImage();
            if (setup.mode == 1) reference = last;
            // The last frame of the fly-through, checked against the unfiltered one and kept.
            const std::string problem = checkBlocks(*last, *unfiltered);
            row.frameFailed = !problem.empty();
            if (sz[0] == 1920 || row.frameFailed)
                keepFrame(*last, "filtering-" + std::to_string(sz[0]) + "x" + std::to_string(sz[1]) + "-" +
                                     std::string(setup.name));
            const bool compared = setup.mode > 0;
            std::ostringstream p;
            p << sz[0] << "x" << sz[1] << " " << setup.name << " filter="
              << (setup.mode <= 0 ? std::string("none") : noCommas(filter->getParameterString()))
              << std::fixed << std::setprecision(2) << " avg_fps=" << 1000.0 / row.times.mean()
              << " min_fps=" << 1000.0 / row.times.max() << " first_frame_ms=" << firstMs
              << " frame=" << (problem.empty() ? std::string("ok") : "FAILED(" + problem + ")");
            if (deferred)
                p << " filtered_texels=" << filteredTexels
                  << " atlas_mib=" << double(deferred->getStatistics().atlasBytes) / (1024.0 * 1024.0)
                  << " gbuffer_mib=" << double(deferred->getStatistics().gbufferBytes) / (1024.0 * 1024.0);
            row.parameters = p.str();
            if (compared && reference && last)
            {
                const auto d = difference8(*last, *reference);
                std::ostringstream a, b;
                a << std::setprecision(4) << d.first;
                b << std::setprecision(4) << d.second;
                row.errorMean = a.str();
                row.errorMax = b.str();
            }
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": mean " << row.times.mean() << " ms, error "
                      << row.errorMean << "\n";
        }
    }
    return rows;
}
