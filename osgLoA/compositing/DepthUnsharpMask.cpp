// DepthUnsharpMask: alpha-weighted Gaussian of the front depth, for unsharp masking.
#include <osgLoA/compositing/DepthUnsharpMask>

#include <osgLoA/render/ShaderLibrary>

#include "RenderTarget.h"

#include <osg/Geode>

#include <stdexcept>

namespace osgLoA
{

DepthUnsharpMask::DepthUnsharpMask(int firstRenderOrder)
{
    osg::ref_ptr<osg::Program> program =
        ShaderLibrary::createProgram("unsharp-blur", {"loa_compose.vert.glsl", "loa_unsharp_blur.frag.glsl"});
    _sigmaUniform = new osg::Uniform("loa_blurSigma", _sigma);
    _rangeUniform = new osg::Uniform("loa_depthRange", osg::Vec2f(1.0f, 1000.0f));
    _orthoUniform = new osg::Uniform("loa_orthographic", false);
    for (unsigned p = 0; p < 2; ++p)
    {
        _camera[p] =
            detail::createPassCamera(firstRenderOrder + int(p), osg::Vec4(0, 0, 0, 0), GL_COLOR_BUFFER_BIT);
        _camera[p]->setName(p == 0 ? "osgLoA.DepthUnsharpMask.x" : "osgLoA.DepthUnsharpMask.y");
        _result[p] = detail::createTargetTexture(GL_RG32F, GL_RG, GL_FLOAT);
        _camera[p]->attach(osg::Camera::COLOR_BUFFER0, _result[p].get());
        osg::ref_ptr<osg::Geode> quad = new osg::Geode;
        quad->setCullingActive(false);
        quad->addDrawable(detail::createFullScreenTriangle().get());
        _camera[p]->addChild(quad.get());
        osg::StateSet* ss = _camera[p]->getOrCreateStateSet();
        ss->setAttributeAndModes(program.get(), osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE);
        ss->setMode(GL_DEPTH_TEST, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);
        ss->setMode(GL_BLEND, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);
        ss->addUniform(new osg::Uniform("loa_blurInput", 0));
        ss->addUniform(new osg::Uniform("loa_blurCoverage", 1));
        ss->addUniform(new osg::Uniform("loa_blurFirstPass", p == 0));
        ss->addUniform(new osg::Uniform("loa_blurDirection", p == 0 ? osg::Vec2f(1, 0) : osg::Vec2f(0, 1)));
        ss->addUniform(_sigmaUniform.get());
        ss->addUniform(_rangeUniform.get());
        ss->addUniform(_orthoUniform.get());
    }
    _camera[1]->getOrCreateStateSet()->setTextureAttribute(0, _result[0].get(),
                                                           osg::StateAttribute::OVERRIDE);
}

void DepthUnsharpMask::setInput(osg::Texture2D* depth, osg::Texture2D* coverage)
{
    osg::StateSet* ss = _camera[0]->getOrCreateStateSet();
    ss->setTextureAttribute(0, depth, osg::StateAttribute::OVERRIDE);
    ss->setTextureAttribute(1, coverage, osg::StateAttribute::OVERRIDE);
}

void DepthUnsharpMask::setSize(int width, int height)
{
    for (unsigned p = 0; p < 2; ++p)
        detail::resizeTargets(*_camera[p], {_result[p].get()}, width, height);
}

void DepthUnsharpMask::setSigma(float pixels)
{
    if (!(pixels > 0.0f) || pixels > 64.0f)
        throw std::invalid_argument("DepthUnsharpMask: sigma must be in (0, 64] pixels, got " +
                                    std::to_string(pixels));
    _sigma = pixels;
    _sigmaUniform->set(pixels);
}

void DepthUnsharpMask::setDepthRange(float nearPlane, float farPlane, bool orthographic)
{
    _rangeUniform->set(osg::Vec2f(nearPlane, farPlane));
    _orthoUniform->set(orthographic);
}

double DepthUnsharpMask::memoryBytes(int width, int height)
{
    return 2.0 * double(width) * height * detail::bytesPerTexel(GL_RG32F);
}

} // namespace osgLoA
