// loa-bench case "abstraction": the rows of Table 1 of papers 001 and 002 on the demo city
// (regular rendering; DoG; Kuwahara 3x3 and 5x5; adaptive abstraction with and without
// segmentation; cel and pencil shading; Sobel; hybrid pencil and hybrid toon), plus the other
// built-in abstraction styles, at 640x480, 800x600 and 1280x1024. Every style renders the same
// content (the demo city with the loa_plain program: the "regular rendering" row) under an
// AbstractionNode, along a short camera move (the oblique camera turned by 0.25 degrees per
// frame; the first frame is a warm-up and is not timed: llvmpipe compiles shaders then).
// Frame times: glFinish-ended frames (OffscreenRenderer::renderTimedFrame); each style's speed is
// its mean frame time as a ratio to regular rendering's at the same size, measured in the same
// run. Accuracy has no reference picture here (a style is its own definition; the GPU stages are
// held to their CPU references by the tests); the measure against speed is temporal coherence:
// error_mean is the mean per-pixel change between consecutive frames (8-bit units), error_max its
// ratio to regular rendering's.
#include "BenchCase.h"

#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/city/CityCameras>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

std::vector<Row> abstraction(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Group> content = withPlainProgram(demoCity().get());
    // Table 1 of both papers first, in their order, then the other built-ins.
    std::vector<std::string> styles = {
        "regular", "dog",    "kuwahara3", "kuwahara5",     "adaptive",   "adaptive-segmented",
        "cel",     "pencil", "sobel",     "hybrid-pencil", "hybrid-toon"};
    for (const std::string& s : osgLoA::AbstractionStyle::builtinNames())
        if (std::find(styles.begin(), styles.end(), s) == styles.end()) styles.push_back(s);
    const unsigned n = std::max(2u, frames) + 1;
    const int sizes[3][2] = {{640, 480}, {800, 600}, {1280, 1024}};
    for (const auto& sz : sizes)
    {
        double regularMs = 0.0, regularChange = 0.0;
        osg::ref_ptr<osg::Image> regularFrame;
        for (const std::string& style : styles)
        {
            osg::ref_ptr<osg::Node> scene = content;
            osg::ref_ptr<osgLoA::AbstractionNode> node;
            if (style != "regular")
            {
                node = new osgLoA::AbstractionNode;
                node->setStyle(osgLoA::AbstractionStyleCatalog::instance().create(style).get());
                node->addChild(content.get());
                scene = node;
            }
            auto r = makeRenderer(sz[0], sz[1], 0, scene.get(), "oblique");
            renderer = r->getCapabilities().renderer;
            const osgLoA::CameraPose pose =
                osgLoA::CityCameras::compute("oblique", *demoCity(), double(sz[0]) / double(sz[1]));
            Row row;
            double change = 0.0;
            osg::ref_ptr<osg::Image> previous;
            for (unsigned i = 0; i < n; ++i)
            {
                const osg::Quat turn(osg::DegreesToRadians(0.25 * i), osg::Vec3d(0, 0, 1));
                r->setPerspective(pose.fovy);
                r->setViewMatrixAsLookAt(pose.center + turn * (pose.eye - pose.center), pose.center, pose.up);
                const double ms = r->renderTimedFrame();
                if (i > 0) row.times.milliseconds.push_back(ms);
            }
            // Coherence: the same poses again, read back (outside the timed frames).
            for (unsigned i = 0; i < n; ++i)
            {
                const osg::Quat turn(osg::DegreesToRadians(0.25 * i), osg::Vec3d(0, 0, 1));
                r->setViewMatrixAsLookAt(pose.center + turn * (pose.eye - pose.center), pose.center, pose.up);
                osg::ref_ptr<osg::Image> img = r->renderImage();
                if (previous) change += meanChange(*previous, *img);
                previous = img;
            }
            change /= double(n - 1);
            if (style == "regular")
            {
                regularMs = row.times.mean();
                regularChange = change;
                regularFrame = previous;
            }
            // The last frame, checked against regular rendering of the same pose and kept.
            const std::string problem = checkBlocks(*previous, *regularFrame);
            row.frameFailed = !problem.empty();
            if (sz[0] == 1280 || row.frameFailed)
                keepFrame(*previous,
                          "abstraction-" + std::to_string(sz[0]) + "x" + std::to_string(sz[1]) + "-" + style);
            if (node && !node->getLastError().empty())
                throw std::runtime_error("abstraction style '" + style + "': " + node->getLastError());
            std::ostringstream p;
            p << sz[0] << "x" << sz[1] << " style=" << style << std::fixed << std::setprecision(2)
              << " avg_fps=" << 1000.0 / row.times.mean()
              << " ratio_to_regular=" << row.times.mean() / regularMs
              << " frame=" << (problem.empty() ? std::string("ok") : "FAILED(" + problem + ")");
            if (node)
            {
                const osgLoA::AbstractionNode::FrameStatistics st = node->getLastFrameStatistics();
                p << " scene_passes=" << st.passes << " filter_runs=" << st.filterRuns
                  << " filter_texels=" << st.filterTexels
                  << " targets_mib=" << node->memoryBytes(sz[0], sz[1]) / (1024.0 * 1024.0);
            }
            row.parameters = p.str();
            std::ostringstream a, b;
            a << std::setprecision(4) << change;
            b << std::setprecision(4) << change / regularChange;
            row.errorMean = a.str();
            row.errorMax = b.str();
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": mean " << row.times.mean() << " ms, change " << change
                      << "\n";
        }
    }
    return rows;
}
