// osgdb_citygml (and osgdb_gml): reads CityGML 1.0 / 2.0 through Debian's libcitygml
// (docs/citygml.md), the way osgdb_cityjson reads CityJSON:
//   osgviewer city.gml
//   osgviewer city.citygml -O "lod=1 theme=summer recenter=0"
// Each top-level city object becomes a feature (a BuildingPart or BridgePart a nested one),
// typed through osgLoA::CityObjectTypes; thematic surfaces, openings and installations are drawn
// with their object, one drawable per surface type and appearance, named after the surface type.
#include "CityGmlPrescan.h"

#include <osgLoA/semantics/CityObjectTypes>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/Texture2D>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgUtil/SmoothingVisitor>

#include <citygml/citygml.h>
#include <citygml/citygmllogger.h>
#include <citygml/citymodel.h>
#include <citygml/cityobject.h>
#include <citygml/envelope.h>
#include <citygml/geometry.h>
#include <citygml/material.h>
#include <citygml/polygon.h>
#include <citygml/texture.h>

#include <cmath>
#include <map>
#include <sstream>

namespace
{
/** libcitygml's messages go to osg::notify, errors as warnings. */
class Logger : public citygml::CityGMLLogger
{
public:
    Logger() : citygml::CityGMLLogger(LOGLEVEL::LL_WARNING) {}
    void log(LOGLEVEL level, const std::string& message, const char* file, int line) const override
    {
        (void)file;
        (void)line;
        if (level == LOGLEVEL::LL_ERROR || level == LOGLEVEL::LL_WARNING)
        {
            OSG_WARN << "citygml: " << message << std::endl;
        }
        else
        {
            OSG_INFO << "citygml: " << message << std::endl;
        }
        if (level == LOGLEVEL::LL_ERROR) ++errors;
    }
    mutable unsigned errors = 0;
};

struct Settings
{
    int lod = -1; ///< -1: each object's highest
    std::string theme;
    bool recenter = true;
};

/** Types that are parts of their parent object, drawn with it (no feature of their own). */
bool isPart(const std::string& type)
{
    const osgLoA::CityObjectTypes::Entry* e = osgLoA::CityObjectTypes::find(type);
    if (!e) return false;
    const std::string sub = e->subType;
    return sub == "surface" || sub == "opening" || type == "BuildingInstallation" ||
           type == "IntBuildingInstallation" || type == "BridgeInstallation" ||
           type == "BridgeConstructionElement" || type == "TrafficArea" || type == "AuxiliaryTrafficArea";
}

class Builder
{
public:
    Builder(const Settings& s, const std::string& directory, const osgDB::Options* options)
        : _settings(s), _directory(directory), _options(options)
    {
    }

    osg::Vec3d origin;
    unsigned nextId = 1;
    unsigned features = 0;
    std::vector<std::string> missingTextures;

    osg::ref_ptr<osg::Node> object(const citygml::CityObject& o)
    {
        const std::string type = o.getTypeAsString();
        osg::ref_ptr<osg::Group> group = new osg::Group;
        group->setName(o.getId().empty() ? type : o.getId());
        const int lod = _settings.lod >= 0 ? _settings.lod : highestLod(o);
        Batches batches;
        collect(o, lod, type, batches);
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        for (auto& kv : batches)
            if (kv.second.geometry->getNumPrimitiveSets()) geode->addDrawable(finish(kv.second));
        if (geode->getNumDrawables()) group->addChild(geode);
        for (unsigned i = 0; i < o.getChildCityObjectsCount(); ++i)
        {
            const citygml::CityObject& child = o.getChildCityObject(i);
            if (!isPart(child.getTypeAsString())) group->addChild(object(child));
        }
        osg::ref_ptr<osgLoA::Feature> f = new osgLoA::Feature(nextId++, osgLoA::FeatureType::Generic);
        const osgLoA::CityObjectTypes::Entry* e = osgLoA::CityObjectTypes::find(type);
        f->setType(e ? e->type : osgLoA::FeatureType::Generic);
        f->setSubType(e ? e->subType : "");
        f->setSource(e ? osgLoA::Feature::MODEL_DATA : osgLoA::Feature::UNCLASSIFIED);
        f->setSourceType(type);
        if (lod >= 0) f->setLod(float(lod));
        for (const auto& kv : o.getAttributes())
            group->setUserValue("citygml." + kv.first, kv.second.asString());
        osgLoA::Feature::attach(*group, f.get());
        ++features;
        return group;
    }

private:
    struct Batch
    {
        osg::ref_ptr<osg::Geometry> geometry;
        osg::ref_ptr<osg::Vec3Array> vertices;
        osg::ref_ptr<osg::Vec2Array> texCoords;
        osg::ref_ptr<osg::DrawElementsUInt> triangles;
    };
    typedef std::map<std::string, Batch> Batches; // key: surface type + appearance

