// loa-scenario --image: renders osgLoA::InterestDebugView headless and writes it atomically.
#include "InterestImage.h"

#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/transitions/InterestDebugView>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>

void writeInterestImage(osgLoA::LoANode& node, const loa::CameraChoice& camera, int width, int height,
                        const std::string& path)
{
    node.bind(); // creates the region distance map, if the scenario needs one
    osgLoA::OffscreenRenderer::Settings settings;
    settings.width = width;
    settings.height = height;
    settings.clearColor = osg::Vec4(0.55f, 0.7f, 0.9f, 1.0f);
    osg::ref_ptr<osgLoA::OffscreenRenderer> renderer = new osgLoA::OffscreenRenderer(settings);
    // Frame the camera on the model itself, then evaluate the scenario from exactly that eye.
    osg::ref_ptr<osg::Group> frame = new osg::Group;
    for (unsigned i = 0; i < node.getNumChildren(); ++i)
        frame->addChild(node.getChild(i));
    renderer->setSceneData(frame.get());
    loa::applyCamera(*renderer, camera);
    const osg::Matrixd view = renderer->getCamera()->getViewMatrix();
    node.evaluate(osg::Matrixd::inverse(view).getTrans());
    osg::ref_ptr<osg::Group> debug = osgLoA::InterestDebugView::create(node);
    renderer->setSceneData(debug.get());
    renderer->getCamera()->setViewMatrix(view);
    osg::ref_ptr<osg::Image> image = renderer->renderImage();
    osgLoA::ImageFile::write(path, *image);
}
