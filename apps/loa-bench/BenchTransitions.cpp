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

namespace
{
/** One graphic style for every feature: the LoA pipeline with nothing to blend. */
osg::ref_ptr<osgLoA::UsageScenario> homogeneous(const std::string& style)
{
    osg::ref_ptr<osgLoA::UsageScenario> s = new osgLoA::UsageScenario;
    s->setName("homogeneous-" + style);
    osg::ref_ptr<osgLoA::TransitionConfiguration> c = new osgLoA::TransitionConfiguration;
    c->setName(style);
    c->setStyle(style);
    c->setFeatureTypes(osgLoA::TransitionConfiguration::FeatureTypes(std::begin(osgLoA::kFeatureTypes),
                                                                     std::end(osgLoA::kFeatureTypes)));
    c->setInterpolation(osgLoA::TransitionConfiguration::OBJECT);
    c->setBlendFunction(osgLoA::BlendFunction(0.0f, 0.0f, 1.0f, 1.0f));
    c->addMetric(new osgLoA::SaliencyMetric(osgLoA::SaliencyMetric::FEATURE_INTEREST, 0.0, 0.0));
    s->addConfiguration(c.get());
    return s;
}

/** Writes a benchmark's frame to out/bench-frames/NAME.png, to be looked at. */
void keepFrame(const osg::Image& frame, const std::string& name)
{
    osgDB::makeDirectory("out/bench-frames");
    osgLoA::ImageFile::write("out/bench-frames/" + name + ".png", frame);
}

} // namespace

std::string checkFrame(const osg::Image& frame, const osg::Image& reference, const osg::Vec4& clear)
{
    if (frame.s() != reference.s() || frame.t() != reference.t()) return "size differs from the reference";
    const int cr = int(std::lround(clear.r() * 255.0f)), cg = int(std::lround(clear.g() * 255.0f)),
              cb = int(std::lround(clear.b() * 255.0f));
    auto isClear = [&](const unsigned char* p)
    { return std::abs(p[0] - cr) <= 1 && std::abs(p[1] - cg) <= 1 && std::abs(p[2] - cb) <= 1; };
    auto isBlack = [](const unsigned char* p) { return p[0] < 4 && p[1] < 4 && p[2] < 4; };
    long long covered[2] = {0, 0}, black[2] = {0, 0};
    const osg::Image* images[2] = {&frame, &reference};
    for (int i = 0; i < 2; ++i)
        for (int y = 0; y < frame.t(); ++y)
            for (int x = 0; x < frame.s(); ++x)
            {
                const unsigned char* p = images[i]->data(x, y);
                covered[i] += isClear(p) ? 0 : 1;
                black[i] += isBlack(p) ? 1 : 0;
            }
    const double bar = 0.002 * double(frame.s()) * frame.t();
    std::ostringstream why;
    if (double(std::llabs(covered[0] - covered[1])) > bar)
        why << "covered " << covered[0] << " px against plain rendering's " << covered[1];
    if (double(black[0] - black[1]) > bar)
        why << (why.str().empty() ? "" : "; ") << black[0] << " black px against " << black[1];
    return why.str();
}

std::vector<Row> transitions(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    // Plain: the city with the loa_plain program (textured, lit), no LoA node.
    osg::ref_ptr<osg::Group> plain = withPlainProgram(city.get());

    typedef std::pair<std::string, osg::ref_ptr<osgLoA::UsageScenario>> Named;
    std::vector<Named> scenarios;
    for (const char* style : {"photorealistic", "cartographic"})
        scenarios.emplace_back(std::string("homogeneous-") + style, homogeneous(style));
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
