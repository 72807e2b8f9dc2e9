#include "MeshBuilder.h"

#include <utility>

namespace osgLoA
{
namespace detail
{

MeshBuilder::MeshBuilder()
    : _vertices(new osg::Vec3Array), _normals(new osg::Vec3Array), _texCoords(new osg::Vec2Array),
      _colors(new osg::Vec4Array), _indices(new osg::DrawElementsUInt(GL_TRIANGLES))
{
}

unsigned MeshBuilder::vertex(const osg::Vec3& p, const osg::Vec3& n, const osg::Vec2& uv)
{
    _vertices->push_back(p);
    _normals->push_back(n);
    _texCoords->push_back(uv);
    _colors->push_back(color);
    return static_cast<unsigned>(_vertices->size() - 1);
}

void MeshBuilder::triangleIndices(unsigned a, unsigned b, unsigned c)
{
    _indices->push_back(a);
    _indices->push_back(b);
    _indices->push_back(c);
}

void MeshBuilder::triangle(osg::Vec3 p0, osg::Vec3 p1, osg::Vec3 p2, osg::Vec2 t0, osg::Vec2 t1, osg::Vec2 t2,
                           const osg::Vec3* outwardFrom)
{
    osg::Vec3 n = (p1 - p0) ^ (p2 - p0);
    if (n.length2() <= 0.0f) return; // degenerate: nothing to draw
    if (outwardFrom && n * ((p0 + p1 + p2) / 3.0f - *outwardFrom) < 0.0f)
    {
        std::swap(p1, p2);
        std::swap(t1, t2);
        n = -n;
    }
    n.normalize();
    const unsigned a = vertex(p0, n, t0), b = vertex(p1, n, t1), c = vertex(p2, n, t2);
    triangleIndices(a, b, c);
}

void MeshBuilder::quad(const osg::Vec3 p[4], const osg::Vec2 t[4], const osg::Vec3* outwardFrom)
{
    osg::Vec3 n = (p[1] - p[0]) ^ (p[2] - p[0]);
    if (n.length2() <= 0.0f) n = (p[2] - p[0]) ^ (p[3] - p[0]);
    if (n.length2() <= 0.0f) return;
    const bool flip = outwardFrom && n * ((p[0] + p[1] + p[2] + p[3]) / 4.0f - *outwardFrom) < 0.0f;
    if (flip) n = -n;
    n.normalize();
    unsigned i[4];
    for (int k = 0; k < 4; ++k)
        i[k] = vertex(p[k], n, t[k]);
    if (flip)
    {
        triangleIndices(i[0], i[2], i[1]);
        triangleIndices(i[0], i[3], i[2]);
    }
    else
    {
        triangleIndices(i[0], i[1], i[2]);
        triangleIndices(i[0], i[2], i[3]);
    }
}

osg::ref_ptr<osg::Geometry> MeshBuilder::build(const std::string& name) const
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    g->setName(name);
    g->setUseDisplayList(false);
    g->setUseVertexBufferObjects(true);
    g->setVertexArray(_vertices.get());
    g->setNormalArray(_normals.get(), osg::Array::BIND_PER_VERTEX);
    g->setTexCoordArray(0, _texCoords.get(), osg::Array::BIND_PER_VERTEX);
    bool uniform = true;
    for (const auto& c : *_colors)
        if (c != _colors->front())
        {
            uniform = false;
            break;
        }
    if (uniform && !_colors->empty())
    {
        osg::ref_ptr<osg::Vec4Array> one = new osg::Vec4Array;
        one->push_back(_colors->front());
        g->setColorArray(one.get(), osg::Array::BIND_OVERALL);
    }
    else
        g->setColorArray(_colors.get(), osg::Array::BIND_PER_VERTEX);
    g->addPrimitiveSet(_indices.get());
    return g;
}

} // namespace detail
} // namespace osgLoA
