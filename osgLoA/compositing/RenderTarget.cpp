// Private: textures and pre-render cameras of the LoA node's image-space passes.
#include "RenderTarget.h"

namespace osgLoA
{
namespace detail
{

osg::ref_ptr<osg::Texture2D> createTargetTexture(GLint internalFormat, GLenum format, GLenum type)
{
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D;
    t->setInternalFormat(internalFormat);
    t->setSourceFormat(format);
    t->setSourceType(type);
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::CLAMP_TO_EDGE);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::CLAMP_TO_EDGE);
    t->setResizeNonPowerOfTwoHint(false);
    t->setUseHardwareMipMapGeneration(false);
    t->setTextureSize(1, 1);
    return t;
}

osg::ref_ptr<osg::Camera> createPassCamera(int order, const osg::Vec4& clearColor, GLbitfield clearMask)
{
    osg::ref_ptr<osg::Camera> c = new osg::Camera;
    c->setRenderOrder(osg::Camera::PRE_RENDER, order);
    c->setRenderTargetImplementation(osg::Camera::FRAME_BUFFER_OBJECT);
    c->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    c->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    c->setClearColor(clearColor);
    c->setClearMask(clearMask);
    c->setViewport(0, 0, 1, 1);
    c->setAllowEventFocus(false);
    return c;
}

bool resizeTargets(osg::Camera& camera, const std::vector<osg::Texture2D*>& textures, int width, int height)
{
    const osg::Viewport* vp = camera.getViewport();
    if (vp && int(vp->width()) == width && int(vp->height()) == height) return false;
    for (osg::Texture2D* t : textures)
    {
        t->setTextureSize(width, height);
        t->dirtyTextureObject();
    }
    camera.setViewport(0, 0, width, height);
    camera.dirtyAttachmentMap();
    return true;
}

namespace
{
struct NoBound : public osg::Drawable::ComputeBoundingBoxCallback
{
    osg::BoundingBox computeBound(const osg::Drawable&) const override { return osg::BoundingBox(); }
};
} // namespace

osg::ref_ptr<osg::Geometry> createFullScreenTriangle()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(-1.0f, -1.0f, 0.0f));
    v->push_back(osg::Vec3(3.0f, -1.0f, 0.0f));
    v->push_back(osg::Vec3(-1.0f, 3.0f, 0.0f));
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
    g->setUseDisplayList(false);
    g->setUseVertexBufferObjects(true);
    g->setCullingActive(false);
    g->setComputeBoundingBoxCallback(new NoBound);
    return g;
}

unsigned bytesPerTexel(GLint internalFormat)
{
    switch (internalFormat)
    {
    case GL_RGBA8:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
    case GL_R32F:
        return 4;
    case GL_RG32F:
        return 8;
    case GL_RGBA16F:
        return 8;
    case GL_RGBA32F:
        return 16;
    default:
        return 4;
    }
}

} // namespace detail
} // namespace osgLoA
