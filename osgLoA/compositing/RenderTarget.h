// Private: textures and pre-render cameras of the LoA node's image-space passes, sized to the
// viewport and resized in place when it changes.
#ifndef OSGLOA_COMPOSITING_RENDERTARGET_H
#define OSGLOA_COMPOSITING_RENDERTARGET_H 1

#include <osg/Camera>
#include <osg/Geometry>
#include <osg/Texture2D>

#include <vector>

namespace osgLoA
{
namespace detail
{

/** A nearest-filtered, edge-clamped, non-mipmapped 2D texture of the given formats. */
osg::ref_ptr<osg::Texture2D> createTargetTexture(GLint internalFormat, GLenum format, GLenum type);

/** A PRE_RENDER FBO camera with the given render order and clear colour, and a
 *  DO_NOT_COMPUTE_NEAR_FAR, absolute reference frame: the caller sets its matrices each frame. */
osg::ref_ptr<osg::Camera> createPassCamera(int order, const osg::Vec4& clearColor, GLbitfield clearMask);

/** Resizes the textures and the camera's viewport; a no-op when the size is unchanged. Returns
 *  whether it changed anything. */
bool resizeTargets(osg::Camera& camera, const std::vector<osg::Texture2D*>& textures, int width, int height);

/** A triangle that covers the viewport, its vertices in clip space (shaders/loa_compose.vert.glsl),
 *  never culled and without a bound, so it does not change a camera's near and far planes. */
osg::ref_ptr<osg::Geometry> createFullScreenTriangle();

/** Bytes of one texel of a texture's internal format (the formats used here). */
unsigned bytesPerTexel(GLint internalFormat);

} // namespace detail
} // namespace osgLoA

#endif
