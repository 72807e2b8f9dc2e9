// loa-bench case "transitions": the analogue of paper 004's Table 1 on the demo city.
#include "BenchCase.h"

#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageFile>

#include <osgDB/FileUtils>

#include <cmath>
#include <cstdlib>

#include <iomanip>
#include <iostream>
#include <sstream>


std::vector<Row> transitions(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    // Plain: the city with the loa_plain program (textured, lit), no LoA node.
    osg::ref_ptr<osg::Group> plain = withPlainProgram(city.get());

    typedef std::pair<std::string, osg::ref_ptr<osgLoA::UsageScenario>> Named;
    std::vector<Named> scenarios;
    for (const char* style : {"photorealistic", "cartographic"})
        scenarios.emplace_back(std::string("homogeneous-") + style, osgLoA::ScenarioLibrary::createHomogeneous(style));
    for (const std::string& name : osgLoA::ScenarioLibrary::builtinNames())
        scenarios.emplace_back(name, osgLoA::ScenarioLibrary::createBuiltin(name));
    // From the street the view distance runs through all three levels of "distance" (from the
    // oblique camera every feature is far: one style); paper 004's Table 1 compares such a view
    // with a homogeneous style.
    const std::vector<Named> street = {scenarios[0], scenarios[1],
                                       Named("distance", osgLoA::ScenarioLibrary::createBuiltin("distance"))};

    const int sizes[3][2] = {{800, 600}, {1280, 720}, {1920, 1080}};
    for (const auto& sz : sizes)
        for (const char* camera : {"oblique", "street"})
        {
            const std::string size = std::to_string(sz[0]) + "x" + std::to_string(sz[1]);
            const bool oblique = std::string(camera) == "oblique";
            osg::ref_ptr<osg::Image> plainFrame;
            osg::Vec4 clear;
            {
                auto r = makeRenderer(sz[0], sz[1], 0, plain.get(), camera);
                renderer = r->getCapabilities().renderer;
                Row row;
                row.parameters = size + " camera=" + camera + " scenario=plain";
                row.times = r->timeFrames(frames);
                // The last frame, untimed: the reference the scenario frames are checked against.
                plainFrame = r->renderImage();
                clear = r->getSettings().clearColor;
                rows.push_back(row);
                std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
            }
            for (const auto& sc : oblique ? scenarios : street)
            {
                osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
                loa->setScenario(sc.second.get());
                loa->addChild(city.get());
                auto r = makeRenderer(sz[0], sz[1], 0, loa.get(), camera);
                Row row;
                row.times = r->timeFrames(frames);
                const auto& st = loa->getRenderer()->getStatistics();
                const osgLoA::ABufferFrameStatistics ab =
                    loa->getRenderer()->getABuffer()->getLastFrameStatistics();
                std::ostringstream p;
                p << size << " camera=" << camera << " scenario=" << sc.first << " shared=" << st.sharedDraws
                  << " transition=" << st.depthOnlyDraws << " abuffer_draws=" << st.aBufferDraws
                  << " pingpong_draws=" << st.pingPongDraws
                  << " abuffer_passes=" << (st.aBuffer ? ab.passes : 0);
                // The frame that was timed, checked (untimed) against plain rendering's and kept
                // to look at (out/bench-frames/).
                osg::ref_ptr<osg::Image> frame = r->renderImage();
                const std::string problem = checkFrame(*frame, *plainFrame, clear);
                p << " frame=" << (problem.empty() ? "ok" : "FAILED(" + problem + ")");
                row.frameFailed = !problem.empty();
                if (sz[0] == 1920 || row.frameFailed)
                    keepFrame(*frame, "transitions-" + size + "-" + camera + "-" + sc.first);
                row.parameters = p.str();
                // Accuracy: the fraction of pixels whose fragments did not all fit the A-buffer.
                const double lost = st.aBuffer && ab.truncated && !ab.overflowPixels.empty()
                                        ? double(ab.overflowPixels.back()) / (double(sz[0]) * sz[1])
                                        : 0.0;
                std::ostringstream e;
                e << std::setprecision(4) << lost;
                row.errorMean = e.str();
                row.errorMax = e.str();
                rows.push_back(row);
                std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
            }
        }
    return rows;
}
