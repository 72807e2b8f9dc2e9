// PingPongBuffer: two opaque colour+depth targets for features of high depth complexity.
#include <osgLoA/compositing/PingPongBuffer>

#include "RenderTarget.h"

namespace osgLoA
{

PingPongBuffer::PingPongBuffer(int firstRenderOrder)
{
    for (unsigned t = 0; t < 2; ++t)
    {
        _camera[t] = detail::createPassCamera(firstRenderOrder + int(t), osg::Vec4(0, 0, 0, 0),
                                              GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        _camera[t]->setName(t == 0 ? "osgLoA.PingPongBuffer.0" : "osgLoA.PingPongBuffer.1");
        _color[t] = detail::createTargetTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
        _depth[t] = detail::createTargetTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
        _camera[t]->attach(osg::Camera::COLOR_BUFFER0, _color[t].get());
        _camera[t]->attach(osg::Camera::DEPTH_BUFFER, _depth[t].get());
    }
}

void PingPongBuffer::setSize(int width, int height)
{
    for (unsigned t = 0; t < 2; ++t)
        detail::resizeTargets(*_camera[t], {_color[t].get(), _depth[t].get()}, width, height);
}

double PingPongBuffer::memoryBytes(int width, int height)
{
    return 2.0 * double(width) * height *
           (detail::bytesPerTexel(GL_RGBA8) + detail::bytesPerTexel(GL_DEPTH_COMPONENT32F));
}

} // namespace osgLoA
