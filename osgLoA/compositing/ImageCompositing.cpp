// ImageCompositing: Algorithm 2 of paper 004 with edges and depth unsharp masking.
#include <osgLoA/compositing/ImageCompositing>

#include <osgLoA/render/ShaderLibrary>

#include "RenderTarget.h"

#include <osg/BlendFunc>
#include <osg/Depth>
#include <osg/Geode>

namespace osgLoA
{

namespace
{
osg::Uniform* sampler(osg::StateSet& ss, const char* name, int unit)
{
    osg::ref_ptr<osg::Uniform> u = new osg::Uniform(name, unit);
    ss.addUniform(u.get());
    return u.get();
}
} // namespace

ImageCompositing::ImageCompositing()
{
    _switch = new osg::Switch;
    _switch->setName("osgLoA.ImageCompositing");
    _switch->setCullingActive(false);
    for (bool aBuffer : {false, true})
    {
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->setName(aBuffer ? "osgLoA.ImageCompositing.abuffer" : "osgLoA.ImageCompositing.opaque");
        geode->setCullingActive(false);
        geode->addDrawable(detail::createFullScreenTriangle().get());
        if (aBuffer) geode->getOrCreateStateSet()->setDefine("LOA_USE_ABUFFER");
        _switch->addChild(geode.get(), !aBuffer);
    }
    osg::StateSet* ss = _switch->getOrCreateStateSet();
    ss->setDataVariance(osg::Object::DYNAMIC);
    setFetchShader("loa_abuffer_fetch_stencil.frag.glsl");
    ss->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA),
                             osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE |
                                 osg::StateAttribute::PROTECTED);
    ss->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false),
                             osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                 osg::StateAttribute::PROTECTED);
    ss->setMode(GL_CULL_FACE,
                osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
    ss->setRenderBinDetails(1000, "RenderBin");
    const char* gNames[] = {"loa_gColor", "loa_gNormal", "loa_gId", "loa_gEdge", "loa_gDepth"};
    for (int t = 0; t < GeometryBuffer::NUM_TARGETS; ++t)
        sampler(*ss, gNames[t], int(kFirstUnit) + t);
    sampler(*ss, "loa_unsharpBlur", 6);
    sampler(*ss, "loa_pingColor0", 8);
    sampler(*ss, "loa_pingDepth0", 9);
    sampler(*ss, "loa_pingColor1", 10);
    sampler(*ss, "loa_pingDepth1", 11);
    _usePingPong = new osg::Uniform("loa_usePingPong", false);
    _useEdges = new osg::Uniform("loa_useEdges", false);
    _useUnsharp = new osg::Uniform("loa_useUnsharp", false);
    _range = new osg::Uniform("loa_depthRange", osg::Vec2f(1.0f, 1000.0f));
    _ortho = new osg::Uniform("loa_orthographic", false);
    _merge = new osg::Uniform("loa_mergeEpsilon", 2.0e-6f);
    _origin = new osg::Uniform("loa_viewportOrigin", 0, 0);
    for (osg::Uniform* u : {_usePingPong.get(), _useEdges.get(), _useUnsharp.get(), _range.get(),
                            _ortho.get(), _merge.get(), _origin.get()})
    {
        u->setDataVariance(osg::Object::DYNAMIC);
        ss->addUniform(u);
    }
}

void ImageCompositing::setFetchShader(const std::string& name)
{
    if (name == _fetchShader) return;
    _fetchShader = name;
    getStateSet()->setAttributeAndModes(
        ShaderLibrary::createProgram("compose", {"loa_compose.vert.glsl", "loa_compose.frag.glsl",
                                                 "loa_abuffer_resolve.frag.glsl", name.c_str()})
            .get(),
        osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED);
}

void ImageCompositing::setGeometryBuffer(GeometryBuffer* g)
{
    osg::StateSet* ss = getStateSet();
    for (int t = 0; t < GeometryBuffer::NUM_TARGETS; ++t)
        ss->setTextureAttribute(kFirstUnit + unsigned(t), g->getTexture(GeometryBuffer::Target(t)));
}

void ImageCompositing::setPingPongBuffer(PingPongBuffer* p)
{
    osg::StateSet* ss = getStateSet();
    for (unsigned t = 0; t < 2; ++t)
    {
        ss->setTextureAttribute(8 + 2 * t, p->getColorTexture(t));
        ss->setTextureAttribute(9 + 2 * t, p->getDepthTexture(t));
    }
}

void ImageCompositing::setDepthUnsharpMask(DepthUnsharpMask* u)
{
    getStateSet()->setTextureAttribute(6, u->getResult());
    getStateSet()->addUniform(u->getResultScaleUniform());
}

void ImageCompositing::setInputs(bool aBuffer, bool pingPong, bool edges, bool unsharp)
{
    _switch->setSingleChildOn(aBuffer ? 1u : 0u);
    _usePingPong->set(pingPong);
    _useEdges->set(edges);
    _useUnsharp->set(unsharp);
}

void ImageCompositing::setDepthRange(float nearPlane, float farPlane, bool orthographic)
{
    _range->set(osg::Vec2f(nearPlane, farPlane));
    _ortho->set(orthographic);
}

void ImageCompositing::setMergeEpsilon(float epsilon)
{
    _merge->set(epsilon);
}

void ImageCompositing::setViewportOrigin(int x, int y)
{
    _origin->set(x, y);
}

} // namespace osgLoA
