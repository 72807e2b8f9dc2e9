// DepthUnsharpMask: alpha-weighted Gaussian of the front depth at a reduced resolution, for
// unsharp masking.
#include <osgLoA/compositing/DepthUnsharpMask>

#include <osgLoA/render/ShaderLibrary>

#include "RenderTarget.h"

#include <osg/Geode>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace osgLoA
{

namespace
{
int reduced(int size, int factor)
{
    return std::max(1, (size + factor - 1) / factor);
}
} // namespace

int DepthUnsharpMask::downsampleFactor(float sigma)
{
    return std::clamp(int(std::floor(sigma / 2.0f)), 1, 8);
}

DepthUnsharpMask::DepthUnsharpMask(int firstRenderOrder)
{
    osg::ref_ptr<osg::Program> program =
        ShaderLibrary::createProgram("unsharp-blur", {"loa_compose.vert.glsl", "loa_unsharp_blur.frag.glsl"});
    _sigmaUniform = new osg::Uniform("loa_blurSigma", _sigma);
    _factorUniform = new osg::Uniform("loa_blurFactor", 1);
    _rangeUniform = new osg::Uniform("loa_depthRange", osg::Vec2f(1.0f, 1000.0f));
    _orthoUniform = new osg::Uniform("loa_orthographic", false);
    _resultScale = new osg::Uniform("loa_unsharpScaleToTexture", osg::Vec2f(1.0f, 1.0f));
    for (osg::Uniform* u : {_sigmaUniform.get(), _factorUniform.get(), _rangeUniform.get(),
                            _orthoUniform.get(), _resultScale.get()})
        u->setDataVariance(osg::Object::DYNAMIC);
    const char* names[NUM_PASSES] = {"osgLoA.DepthUnsharpMask.reduce", "osgLoA.DepthUnsharpMask.x",
                                     "osgLoA.DepthUnsharpMask.y"};
    for (unsigned p = 0; p < NUM_PASSES; ++p)
    {
        _camera[p] =
            detail::createPassCamera(firstRenderOrder + int(p), osg::Vec4(0, 0, 0, 0), GL_COLOR_BUFFER_BIT);
        _camera[p]->setName(names[p]);
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
        ss->addUniform(new osg::Uniform("loa_blurPass", int(p)));
        ss->addUniform(new osg::Uniform("loa_blurDirection", p == 1 ? osg::Vec2f(1, 0) : osg::Vec2f(0, 1)));
        ss->addUniform(_sigmaUniform.get());
        ss->addUniform(_factorUniform.get());
        ss->addUniform(_rangeUniform.get());
        ss->addUniform(_orthoUniform.get());
        if (p > 0) ss->setTextureAttribute(0, _result[p - 1].get(), osg::StateAttribute::OVERRIDE);
    }
    // The compositing upsamples the last pass bilinearly.
    _result[NUM_PASSES - 1]->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR);
    _result[NUM_PASSES - 1]->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
}

void DepthUnsharpMask::setInput(osg::Texture2D* depth, osg::Texture2D* coverage)
{
    osg::StateSet* ss = _camera[0]->getOrCreateStateSet();
    ss->setTextureAttribute(0, depth, osg::StateAttribute::OVERRIDE);
    ss->setTextureAttribute(1, coverage, osg::StateAttribute::OVERRIDE);
}

void DepthUnsharpMask::resize()
{
    const int f = downsampleFactor(_sigma);
    const int w = reduced(_width, f), h = reduced(_height, f);
    for (unsigned p = 0; p < NUM_PASSES; ++p)
        detail::resizeTargets(*_camera[p], {_result[p].get()}, w, h);
    _factorUniform->set(f);
    _resultScale->set(osg::Vec2f(float(f * w), float(f * h)));
}

void DepthUnsharpMask::setSize(int width, int height)
{
    _width = std::max(1, width);
    _height = std::max(1, height);
    resize();
}

void DepthUnsharpMask::setSigma(float pixels)
{
    if (!(pixels > 0.0f) || pixels > 64.0f)
        throw std::invalid_argument("DepthUnsharpMask: sigma must be in (0, 64] pixels, got " +
                                    std::to_string(pixels));
    _sigma = pixels;
    _sigmaUniform->set(pixels);
    resize();
}

void DepthUnsharpMask::setDepthRange(float nearPlane, float farPlane, bool orthographic)
{
    _rangeUniform->set(osg::Vec2f(nearPlane, farPlane));
    _orthoUniform->set(orthographic);
}

double DepthUnsharpMask::memoryBytes(int width, int height, float sigma)
{
    const int f = downsampleFactor(sigma);
    return double(NUM_PASSES) * reduced(width, f) * reduced(height, f) * detail::bytesPerTexel(GL_RG32F);
}

} // namespace osgLoA
