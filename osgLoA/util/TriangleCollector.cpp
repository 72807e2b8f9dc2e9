/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include "TriangleCollector.h"

#include <osg/Drawable>
#include <osg/Transform>
#include <osg/TriangleFunctor>

namespace osgLoA
{

namespace
{
struct TriangleSink
{
    std::vector<osg::Vec3d>* out = nullptr;
    osg::Matrixd matrix;
    void operator()(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c)
    {
        out->push_back(osg::Vec3d(a) * matrix);
        out->push_back(osg::Vec3d(b) * matrix);
        out->push_back(osg::Vec3d(c) * matrix);
    }
};
} // namespace

TriangleCollector::TriangleCollector(const osg::Matrixd& start, TraversalMode mode) : osg::NodeVisitor(mode)
{
    _stack.push_back(start);
}

void TriangleCollector::apply(osg::Transform& t)
{
    osg::Matrixd m = _stack.back();
    t.computeLocalToWorldMatrix(m, this);
    _stack.push_back(m);
    traverse(t);
    _stack.pop_back();
}

void TriangleCollector::apply(osg::Drawable& d)
{
    osg::TriangleFunctor<TriangleSink> f;
    f.out = &_corners;
    f.matrix = _stack.back();
    d.accept(f);
}

} // namespace osgLoA
