// loa-bench case "abuffer": the order-independent transparency methods (osgLoA::
// OrderIndependentTransparency: the stencil-routed A-buffer for N samples per pass and a maximum
// number of routing passes, per-pixel linked lists, weighted blended OIT) on a scene of controlled
// depth complexity: K transparent quads covering the view, drawn in a scrambled depth order;
// frame time against the error to the CPU reference composite of all K fragments
// (osgLoA::ReferenceCompositor).
#include "BenchCase.h"

#include <osgLoA/compositing/OrderIndependentTransparency>
#include <osgLoA/compositing/ReferenceCompositor>
#include <osgLoA/compositing/StencilRoutedABuffer>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/util/ImageCompare>

#include <osg/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace
{
const osg::Vec4 kBackground(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 1.0f);

struct Layer
{
    float distance;
    osg::Vec4 color;
};

/** K layers at distances 1, 1.5, ... in a scrambled order, colours in whole 1/255 steps. */
std::vector<Layer> layersOf(int k)
{
    std::mt19937 rng(unsigned(k) * 31u + 7u);
    std::vector<int> order(std::size_t(k), 0);
    for (int i = 0; i < k; ++i)
        order[std::size_t(i)] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Layer> layers;
    for (int i = 0; i < k; ++i)
        layers.push_back({1.0f + 0.5f * float(order[std::size_t(i)]),
                          osg::Vec4(float(rng() % 256) / 255.0f, float(rng() % 256) / 255.0f,
                                    float(rng() % 256) / 255.0f, float(40 + rng() % 180) / 255.0f)});
    return layers;
}

/** A quad over [-extent, extent]^2 of the view (1: all of it). */
osg::ref_ptr<osg::Geometry> quad(const Layer& l, float extent = 1.0f)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (const osg::Vec2& c : {osg::Vec2(-1, -1), osg::Vec2(1, -1), osg::Vec2(1, 1), osg::Vec2(-1, 1)})
        v->push_back(osg::Vec3(c.x() * extent, c.y() * extent, -l.distance));
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(l.color);
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLE_FAN, 0, 4));
    return g;
}

/** The reference: every pixel of the central [-extent, extent]^2 of the view holds the same K
 *  fragments, the others none. */
osg::ref_ptr<osg::Image> referenceImage(const std::vector<Layer>& layers, int w, int h, float extent = 1.0f)
{
    osgLoA::ReferenceCompositor::FragmentList f;
    for (const Layer& l : layers)
    {
        osgLoA::ReferenceCompositor::Fragment x;
        x.color = l.color;
        x.depth = l.distance / 10.0f;
        f.push_back(x);
    }
    osgLoA::ReferenceCompositor::FragmentImage one(1, 1);
    one.at(0, 0) = f;
    const osg::ref_ptr<osg::Image> px = osgLoA::ReferenceCompositor().compositeImage(one, kBackground);
    const osg::ref_ptr<osg::Image> bg = osgLoA::ReferenceCompositor().compositeImage(
        osgLoA::ReferenceCompositor::FragmentImage(1, 1), kBackground);
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const double cx = (x + 0.5) / w * 2.0 - 1.0, cy = (y + 0.5) / h * 2.0 - 1.0;
            const bool in = std::abs(cx) <= extent && std::abs(cy) <= extent;
            std::copy((in ? px : bg)->data(0, 0), (in ? px : bg)->data(0, 0) + 4, img->data(x, y));
        }
    return img;
}
} // namespace

