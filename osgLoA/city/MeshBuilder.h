// Private helper of the city generator: accumulates an indexed triangle mesh.
#ifndef OSGLOA_CITY_MESHBUILDER_H
#define OSGLOA_CITY_MESHBUILDER_H 1

#include <osg/Geometry>

#include <string>

namespace osgLoA
{
namespace detail
{

class MeshBuilder
{
public:
    MeshBuilder();

    osg::Vec4 color = osg::Vec4(1.0f, 1.0f, 1.0f, 1.0f);

    unsigned vertex(const osg::Vec3& p, const osg::Vec3& n, const osg::Vec2& uv);
    void triangleIndices(unsigned a, unsigned b, unsigned c);

    /** A flat-shaded triangle; when outwardFrom is given the winding is fixed so the face
     *  points away from that point (closed shapes: pass their centre). */
    void triangle(osg::Vec3 p0, osg::Vec3 p1, osg::Vec3 p2, osg::Vec2 t0, osg::Vec2 t1, osg::Vec2 t2,
                  const osg::Vec3* outwardFrom = nullptr);
    /** A flat-shaded planar quad p0..p3, split along p0-p2. */
    void quad(const osg::Vec3 p[4], const osg::Vec2 t[4], const osg::Vec3* outwardFrom = nullptr);

    bool empty() const { return _indices->empty(); }
    unsigned numVertices() const { return static_cast<unsigned>(_vertices->size()); }

    /** The geometry (VBOs, no display lists), named after a CityGML surface. */
    osg::ref_ptr<osg::Geometry> build(const std::string& name) const;

private:
    osg::ref_ptr<osg::Vec3Array> _vertices;
    osg::ref_ptr<osg::Vec3Array> _normals;
    osg::ref_ptr<osg::Vec2Array> _texCoords;
    osg::ref_ptr<osg::Vec4Array> _colors;
    osg::ref_ptr<osg::DrawElementsUInt> _indices;
};

} // namespace detail
} // namespace osgLoA

#endif