    static void highest(const citygml::Geometry& g, int& best)
    {
        if (g.getPolygonsCount()) best = std::max(best, int(g.getLOD()));
        for (unsigned i = 0; i < g.getGeometriesCount(); ++i)
            highest(g.getGeometry(i), best);
    }
    static int highestLod(const citygml::CityObject& o)
    {
        int best = -1;
        for (unsigned i = 0; i < o.getGeometriesCount(); ++i)
            highest(o.getGeometry(i), best);
        for (unsigned i = 0; i < o.getChildCityObjectsCount(); ++i)
            if (isPart(o.getChildCityObject(i).getTypeAsString()))
                best = std::max(best, highestLod(o.getChildCityObject(i)));
        return best;
    }

    void collect(const citygml::CityObject& o, int lod, const std::string& surface, Batches& batches)
    {
        for (unsigned i = 0; i < o.getGeometriesCount(); ++i)
            geometry(o.getGeometry(i), lod, surface, batches);
        for (unsigned i = 0; i < o.getChildCityObjectsCount(); ++i)
        {
            const citygml::CityObject& child = o.getChildCityObject(i);
            if (isPart(child.getTypeAsString())) collect(child, lod, child.getTypeAsString(), batches);
        }
    }

    void geometry(const citygml::Geometry& g, int lod, const std::string& surface, Batches& batches)
    {
        for (unsigned i = 0; i < g.getGeometriesCount(); ++i)
            geometry(g.getGeometry(i), lod, surface, batches);
        if (lod >= 0 && int(g.getLOD()) != lod) return;
        for (unsigned i = 0; i < g.getPolygonsCount(); ++i)
            polygon(*g.getPolygon(i), surface, batches);
    }

    void polygon(const citygml::Polygon& p, const std::string& kind, Batches& batches)
    {
        const std::vector<TVec3d>& v = p.getVertices();
        const std::vector<unsigned int>& idx = p.getIndices();
        if (v.empty() || idx.size() < 3) return;
        std::shared_ptr<const citygml::Texture> texture =
            _settings.theme.empty() ? nullptr : p.getTextureFor(_settings.theme);
        std::shared_ptr<const citygml::Material> material =
            _settings.theme.empty() ? nullptr : p.getMaterialFor(_settings.theme);
        std::vector<TVec2f> uv =
            texture ? p.getTexCoordsForTheme(_settings.theme, true) : std::vector<TVec2f>();
        if (uv.size() != v.size())
        {
            uv.clear();
            texture = nullptr;
        }
        const std::string key = kind + "|" + (texture ? "t:" + texture->getUrl() : "") +
                                (material ? "|m:" + material->getId() : "");
        Batch& b = batches[key];
        if (!b.geometry)
        {
            b.geometry = new osg::Geometry;
            b.geometry->setName(kind);
            b.vertices = new osg::Vec3Array;
            b.triangles = new osg::DrawElementsUInt(GL_TRIANGLES);
            b.geometry->setVertexArray(b.vertices);
            b.geometry->addPrimitiveSet(b.triangles);
            if (texture)
            {
                b.texCoords = new osg::Vec2Array;
                b.geometry->setTexCoordArray(0, b.texCoords);
                applyTexture(*b.geometry->getOrCreateStateSet(), *texture);
            }
            if (material) applyMaterial(*b.geometry->getOrCreateStateSet(), *material);
        }
        const unsigned base = unsigned(b.vertices->size());
        for (std::size_t i = 0; i < v.size(); ++i)
        {
            b.vertices->push_back(osg::Vec3(float(v[i].x - origin.x()), float(v[i].y - origin.y()),
                                            float(v[i].z - origin.z())));
            if (b.texCoords.valid()) b.texCoords->push_back(osg::Vec2(uv[i].x, uv[i].y));
        }
        // Triangles with an index out of range or no area (the tesselator keeps a ring's closing
        // vertex and can emit slivers through it) are dropped.
        for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
        {
            const unsigned a = idx[t], c = idx[t + 1], d = idx[t + 2];
            if (a >= v.size() || c >= v.size() || d >= v.size()) continue;
            const TVec3d e1 = v[c] - v[a], e2 = v[d] - v[a];
            const double cx = e1.y * e2.z - e1.z * e2.y, cy = e1.z * e2.x - e1.x * e2.z,
                         cz = e1.x * e2.y - e1.y * e2.x;
            if (cx * cx + cy * cy + cz * cz <= 1e-18) continue;
            b.triangles->push_back(base + a);
            b.triangles->push_back(base + c);
            b.triangles->push_back(base + d);
        }
    }

