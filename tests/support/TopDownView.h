// Top-down views of small map scenes for the cartographic styles' tests (waterlining, relief):
// horizontal quads as features, and a model drawn through a LoA node in one style, orthographic
// from above, north up.
#pragma once

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/Feature>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/ImageFile>

#include <osg/BoundingBox>
#include <osg/ComputeBoundsVisitor>
#include <osg/Geometry>
#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace loatest
{

struct Viewport
{
    int x = 0, y = 0, w = 0, h = 0;
};

/** The plane z = a x + b y + c over [x0, x1] x [y0, y1]: one quad with its normal, white. */
inline osg::ref_ptr<osg::Geometry> planeQuad(double x0, double y0, double x1, double y1, double a = 0.0,
                                             double b = 0.0, double c = 0.0)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (const osg::Vec2d& p :
         {osg::Vec2d(x0, y0), osg::Vec2d(x1, y0), osg::Vec2d(x1, y1), osg::Vec2d(x0, y1)})
        v->push_back(osg::Vec3(p.x(), p.y(), a * p.x() + b * p.y() + c));
    g->setVertexArray(v.get());
    osg::Vec3 n(-a, -b, 1.0);
    n.normalize();
    osg::ref_ptr<osg::Vec3Array> na = new osg::Vec3Array;
    na->push_back(n);
    g->setNormalArray(na.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec4Array> col = new osg::Vec4Array;
    col->push_back(osg::Vec4(1, 1, 1, 1));
    g->setColorArray(col.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    return g;
}

/** child under a group that carries a Feature of this id and type. */
inline osg::ref_ptr<osg::Node> asFeature(osg::Node* child, unsigned id, osgLoA::FeatureType type)
{
    osg::ref_ptr<osg::Group> g = new osg::Group;
    g->addChild(child);
    osgLoA::Feature::attach(*g, new osgLoA::Feature(id, type));
    return g;
}

/** A quad over [x0, x1] x [y0, y1] (z = 0) under a group carrying a Feature of this id, type
 *  and sub-type. */
inline osg::ref_ptr<osg::Node> featureQuad(unsigned id, osgLoA::FeatureType type, const std::string& subType,
                                           double x0, double y0, double x1, double y1)
{
    osg::ref_ptr<osg::Group> g = new osg::Group;
    g->addChild(planeQuad(x0, y0, x1, y1).get());
    osgLoA::Feature::attach(*g, new osgLoA::Feature(id, type, subType));
    return g;
}

/** The model drawn through a LoA node with this scenario by the camera `pose(renderer)` sets
 *  (projection and view); with an offset viewport the whole target is drawn once first (what
 *  stays outside it). */
template <class Pose>
osg::ref_ptr<osg::Image> throughLoA(osg::Node* model, osgLoA::UsageScenario* scenario, int width, int height,
                                    const Viewport& vp, const Pose& pose)
{
    osg::ref_ptr<osgLoA::LoANode> loa = new osgLoA::LoANode;
    loa->setScenario(scenario);
    loa->addChild(model);
    osgLoA::OffscreenRenderer::Settings s;
    s.width = width;
    s.height = height;
    s.clearColor = osg::Vec4(0.2f, 0.3f, 0.4f, 1.0f);
    osg::ref_ptr<osgLoA::OffscreenRenderer> r = new osgLoA::OffscreenRenderer(s);
    r->setSceneData(loa.get());
    if (vp.w != width || vp.h != height || vp.x || vp.y)
    {
        pose(*r);
        r->renderImage();
        r->getCamera()->setViewport(vp.x, vp.y, vp.w, vp.h);
    }
    pose(*r);
    osg::ref_ptr<osg::Image> image = r->renderImage();
    EXPECT_EQ(loa->getBindError(), "");
    return image;
}

/** The model drawn top-down (orthographic from above view's z range, north up) over view's x/y
 *  through a LoA node with this scenario. */
inline osg::ref_ptr<osg::Image> topDown(osg::Node* model, osgLoA::UsageScenario* scenario, int width,
                                        int height, const Viewport& vp, const osg::BoundingBoxd& view)
{
    const double top = view.zMax() + 500.0;
    return throughLoA(
        model, scenario, width, height, vp,
        [&](osgLoA::OffscreenRenderer& r)
        {
            r.getCamera()->setProjectionMatrixAsOrtho(view.xMin(), view.xMax(), view.yMin(), view.yMax(), 1.0,
                                                      top - view.zMin() + 10.0);
            r.setViewMatrixAsLookAt(osg::Vec3d(0, 0, top), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 1, 0));
        });
}

/** The same, through a scenario that draws everything in `style`. */
inline osg::ref_ptr<osg::Image> topDown(osg::Node* model, const std::string& style, int width, int height,
                                        const Viewport& vp, const osg::BoundingBoxd& view)
{
    return topDown(model, osgLoA::ScenarioLibrary::createHomogeneous(style).get(), width, height, vp, view);
}

/** Writes a frame a test made into the build's test-output/<folder>/<name>.png, to look at. */
inline void keepFrame(const std::string& folder, const osg::Image& image, const std::string& name)
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/" + folder;
    osgDB::makeDirectory(dir);
    osgLoA::ImageFile::write(dir + "/" + name + ".png", image);
}

