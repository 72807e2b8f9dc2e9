/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#ifndef OSGLOA_UTIL_TRIANGLECOLLECTOR_H
#define OSGLOA_UTIL_TRIANGLECOLLECTOR_H 1

#include <osg/Matrixd>
#include <osg/NodeVisitor>
#include <osg/Vec3d>

#include <vector>

namespace osgLoA
{

/** Collects the triangles of the drawables under the node it visits (osg::TriangleFunctor: strips,
 *  fans and quads split), transformed by the matrix the traversal starts with and every
 *  osg::Transform below: three corners per triangle in corners(). Used where the library needs a
 *  scene's geometry on the CPU (ViewpointEntropy's best views, Waterlining's shoreline map). */
class TriangleCollector : public osg::NodeVisitor
{
public:
    explicit TriangleCollector(const osg::Matrixd& start, TraversalMode mode = TRAVERSE_ACTIVE_CHILDREN);

    void apply(osg::Transform& t) override;
    void apply(osg::Drawable& d) override;

    const std::vector<osg::Vec3d>& corners() const { return _corners; }
    std::vector<osg::Vec3d>& corners() { return _corners; }

private:
    std::vector<osg::Matrixd> _stack;
    std::vector<osg::Vec3d> _corners;
};

/** Collects the vertex indices of the triangles an osg::TriangleIndexFunctor<TriangleIndexList>
 *  visits (strips, fans, quads and polygons split), three per triangle, into *out. */
struct TriangleIndexList
{
    std::vector<unsigned>* out = nullptr;
    void operator()(unsigned a, unsigned b, unsigned c)
    {
        out->push_back(a);
        out->push_back(b);
        out->push_back(c);
    }
};

} // namespace osgLoA

#endif
