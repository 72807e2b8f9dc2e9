// loa-bench case "viewer": loa-viewer's edit-to-frame latency against scene size (issue 20 item 5).
// On each scene, the circle-of-interest scenario a user authors in the viewer (a circle at the
// scene's centre, detail inside, abstract outside), seen from the oblique camera at 1280x720
// (the viewer's default window). Each edit is made through osgLoA::ScenarioEditor, as the panels
// and the mouse make it, then one frame is rendered and finished: the row's times are edit plus
// frame, in milliseconds. Edits: a fade range (values: the scenario re-fitted, uniforms set), the
// circle moved (values plus the distance map), a style (structure: a re-bind), a feature's type
// (features: re-indexed and re-bound), and the same fade edit made as every edit was before
// (UsageScenario::dirty(): a full re-bind) - ratio_to_rebind compares the first with it in the
// same run. error_mean: the mean per-pixel difference (8-bit units) between the frame after the
// edit and the frame after a full re-bind of the same scenario (0: the partial rebuild draws the
// same frame); error_max: the fraction of its pixels more than 16/255 apart. Every last frame is checked
// against plain rendering and kept.
#include "BenchCase.h"

#include <osgLoA/authoring/ScenarioEditor>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageCompare>

#include <osg/ComputeBoundsVisitor>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> viewerScenes()
{
    std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> scenes;
    for (const std::pair<int, int>& blocks :
         {std::make_pair(2, 2), std::make_pair(4, 4), std::make_pair(10, 8), std::make_pair(16, 16)})
    {
        osgLoA::CityParameters p;
        p.blocksX = blocks.first;
        p.blocksY = blocks.second;
        scenes.push_back({"demo-city-" + std::to_string(blocks.first) + "x" + std::to_string(blocks.second),
                          osgLoA::CityGenerator(p).generate()});
    }
    for (const char* name : {"opencity-block", "torcs-street-1"})
    {
        const std::string file = std::string("data/test-scenes/") + name + ".osgt";
        osg::ref_ptr<osg::Node> model = osgDB::fileExists(file) ? osgDB::readRefNodeFile(file) : nullptr;
        if (!model)
        {
            std::cerr << "  " << name
                      << ": not found (run from the repository root after scripts/fetch-test-data)\n";
            continue;
        }
        osg::ref_ptr<osg::Group> group = new osg::Group;
        group->addChild(model.get());
        osgLoA::FeatureClassifier().classify(*group);
        scenes.push_back({name, group});
    }
    return scenes;
}

double since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

std::vector<Row> viewer(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    const int w = 1280, h = 720;
    for (const auto& scene : viewerScenes())
    {
        auto plain = makeRenderer(w, h, 0, scene.second.get(), "oblique");
        osg::ref_ptr<osg::Image> plainFrame = plain->renderImage();
        // The circle-of-interest scenario, authored as in the viewer.
        osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
        loa->setScenario(osgLoA::ScenarioLibrary::createBuiltin("distance").get());
        loa->addChild(scene.second.get());
        auto r = makeRenderer(w, h, 0, loa.get(), "oblique");
        renderer = r->getCapabilities().renderer;
        r->renderImage(); // binds
        osg::ComputeBoundsVisitor cbv;
        scene.second->accept(cbv);
        const osg::BoundingBox box = cbv.getBoundingBox();
        const double size = 0.5 * std::hypot(box.xMax() - box.xMin(), box.yMax() - box.yMin());
        const osg::Vec2d centre(box.center().x(), box.center().y());
        osg::ref_ptr<osgLoA::ScenarioEditor> editor = new osgLoA::ScenarioEditor(*loa);
        editor->placeCircle("circle-1", centre, 0.15 * size);
        editor->useRegionDetail("photorealistic", "abstract", 0.09 * size);
        const unsigned features = unsigned(loa->getFeatureIndex().size());
        r->timeFrames(1); // re-bound, programs compiled
        Row still;
        still.times = r->timeFrames(frames);
        // A building whose type the features edit changes back and forth.
        unsigned building = 0;
        for (const auto& e : loa->getFeatureIndex().entries())
            if (!building && e.parent < 0 && e.feature->getType() == osgLoA::FeatureType::Building &&
                e.node.valid() && !e.node->getName().empty())
            {
                bool unique = true;
                for (const auto& o : loa->getFeatureIndex().entries())
                    unique = unique && (o.feature == e.feature || !o.node.valid() ||
                                        o.node->getName() != e.node->getName());
                if (unique) building = e.feature->getId();
            }
        std::ostringstream base;
        base << w << "x" << h << " scene=" << scene.first << " features=" << features;
        still.parameters = base.str() + " edit=none frame=" + "ok";
        rows.push_back(still);
        std::cerr << "  " << still.parameters << ": median " << still.times.median() << " ms\n";
        double rebind = 0.0;
        for (const char* edit : {"full-rebind", "fade", "region-move", "style", "feature-type"})
        {
            const std::string kind = edit;
            if (kind == "feature-type" && !building) continue;
            Row row;
            for (unsigned i = 0; i <= frames; ++i)
            {
                const bool odd = (i % 2) != 0;
                const auto t0 = std::chrono::steady_clock::now();
                if (kind == "fade" || kind == "full-rebind")
                {
                    editor->setFadeIn(0, osg::Vec2f(odd ? 0.1f : 0.0f, 1.0f));
                    if (kind == "full-rebind") loa->getScenario()->dirty(); // every edit before issue 20
                }
                else if (kind == "region-move")
                    editor->placeCircle("circle-1", centre + osg::Vec2d(odd ? 0.05 * size : 0.0, 0.0),
                                        0.15 * size);
                else if (kind == "style")
                    editor->setStyle(0, odd ? "blueprint" : "photorealistic");
                else
                    editor->setFeatureType(building,
                                           odd ? osgLoA::FeatureType::Water : osgLoA::FeatureType::Building);
                const double editMs = since(t0);
                const double frameMs = r->renderTimedFrame();
                if (i > 0) row.times.milliseconds.push_back(editMs + frameMs); // the first: programs compiled
            }
            // The frame after the edit against the frame after a full re-bind of the same scenario.
            osg::ref_ptr<osg::Image> frame = r->renderImage();
            loa->getScenario()->dirty();
            osg::ref_ptr<osg::Image> rebound = r->renderImage();
            const double difference = meanChange(*frame, *rebound);
            const osgLoA::ImageComparison differing = osgLoA::ImageComparison::compare(*frame, *rebound, 16);
            const std::string problem = checkFrame(*frame, *plainFrame, r->getSettings().clearColor);
            row.frameFailed = !problem.empty() || difference > 0.5;
            if (kind == "full-rebind") rebind = row.times.median();
            std::ostringstream p, e;
            p << base.str() << " edit=" << kind << std::setprecision(3)
              << " ratio_to_rebind=" << (rebind > 0.0 ? row.times.median() / rebind : 0.0)
              << " frame_ms=" << still.times.median() << " binds=" << loa->getBindCount()
              << " refits=" << loa->getRefitCount() << " frame="
              << (problem.empty() ? (difference > 0.5 ? "FAILED(differs from a full re-bind)" : "ok")
                                  : "FAILED(" + problem + ")");
            std::ostringstream f;
            e << std::setprecision(4) << difference;
            f << std::setprecision(4) << differing.failingFraction;
            row.parameters = p.str();
            row.errorMean = e.str();
            row.errorMax = f.str();
            keepFrame(*frame, "viewer-" + scene.first + "-" + kind);
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
        }
    }
    return rows;
}