std::vector<Row> abuffer(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    const int w = 640, h = 480;
    osgLoA::OffscreenRenderer::Settings s;
    s.width = w;
    s.height = h;
    s.clearColor = kBackground;
    osg::ref_ptr<osgLoA::OffscreenRenderer> r = new osgLoA::OffscreenRenderer(s);
    renderer = r->getCapabilities().renderer;
    osg::Camera* cam = r->getCamera();
    cam->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    cam->setProjectionMatrixAsOrtho(-1.0, 1.0, -1.0, 1.0, 0.0, 10.0);
    cam->setViewMatrix(osg::Matrix::identity());
    const int maxSamples = r->getCapabilities().maxSamples;
    using OIT = osgLoA::OrderIndependentTransparency;
    struct Config
    {
        OIT::Method method;
        int n, maxPasses;
    };
    std::vector<Config> configs;
    for (int n : {1, 2, 4, 8})
        for (int maxPasses : {1, 2, 3, 4})
            if (n <= maxSamples) configs.push_back({OIT::STENCIL_ROUTED, n, maxPasses});
    configs.push_back({OIT::LINKED_LIST, 4, 4});
    configs.push_back({OIT::WEIGHTED_BLENDED, 1, 1});
    // Times the scene, compares its frame with the reference and adds the row.
    auto measure = [&](const std::string& parameters, const osg::Image& reference)
    {
        Row row;
        row.times = r->timeFrames(frames);
        const auto cmp = osgLoA::ImageComparison::compare(*r->renderImage(), reference, 1);
        std::ostringstream m, x;
        m << std::setprecision(4) << cmp.meanDifference;
        x << cmp.maxDifference;
        row.parameters = parameters;
        row.errorMean = m.str();
        row.errorMax = x.str();
        rows.push_back(row);
        std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms, mean error "
                  << row.errorMean << "/255, max " << row.errorMax << "/255\n";
    };
    for (const Config& cfg : configs)
    {
        // One instance per configuration: its storage grows only to what its rows need.
        osg::ref_ptr<OIT> ab = OIT::create(cfg.method, cfg.n, cfg.maxPasses);
        ab->getRoutedStateSet()->setAttribute(ab->createVertexColorProgramForMethod().get());
        osg::ref_ptr<osg::Group> root = new osg::Group;
        root->addChild(ab->getCamera());
        root->addChild(ab->createResolveNode().get());
        r->setSceneData(root.get());
        for (int k : {1, 2, 4, 8, 12, 16})
        {
            const std::vector<Layer> layers = layersOf(k);
            osg::Group* g = ab->getRoutedGroup();
            g->removeChildren(0, g->getNumChildren());
            for (const Layer& l : layers)
                g->addChild(quad(l).get());
            // The statistics are those of the frame before the parameters are written: the
            // warm-up and timed frames have drawn the same scene.
            r->renderImage();
            const osgLoA::OITFrameStatistics st = ab->getFrameStatistics();
            std::ostringstream p;
            p << "method=" << OIT::methodName(cfg.method);
            if (cfg.method == OIT::STENCIL_ROUTED) p << " N=" << cfg.n << " max=" << cfg.maxPasses;
            p << " K=" << k << " passes=" << st.geometryPasses << " " << w << "x" << h
              << (st.truncated ? " truncated" : "") << " " << std::fixed << std::setprecision(1)
              << double(st.bytes) / 1048576.0 << " MiB";
            measure(p.str(), *referenceImage(layers, w, h));
        }
        // The routed region (issue 21 item 2): 4 layers over the central sixteenth of the view,
        // passes restricted to the tiles they touch, then over the whole viewport.
        if (cfg.method == OIT::STENCIL_ROUTED && (cfg.n != 4 || cfg.maxPasses != 4)) continue;
        const std::vector<Layer> layers = layersOf(4);
        osg::Group* g = ab->getRoutedGroup();
        g->removeChildren(0, g->getNumChildren());
        for (const Layer& l : layers)
            g->addChild(quad(l, 0.25f).get());
        for (bool restrict : {true, false})
        {
            ab->setRestrictToRoutedRegion(restrict);
            r->renderImage();
            const osgLoA::OITFrameStatistics st = ab->getFrameStatistics();
            std::ostringstream p;
            p << "method=" << OIT::methodName(cfg.method)
              << (cfg.method == OIT::STENCIL_ROUTED ? " N=4 max=4" : "")
              << " K=4 region=" << (restrict ? "tiles" : "viewport") << " sixteenth-of-view " << w << "x" << h
              << " tiles=" << st.regionTiles << "/" << st.viewportTiles;
            measure(p.str(), *referenceImage(layers, w, h, 0.25f));
        }
        ab->setRestrictToRoutedRegion(true);
    }
    return rows;
}
