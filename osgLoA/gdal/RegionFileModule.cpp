// libosgLoA_gdal: osgLoA::RegionFile's GDAL reader (regions of interest from GeoJSON and the other
// OGR vector formats), in a module of its own that libosgLoA loads beside itself on the first
// region file it reads (interest/RegionFile.cpp): GDAL's 113 shared libraries cost every process
// 0.08 s at start when libosgLoA linked them.
#include <osgLoA/interest/RegionFile>

#include <osg/ValueObject>
#include <osgDB/FileNameUtils>

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>
#include <stdexcept>

namespace osgLoA
{

namespace
{
struct DatasetCloser
{
    void operator()(GDALDataset* d) const { GDALClose(d); }
};
struct TransformDeleter
{
    void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};

class Reader
{
public:
    Reader(const std::string& path, double radius, OGRCoordinateTransformation* toModel,
           const osg::Vec3d& origin)
        : _path(path), _radius(radius), _toModel(toModel), _origin(origin)
    {
    }

    void add(const OGRGeometry* g, const std::string& name)
    {
        if (!g) return;
        switch (wkbFlatten(g->getGeometryType()))
        {
        case wkbPoint:
        {
            RegionOfInterest::Vertices v{point(g->toPoint()->getX(), g->toPoint()->getY())};
            push(RegionOfInterest::CIRCLES, v, name);
            break;
        }
        case wkbLineString:
            push(RegionOfInterest::POLYLINE, ring(g->toLineString()), name);
            break;
        case wkbPolygon:
        {
            const OGRLinearRing* outer = g->toPolygon()->getExteriorRing();
            if (!outer) break;
            RegionOfInterest::Vertices v = ring(outer);
            if (v.size() > 1 && v.front() == v.back()) v.pop_back(); // closed implicitly
            push(RegionOfInterest::POLYGON, v, name);
            break;
        }
        case wkbMultiPoint:
        {
            RegionOfInterest::Vertices v;
            for (const OGRGeometry* p : *g->toMultiPoint())
                v.push_back(point(p->toPoint()->getX(), p->toPoint()->getY()));
            push(RegionOfInterest::CIRCLES, v, name);
            break;
        }
        case wkbMultiLineString:
        case wkbMultiPolygon:
        case wkbGeometryCollection:
            for (const OGRGeometry* part : *g->toGeometryCollection())
                add(part, name);
            break;
        default:
            throw std::runtime_error("regions '" + _path + "': geometry type " +
                                     OGRGeometryTypeToName(g->getGeometryType()) +
                                     " is not a point, line or polygon");
        }
    }

    void setTransform(OGRCoordinateTransformation* t) { _toModel = t; }

    std::vector<osg::ref_ptr<RegionOfInterest>> regions;

private:
    osg::Vec2d point(double x, double y)
    {
        if (_toModel && !_toModel->Transform(1, &x, &y))
            throw std::runtime_error("regions '" + _path +
                                     "': a coordinate cannot be transformed to the model's "
                                     "reference system");
        return osg::Vec2d(x - _origin.x(), y - _origin.y());
    }
    RegionOfInterest::Vertices ring(const OGRSimpleCurve* c)
    {
        RegionOfInterest::Vertices v;
        for (int i = 0; i < c->getNumPoints(); ++i)
            v.push_back(point(c->getX(i), c->getY(i)));
        return v;
    }
    void push(RegionOfInterest::Shape shape, const RegionOfInterest::Vertices& v, const std::string& name)
    {
        osg::ref_ptr<RegionOfInterest> r = new RegionOfInterest(shape, v, _radius);
        r->setName(name.empty() ? osgDB::getStrippedName(_path) + "-" + std::to_string(regions.size() + 1)
                                : name);
        const std::string problem = r->validate();
        if (!problem.empty()) throw std::runtime_error("regions '" + _path + "': " + problem);
        regions.push_back(r);
    }

    std::string _path;
    double _radius;
    OGRCoordinateTransformation* _toModel;
    osg::Vec3d _origin;
};
} // namespace

namespace
{
std::vector<osg::ref_ptr<RegionOfInterest>> readRegions(const std::string& path, const osg::Node* model,
                                                        double radius, RegionFile::Coordinates coordinates)
{
    if (!(radius >= 0.0) || !std::isfinite(radius))
        throw std::invalid_argument("regions '" + path + "': the radius must be finite and >= 0");
    GDALAllRegister();
    std::unique_ptr<GDALDataset, DatasetCloser> ds(static_cast<GDALDataset*>(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds)
        throw std::runtime_error("regions '" + path + "': cannot open it as vector data (" +
                                 std::string(CPLGetLastErrorMsg()) + ")");
    std::string crs;
    osg::Vec3d origin;
    const bool georeferenced = model && model->getUserValue("loa.crs", crs) && !crs.empty();
    if (georeferenced) model->getUserValue("loa.origin", origin);
    const bool geographic =
        coordinates == RegionFile::GEOGRAPHIC || (coordinates == RegionFile::AUTOMATIC && georeferenced);
    if (geographic && !georeferenced)
        throw std::runtime_error("regions '" + path +
                                 "': geographic coordinates need a geo-referenced model "
                                 "(user value loa.crs), and the model has none");
    Reader reader(path, radius, nullptr, geographic ? origin : osg::Vec3d());
    for (OGRLayer* layer : ds->GetLayers())
    {
        std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> toModel;
        if (geographic)
        {
            OGRSpatialReference source, target;
            if (const OGRSpatialReference* s = layer->GetSpatialRef())
                source = *s;
            else
                source.SetWellKnownGeogCS("WGS84"); // RFC 7946
            source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            if (target.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
                throw std::runtime_error("regions '" + path + "': the model's reference system '" + crs +
                                         "' is not one GDAL knows");
            target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            toModel.reset(OGRCreateCoordinateTransformation(&source, &target));
            if (!toModel)
                throw std::runtime_error("regions '" + path +
                                         "': no transformation to the model's reference system");
        }
        reader.setTransform(toModel.get());
        for (auto& feature : *layer)
        {
            const int nameField = feature->GetFieldIndex("name");
            const std::string name = nameField >= 0 && feature->IsFieldSetAndNotNull(nameField)
                                         ? feature->GetFieldAsString(nameField)
                                         : "";
            reader.add(feature->GetGeometryRef(), name);
        }
        reader.setTransform(nullptr);
    }
    if (reader.regions.empty())
        throw std::runtime_error("regions '" + path + "': no point, line or polygon in it");
    return reader.regions;
}
} // namespace

} // namespace osgLoA

/** RegionFile::read's work; its exceptions (std::invalid_argument, std::runtime_error) reach the
 *  caller in libosgLoA unchanged. */
extern "C" __attribute__((visibility("default"))) void
osgLoA_gdal_readRegions(const std::string* path, const osg::Node* model, double radius, int coordinates,
                        std::vector<osg::ref_ptr<osgLoA::RegionOfInterest>>* out)
{
    *out =
        osgLoA::readRegions(*path, model, radius, static_cast<osgLoA::RegionFile::Coordinates>(coordinates));
}
