// loa-bench case "saliency": paper 004 Figure 10 as a number. The paper shows image-saliency maps
// (GBVS) of a photorealistic render and of LoA renders and argues that LoA concentrates attention
// on the region of interest. Here: the share of a spectral-residual saliency map's mass (Hou &
// Zhang 2007, osgLoA::SpectralResidualSaliency) inside the region the scenario draws in detail
// (its interest debug view, paper 004 Figure 5: interest > 0.5), for homogeneous photorealistic
// rendering and for each library scenario, on the same view of the demo city and of the real
// OpenCity block, 1280x720 and 1920x1080, oblique camera. error_mean = the scenario's share,
// error_max = photorealistic's; the times are the scenario's frames.
#include "BenchCase.h"

#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/transitions/InterestDebugView>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/SpectralResidualSaliency>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
/** The region of interest of a LoA node's scenario in the renderer's view: its interest debug
 *  view's dark pixels (interest > 0.5), not the background (pure green here) or red (no match). */
std::vector<unsigned char> regionOfInterest(osgLoA::LoANode& node, osgLoA::OffscreenRenderer& r,
                                            osg::ref_ptr<osg::Image>& keep)
{
    // The same renderer (its projection and pose), the debug view as its scene for one frame.
    const osg::Matrixd view = r.getCamera()->getViewMatrix();
    node.evaluate(osg::Matrixd::inverse(view).getTrans());
    osg::ref_ptr<osg::Node> scene = r.getSceneData();
    const osg::Vec4 clear = r.getCamera()->getClearColor();
    r.getCamera()->setClearColor(osg::Vec4(0, 1, 0, 1));
    r.setSceneData(osgLoA::InterestDebugView::create(node).get());
    r.getCamera()->setViewMatrix(view);
    osg::ref_ptr<osg::Image> img = r.renderImage();
    r.getCamera()->setClearColor(clear);
    r.setSceneData(scene.get());
    r.getCamera()->setViewMatrix(view);
    std::vector<unsigned char> mask(std::size_t(img->s()) * std::size_t(img->t()), 0);
    for (int y = 0; y < img->t(); ++y)
        for (int x = 0; x < img->s(); ++x)
        {
            const unsigned char* p = img->data(x, y);
            const bool background = p[0] < 40 && p[1] > 200 && p[2] < 40;
            const bool unmatched = p[0] > p[1] + 60 && p[0] > p[2] + 60;
            const double luma = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
            mask[std::size_t(y) * std::size_t(img->s()) + std::size_t(x)] =
                !background && !unmatched && luma < 128.0 ? 1 : 0;
        }
    keep = img;
    return mask;
}
} // namespace

std::vector<Row> saliency(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    const std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> scenes = demoCityAndOpenCityBlock();
    using SRS = osgLoA::SpectralResidualSaliency;
    for (const auto& scene : scenes)
        for (const std::pair<int, int>& size : {std::make_pair(1280, 720), std::make_pair(1920, 1080)})
        {
            const std::string sz = std::to_string(size.first) + "x" + std::to_string(size.second);
            osg::ref_ptr<osg::Image> photoFrame;
            {
                // (One LoA node over the scene at a time: each installs its callbacks on the
                // scene's feature nodes.)
                osg::ref_ptr<osgLoA::LoANode> photo = new osgLoA::LoANode;
                photo->setScenario(osgLoA::ScenarioLibrary::createHomogeneous("photorealistic").get());
                photo->addChild(scene.second.get());
                photoFrame = makeRenderer(size.first, size.second, 0, photo.get(), "oblique")->renderImage();
            }
            osg::ref_ptr<osg::Image> plainFrame =
                makeRenderer(size.first, size.second, 0, scene.second.get(), "oblique")->renderImage();
            const std::vector<float> photoMap = SRS::compute(*photoFrame);
            for (const std::string& name : osgLoA::ScenarioLibrary::builtinNames())
            {
                osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
                loa->setScenario(osgLoA::ScenarioLibrary::createBuiltin(name).get());
                loa->addChild(scene.second.get());
                auto r = makeRenderer(size.first, size.second, 0, loa.get(), "oblique");
                renderer = r->getCapabilities().renderer;
                Row row;
                row.times = r->timeFrames(frames);
                osg::ref_ptr<osg::Image> frame = r->renderImage();
                const std::string problem = checkFrame(*frame, *plainFrame, r->getSettings().clearColor);
                row.frameFailed = !problem.empty();
                osg::ref_ptr<osg::Image> debugImage;
                const std::vector<unsigned char> roi = regionOfInterest(*loa, *r, debugImage);
                long inside = 0;
                for (unsigned char m : roi)
                    inside += m;
                const double roiShare = double(inside) / double(roi.size());
                const double photoShare = SRS::massInside(photoMap, roi, size.first, size.second);
                const double share = SRS::massInside(SRS::compute(*frame), roi, size.first, size.second);
                std::ostringstream p;
                p << sz << " scene=" << scene.first << " scenario=" << name << std::fixed
                  << std::setprecision(3) << " roi_area=" << roiShare
                  << " share_photorealistic=" << photoShare << " share_scenario=" << share
                  << " gain=" << (photoShare > 0.0 ? share / photoShare : 0.0)
                  << " frame=" << (problem.empty() ? "ok" : "FAILED(" + problem + ")");
                row.parameters = p.str();
                std::ostringstream a, b;
                a << std::setprecision(4) << share;
                b << std::setprecision(4) << photoShare;
                row.errorMean = a.str();
                row.errorMax = b.str();
                if (size.first == 1920 || row.frameFailed)
                {
                    keepFrame(*frame, "saliency-" + scene.first + "-" + sz + "-" + name);
                    keepFrame(*debugImage, "saliency-" + scene.first + "-" + sz + "-" + name + "-roi");
                }
                rows.push_back(row);
                std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
            }
            if (size.first == 1920)
                keepFrame(*photoFrame, "saliency-" + scene.first + "-" + sz + "-photorealistic");
        }
    return rows;
}