    osg::Geometry* finish(Batch& b)
    {
        osgUtil::SmoothingVisitor::smooth(*b.geometry, osg::PI / 8.0); // flat facets, no shared normals
        return b.geometry.get();
    }

    void applyTexture(osg::StateSet& ss, const citygml::Texture& t)
    {
        const std::string url = t.getUrl();
        auto it = _textures.find(url);
        if (it == _textures.end())
        {
            osg::ref_ptr<osg::Texture2D> tex;
            const std::string path = osgDB::findDataFile(osgDB::concatPaths(_directory, url), _options);
            osg::ref_ptr<osg::Image> image = path.empty() ? nullptr : osgDB::readRefImageFile(path, _options);
            if (image.valid())
            {
                tex = new osg::Texture2D(image.get());
                const osg::Texture::WrapMode wrap =
                    t.getRepeat() ? osg::Texture::REPEAT : osg::Texture::CLAMP_TO_EDGE;
                tex->setWrap(osg::Texture::WRAP_S, wrap);
                tex->setWrap(osg::Texture::WRAP_T, wrap);
                tex->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
            }
            else
                missingTextures.push_back(url);
            it = _textures.emplace(url, tex).first;
        }
        if (it->second.valid()) ss.setTextureAttributeAndModes(0, it->second.get());
    }

    static void applyMaterial(osg::StateSet& ss, const citygml::Material& m)
    {
        osg::ref_ptr<osg::Material> mat = new osg::Material;
        mat->setName(m.getId());
        const TVec3f d = m.getDiffuse();
        const float alpha = 1.0f - m.getTransparency();
        mat->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(d.x, d.y, d.z, alpha));
        mat->setAmbient(osg::Material::FRONT_AND_BACK,
                        osg::Vec4(d.x, d.y, d.z, alpha) * m.getAmbientIntensity());
        const TVec3f s = m.getSpecular();
        mat->setSpecular(osg::Material::FRONT_AND_BACK, osg::Vec4(s.x, s.y, s.z, 1.0f));
        mat->setShininess(osg::Material::FRONT_AND_BACK, 128.0f * m.getShininess());
        ss.setAttributeAndModes(mat.get());
        if (alpha < 1.0f)
        {
            ss.setMode(GL_BLEND, osg::StateAttribute::ON);
            ss.setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
        }
    }

    Settings _settings;
    std::string _directory;
    const osgDB::Options* _options;
    std::map<std::string, osg::ref_ptr<osg::Texture2D>> _textures;
};

class ReaderWriterCityGml : public osgDB::ReaderWriter
{
public:
    ReaderWriterCityGml()
    {
        supportsExtension("citygml", "CityGML 1.0 / 2.0 city model (libcitygml)");
        supportsExtension("gml", "CityGML 1.0 / 2.0 city model (libcitygml)");
        supportsOption("lod=N", "draw LoD N (0-4) of every object; default: each object's highest");
        supportsOption("theme=NAME", "appearance theme; default: the first the file names");
        supportsOption("recenter=0",
                       "keep world coordinates (default 1: re-centre on the envelope's centre)");
        osgLoA::InputLimits::declareOptions(*this);
    }
    const char* className() const override { return "osgLoA CityGML reader (libcitygml)"; }

