// loa-bench case "transitions": the analogue of paper 004's Table 1 on the demo city.
#include "BenchCase.h"

#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
/** One graphic style for every feature: the LoA pipeline with nothing to blend. */
osg::ref_ptr<osgLoA::UsageScenario> homogeneous()
{
    osg::ref_ptr<osgLoA::UsageScenario> s = new osgLoA::UsageScenario;
    s->setName("homogeneous");
    osg::ref_ptr<osgLoA::TransitionConfiguration> c = new osgLoA::TransitionConfiguration;
    c->setName("photorealistic");
    c->setStyle("photorealistic");
    c->setFeatureTypes(osgLoA::TransitionConfiguration::FeatureTypes(std::begin(osgLoA::kFeatureTypes),
                                                                     std::end(osgLoA::kFeatureTypes)));
    c->setInterpolation(osgLoA::TransitionConfiguration::OBJECT);
    c->setBlendFunction(osgLoA::BlendFunction(0.0f, 0.0f, 1.0f, 1.0f));
    c->addMetric(new osgLoA::SaliencyMetric(osgLoA::SaliencyMetric::FEATURE_INTEREST, 0.0, 0.0));
    s->addConfiguration(c.get());
    return s;
}

} // namespace

std::vector<Row> transitions(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    // Plain: the city with the loa_plain program (textured, lit), no LoA node.
    osg::ref_ptr<osg::Group> plain = withPlainProgram(city.get());

    std::vector<std::pair<std::string, osg::ref_ptr<osgLoA::UsageScenario>>> scenarios;
    scenarios.emplace_back("homogeneous", homogeneous());
    for (const char* name : {"distance", "manual", "view-angle", "route", "circular-roi", "blueprint"})
        scenarios.emplace_back(name, osgLoA::ScenarioLibrary::createBuiltin(name));

    const int sizes[3][2] = {{800, 600}, {1280, 720}, {1920, 1080}};
    for (const auto& sz : sizes)
    {
        const std::string size = std::to_string(sz[0]) + "x" + std::to_string(sz[1]);
        {
            auto r = makeRenderer(sz[0], sz[1], 0, plain.get());
            renderer = r->getCapabilities().renderer;
            Row row;
            row.parameters = size + " scenario=plain";
            row.times = r->timeFrames(frames);
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
        }
        for (const auto& sc : scenarios)
        {
            osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
            loa->setScenario(sc.second.get());
            loa->addChild(city.get());
            auto r = makeRenderer(sz[0], sz[1], 0, loa.get());
            Row row;
            row.times = r->timeFrames(frames);
            const auto& st = loa->getRenderer()->getStatistics();
            const osgLoA::ABufferFrameStatistics ab =
                loa->getRenderer()->getABuffer()->getLastFrameStatistics();
            std::ostringstream p;
            p << size << " scenario=" << sc.first << " shared=" << st.sharedDraws
              << " transition=" << st.depthOnlyDraws << " abuffer_draws=" << st.aBufferDraws
              << " pingpong_draws=" << st.pingPongDraws << " abuffer_passes=" << (st.aBuffer ? ab.passes : 0);
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
