/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#ifndef OSGLOA_UTIL_FEATUREGROUNDRASTER_H
#define OSGLOA_UTIL_FEATUREGROUNDRASTER_H 1

#include <osgLoA/interest/DistanceField>
#include <osgLoA/semantics/FeatureType>

#include <osg/Node>
#include <osg/Texture2D>
#include <osg/Vec3d>

#include <cstddef>
#include <string>
#include <vector>

namespace osgLoA
{

/** The triangles of a model's features of one type, in world coordinates, as the cartographic
 *  styles' ground maps need them (Waterlining's shoreline, GreenSpaceSignatures' ground): faces
 *  without a ground footprint (walls) are skipped, and a feature nested in one of its own type is
 *  collected with it. */
struct FeatureTriangles
{
    std::vector<osg::Vec3d> corners; ///< three per triangle
    unsigned features = 0;           ///< features of the type found
};
FeatureTriangles collectFeatureTriangles(osg::Node& model, FeatureType type);

/** For every texel centre of the grid inside a (closed) triangle of `tris` (x/y footprint), the
 *  surface height there, combined into `cells` (row 0 lowest y) by `highest` (max) or not
 *  (min). Texels no triangle covers keep their value. */
void rasterizeHeights(const DistanceField::Grid& grid, const std::vector<osg::Vec3d>& tris, bool highest,
                      std::vector<double>& cells);

/** A single-channel float texture (GL_R32F) of a grid's values (row 0 lowest y), clamped to its
 *  edge, without mipmaps; GL_LINEAR or GL_NEAREST. */
osg::ref_ptr<osg::Texture2D> createGridTexture(const DistanceField::Grid& grid,
                                               const std::vector<float>& values, const std::string& name,
                                               bool linear);

} // namespace osgLoA

#endif