/** A mask style for differenceInMask: "test-TYPE-mask", cartographic with the features of this
 *  type pure magenta; registered in the catalog on first use. Returns its name. */
inline std::string typeMaskStyle(osgLoA::FeatureType type)
{
    const std::string name = std::string("test-") + osgLoA::toString(type) + "-mask";
    osgLoA::GraphicStyleCatalog& catalog = osgLoA::GraphicStyleCatalog::instance();
    if (!catalog.prototype(name))
    {
        osg::ref_ptr<osgLoA::GraphicStyle> mask = catalog.create("cartographic");
        mask->setName(name);
        mask->getParameter("loa_cartographic_colors")->setElement(unsigned(type), osg::Vec3f(1, 0, 1));
        catalog.add(*mask);
    }
    return name;
}

/** The view box that frames a model's bounds (or `bounds`) whole in a width x height frame seen
 *  from above, centred, square pixels: for topDown. */
inline osg::BoundingBoxd framedView(osg::Node* model, int width, int height,
                                    const osg::BoundingBoxd* bounds = nullptr)
{
    osg::BoundingBoxd b;
    if (bounds)
        b = *bounds;
    else
    {
        osg::ComputeBoundsVisitor cbv;
        model->accept(cbv);
        b = osg::BoundingBoxd(cbv.getBoundingBox());
    }
    const double aspect = double(width) / height;
    const osg::Vec3d c = b.center();
    const double half = 0.5 * std::max((b.xMax() - b.xMin()) / aspect, double(b.yMax() - b.yMin()));
    return osg::BoundingBoxd(c.x() - half * aspect, c.y() - half, b.zMin(), c.x() + half * aspect,
                             c.y() + half, b.zMax());
}

/** Pixels of a style's top-down frame that differ from another style's, inside and outside the
 *  magenta of a mask style (a style drawing the features concerned pure magenta; grown by 2 px,
 *  darkened magenta where edges lie on it counts): the model (or the frame given) framed whole,
 *  orthographic. */
struct MaskedDifference
{
    long inside = 0;  ///< mask pixels
    long changed = 0; ///< of those, differing by more than 8/255 in a channel
    long outside = 0; ///< pixels outside the mask differing by more than 2/255
};
inline MaskedDifference differenceInMask(osg::Node* model, const std::string& style,
                                         const std::string& reference, const std::string& maskStyle,
                                         int width, int height, const std::string& folder,
                                         const std::string& name, const osg::BoundingBoxd* frame = nullptr)
{
    const osg::BoundingBoxd view = framedView(model, width, height, frame);
    const Viewport vp{0, 0, width, height};
    osg::ref_ptr<osg::Image> styled = topDown(model, style, width, height, vp, view);
    osg::ref_ptr<osg::Image> flat = topDown(model, reference, width, height, vp, view);
    osg::ref_ptr<osg::Image> mask = topDown(model, maskStyle, width, height, vp, view);
    auto inMask = [&](int x, int y)
    {
        for (int j = std::max(0, y - 2); j <= std::min(height - 1, y + 2); ++j)
            for (int i = std::max(0, x - 2); i <= std::min(width - 1, x + 2); ++i)
            {
                const unsigned char* p = mask->data(i, j);
                if (p[0] > p[1] + 30 && p[2] > p[1] + 30 && std::abs(int(p[0]) - int(p[2])) < 30) return true;
            }
        return false;
    };
    MaskedDifference d;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
            const unsigned char *p = styled->data(x, y), *q = flat->data(x, y);
            const int diff = std::max({std::abs(int(p[0]) - int(q[0])), std::abs(int(p[1]) - int(q[1])),
                                       std::abs(int(p[2]) - int(q[2]))});
            if (inMask(x, y))
            {
                ++d.inside;
                d.changed += diff > 8;
            }
            else if (diff > 2)
                ++d.outside;
        }
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    std::cout << style << " " << name << " " << size << ": " << d.changed << " of " << d.inside
              << " pixels of the mask changed, " << d.outside << " differing pixels outside it\n";
    keepFrame(folder, *styled, name + "-" + size);
    keepFrame(folder, *flat, name + "-" + size + "-" + reference);
    if (d.outside) keepFrame(folder, *mask, name + "-" + size + "-mask");
    return d;
}

} // namespace loatest
