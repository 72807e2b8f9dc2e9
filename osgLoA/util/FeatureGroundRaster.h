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
    /** Per collected feature: its root node and the index in corners where its triangles begin
     *  (they end where the next one's begin). */
    struct Part
    {
        osg::ref_ptr<osg::Node> node;
        std::size_t begin = 0;
    };
    std::vector<Part> parts;
};
FeatureTriangles collectFeatureTriangles(osg::Node& model, FeatureType type);

/** Throws std::invalid_argument naming `who` ("waterlining: resolution 2 is not in 3..4096") for
 *  a resolution outside 3..DistanceField::kMaxResolution or a minimum texel size that is not
 *  finite and >= 0. */
void checkGridParameters(const char* who, int resolution, double minTexelSize);

/** The grid over the triangles' ground footprint (x/y): texel = the larger extent / (resolution -
 *  2), at least minTexelSize, with one texel of margin on every side. Invalid when the triangles
 *  have no footprint. extent, when given, receives the larger extent. */
DistanceField::Grid footprintGrid(const std::vector<osg::Vec3d>& corners, int resolution, double minTexelSize,
                                  double* extent = nullptr);

/** For every texel centre of the grid inside a (closed) triangle of `tris` (x/y footprint), the
 *  surface height there, combined into `cells` (row 0 lowest y) by `highest` (max) or not
 *  (min). Texels no triangle covers keep their value. */
void rasterizeHeights(const DistanceField::Grid& grid, const std::vector<osg::Vec3d>& tris, bool highest,
                      std::vector<double>& cells);

/** A grid's values sampled bilinearly at a world x/y, as a GL_LINEAR fetch with clamp-to-edge
 *  reads them (texel centres at i + 1/2). */
float sampleBilinear(const DistanceField::Grid& grid, const std::vector<float>& values, double x, double y);

/** A single-channel float texture (GL_R32F) of a grid's values (row 0 lowest y), clamped to its
 *  edge, without mipmaps; GL_LINEAR or GL_NEAREST. */
osg::ref_ptr<osg::Texture2D> createGridTexture(const DistanceField::Grid& grid,
                                               const std::vector<float>& values, const std::string& name,
                                               bool linear);

} // namespace osgLoA

#endif
