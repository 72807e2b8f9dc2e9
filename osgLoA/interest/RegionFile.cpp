// RegionFile: user regions of interest from GeoJSON (and other OGR formats) through GDAL, whose
// reader lives in the module libosgLoA_gdal (gdal/RegionFileModule.cpp), loaded on the first read.
#include <osgLoA/interest/RegionFile>

#include "../util/LazyModule.h"

#include <stdexcept>

namespace osgLoA
{

std::vector<osg::ref_ptr<RegionOfInterest>> RegionFile::read(const std::string& path, const osg::Node* model,
                                                             double radius, Coordinates coordinates)
{
#ifndef OSGLOA_WITH_GDAL
    // Built without GDAL (OSGLOA_WITH_GDAL=OFF, scripts/device-bench): no vector formats to read.
    (void)model;
    (void)radius;
    (void)coordinates;
    throw std::runtime_error("regions '" + path +
                             "': osgLoA was built without GDAL (OSGLOA_WITH_GDAL=OFF), "
                             "so it reads no region files");
#else
    using ReadFn = void (*)(const std::string*, const osg::Node*, double, int,
                            std::vector<osg::ref_ptr<RegionOfInterest>>*);
    const auto readRegions =
        reinterpret_cast<ReadFn>(lazyModuleSymbol("osgLoA_gdal", "osgLoA_gdal_readRegions"));
    std::vector<osg::ref_ptr<RegionOfInterest>> regions;
    readRegions(&path, model, radius, int(coordinates), &regions);
    return regions;
#endif
}

} // namespace osgLoA
