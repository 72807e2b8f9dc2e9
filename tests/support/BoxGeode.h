// A box as points, shared by the gtest support library and the fuzz targets (which do not
// link gtest): header-only.
#ifndef OSGLOA_TESTS_SUPPORT_BOXGEODE_H
#define OSGLOA_TESTS_SUPPORT_BOXGEODE_H 1

#include <osg/Geode>
#include <osg/Geometry>

namespace loatest
{

/** A Geode whose one Geometry holds the 8 corners of the box as points, so that its bound is
 *  exactly the box (scenario tests place features by their boxes). */
inline osg::ref_ptr<osg::Geode> boxGeode(const osg::Vec3& minimum, const osg::Vec3& maximum)
{
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (int i = 0; i < 8; ++i)
        v->push_back(osg::Vec3(i & 1 ? maximum.x() : minimum.x(), i & 2 ? maximum.y() : minimum.y(),
                               i & 4 ? maximum.z() : minimum.z()));
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_POINTS, 0, 8));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(g.get());
    return geode;
}

} // namespace loatest

#endif
