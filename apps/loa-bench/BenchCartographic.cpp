// loa-bench case "cartographic": the cost of the cartographic devices of paper 004 §3.2.3
// (waterlining, relief presentation, green-space signatures, streets without and with their labels) as a
// ratio to flat cartographic,
// measured in the same run on the same views: the demo city and the real OpenCity block, at 1280x720 and
// 1920x1080, from the oblique and top cameras. Every frame is checked against plain rendering's coverage and
// kept at 1920x1080 (out/bench-frames/). At 1280x720 each row also measures temporal coherence along a
// 10-frame camera turn: error_mean is the mean per-pixel change between consecutive frames (8-bit
// units), error_max its ratio to plain rendering's on the same move.
#include "BenchCase.h"

#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <iomanip>
#include <iostream>
#include <sstream>

std::vector<Row> cartographic(unsigned frames, std::string& renderer)
{
    // The streets style without its label layer: the labels' cost is streets over this.
    osgLoA::GraphicStyleCatalog& catalog = osgLoA::GraphicStyleCatalog::instance();
    if (!catalog.prototype("streets-unlabelled"))
    {
        osg::ref_ptr<osgLoA::GraphicStyle> s = catalog.create("streets");
        s->setName("streets-unlabelled");
        s->getParameter("loa_labels_size")->set(0.0f);
        catalog.add(*s);
    }
    std::vector<Row> rows;
    const std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> scenes = demoCityAndOpenCityBlock();
    for (const auto& scene : scenes)
        for (const std::pair<int, int>& size : {std::make_pair(1280, 720), std::make_pair(1920, 1080)})
            for (const char* camera : {"oblique", "top"})
            {
                const std::string sz = std::to_string(size.first) + "x" + std::to_string(size.second);
                auto plain = makeRenderer(size.first, size.second, 0, scene.second.get(), camera);
                osg::ref_ptr<osg::Image> plainFrame = plain->renderImage();
                // Temporal coherence (as the abstraction case measures it) at 1280x720: the mean
                // per-pixel change over a 10-frame camera turn, and its ratio to plain rendering's.
                const bool temporal = size.first == 1280;
                const double plainChange = temporal ? temporalChange(*plain, 10) : 0.0;
                double flat = 0.0;
                for (const char* style : {"cartographic", "waterlining", "relief", "signatures",
                                          "streets-unlabelled", "streets", "trees", "object-edges"})
                {
                    osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
                    loa->setScenario(osgLoA::ScenarioLibrary::createHomogeneous(style).get());
                    loa->addChild(scene.second.get());
                    auto r = makeRenderer(size.first, size.second, 0, loa.get(), camera);
                    renderer = r->getCapabilities().renderer;
                    Row row;
                    row.times = r->timeFrames(frames);
                    if (std::string(style) == "cartographic") flat = row.times.median();
                    osg::ref_ptr<osg::Image> frame = r->renderImage();
                    const std::string problem = checkFrame(*frame, *plainFrame, r->getSettings().clearColor);
                    row.frameFailed = !problem.empty();
                    std::ostringstream p;
                    p << sz << " camera=" << camera << " scene=" << scene.first << " style=" << style
                      << " ratio_to_cartographic=" << std::setprecision(3)
                      << (flat > 0.0 ? row.times.median() / flat : 0.0)
                      << " frame=" << (problem.empty() ? "ok" : "FAILED(" + problem + ")");
                    row.parameters = p.str();
                    if (temporal)
                    {
                        const double change = temporalChange(*r, 10);
                        std::ostringstream a, b;
                        a << std::setprecision(4) << change;
                        b << std::setprecision(4) << (plainChange > 0.0 ? change / plainChange : 0.0);
                        row.errorMean = a.str();
                        row.errorMax = b.str();
                    }
                    if (size.first == 1920 || row.frameFailed)
                        keepFrame(*frame,
                                  "cartographic-" + scene.first + "-" + sz + "-" + camera + "-" + style);
                    rows.push_back(row);
                    std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
                }
            }
    return rows;
}