    ReadResult readObject(const std::string& fileName, const Options* options) const override
    {
        return readNode(fileName, options);
    }

    ReadResult readNode(const std::string& fileName, const Options* options) const override
    {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(fileName)))
            return ReadResult::FILE_NOT_HANDLED;
        const std::string path = osgDB::findDataFile(fileName, options);
        if (path.empty()) return ReadResult::FILE_NOT_FOUND;
        Settings s;
        if (options)
        {
            std::istringstream in(options->getOptionString());
            for (std::string token; in >> token;)
            {
                const std::size_t eq = token.find('=');
                const std::string key = token.substr(0, eq),
                                  value = eq == std::string::npos ? "" : token.substr(eq + 1);
                if (key == "lod")
                {
                    char* end = nullptr;
                    const long l = std::strtol(value.c_str(), &end, 10);
                    if (value.empty() || *end || l < 0 || l > 4)
                        return ReadResult("citygml: " + path + ": option lod=" + value +
                                          " is not an LoD 0 to 4");
                    s.lod = int(l);
                }
                else if (key == "theme")
                    s.theme = value;
                else if (key == "recenter")
                    s.recenter = value != "0";
            }
        }
        // The limits that apply before libcitygml builds anything (CityGmlPrescan.h).
        try
        {
            const osgLoA::InputLimits limits =
                osgLoA::InputLimits::fromOptions(options ? options->getOptionString() : std::string());
            citygmlimport::prescan(path, "citygml: " + path, limits);
        }
        catch (const osgLoA::InputLimitError& e)
        {
            return ReadResult(e.what());
        }
        catch (const std::exception& e)
        {
            return ReadResult("citygml: " + path + ": " + e.what());
        }
        std::shared_ptr<Logger> logger = std::make_shared<Logger>();
        citygml::ParserParams params;
        params.tesselate = true;
        std::shared_ptr<const citygml::CityModel> model;
        try
        {
            model = citygml::load(path, params, logger);
        }
        catch (const std::exception& e)
        {
            return ReadResult("citygml: " + path + ": " + e.what());
        }
        catch (...) // xerces throws its own exception types
        {
            return ReadResult("citygml: " + path + ": the XML parser failed (a malformed document)");
        }
        if (!model)
            return ReadResult(
                "citygml: " + path + ": not a CityGML document libcitygml can read" +
                (logger->errors ? " (" + std::to_string(logger->errors) + " parser errors above)" : ""));
        if (model->getNumRootCityObjects() == 0)
            return ReadResult("citygml: " + path + ": the document holds no city object");
        if (s.theme.empty() && !model->themes().empty()) s.theme = model->themes().front();

        Builder b(s, osgDB::getFilePath(path), options);
        const citygml::Envelope& env = model->getEnvelope();
        osg::BoundingBoxd box;
        if (env.validBounds())
        {
            box.expandBy(osg::Vec3d(env.getLowerBound().x, env.getLowerBound().y, env.getLowerBound().z));
            box.expandBy(osg::Vec3d(env.getUpperBound().x, env.getUpperBound().y, env.getUpperBound().z));
        }
        if (s.recenter && box.valid()) b.origin = osg::Vec3d(box.center().x(), box.center().y(), box.zMin());
        osg::ref_ptr<osg::Group> root = new osg::Group;
        root->setName(osgDB::getSimpleFileName(path));
        for (const auto& o : model->getRootCityObjects())
            if (o) root->addChild(b.object(*o));
        root->setUserValue("loa.origin", b.origin);
        root->setUserValue("loa.crs", !model->getSRSName().empty() ? model->getSRSName() : env.srsName());
        osgLoA::FeatureIndex(*root).updateBounds();
        if (!b.missingTextures.empty())
            OSG_WARN << "citygml: " << path << ": " << b.missingTextures.size()
                     << " texture file(s) not found (first: " << b.missingTextures.front()
                     << "); their surfaces are drawn untextured" << std::endl;
        OSG_INFO << "citygml: " << path << ": " << b.features << " features" << std::endl;
        return root.get();
    }
};
} // namespace

REGISTER_OSGPLUGIN(citygml, ReaderWriterCityGml)
