// GeometryBuffer: the front-surface G-buffer of the LoA node.
#include <osgLoA/compositing/GeometryBuffer>

#include "RenderTarget.h"

namespace osgLoA
{

GeometryBuffer::GeometryBuffer(int renderOrder)
{
    _camera = detail::createPassCamera(renderOrder, osg::Vec4(0, 0, 0, 0),
                                       GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    _camera->setName("osgLoA.GeometryBuffer");
    for (int t = COLOR; t < DEPTH; ++t)
    {
        _textures[t] = detail::createTargetTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
        _camera->attach(osg::Camera::BufferComponent(osg::Camera::COLOR_BUFFER0 + t), _textures[t].get());
    }
    _textures[DEPTH] = detail::createTargetTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
    _camera->attach(osg::Camera::DEPTH_BUFFER, _textures[DEPTH].get());
}

void GeometryBuffer::setSize(int width, int height)
{
    std::vector<osg::Texture2D*> t;
    for (auto& tex : _textures)
        t.push_back(tex.get());
    detail::resizeTargets(*_camera, t, width, height);
    _width = width;
    _height = height;
}

double GeometryBuffer::memoryBytes(int width, int height)
{
    return double(width) * height *
           (4.0 * detail::bytesPerTexel(GL_RGBA8) + detail::bytesPerTexel(GL_DEPTH_COMPONENT32F));
}

} // namespace osgLoA
