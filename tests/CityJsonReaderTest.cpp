// The CityJSON reader (plugins/cityjson, docs/cityjson.md) on fixtures this test writes itself:
// versions, geometry types, holes, semantics, appearance, transform and origin, LoD selection,
// parent/child, type mapping, templates, broken files, and a write-read-write round trip.
#include "support/TestSupport.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/BlendFunc>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Material>
#include <osg/Texture2D>
#include <osg/ValueObject>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using osgLoA::Feature;
using osgLoA::FeatureType;

namespace
{

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text)
{
    const std::string path = dir + "/" + name;
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
}

/** A CityJSON document with an identity transform unless `transform` says otherwise. */
std::string cityJson(const std::string& objects, const std::string& vertices,
                     const std::string& version = "2.0", const std::string& extra = "",
                     const std::string& transform = R"("transform":{"scale":[1,1,1],"translate":[0,0,0]},)")
{
    return R"({"type":"CityJSON","version":")" + version + "\"," + transform + R"("CityObjects":{)" +
           objects + R"(},"vertices":)" + vertices + extra + "}";
}

const char* kCubeVertices = "[[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]";
// Bottom, top, front (y=0), right (x=1), back (y=1), left (x=0); outer rings counter-clockwise
// seen from outside.
const char* kCubeShell = "[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]]]";

osgDB::ReaderWriter::ReadResult read(const std::string& path, const std::string& options = "")
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options(options);
    return osgDB::Registry::instance()->readNode(path, opts.get());
}

osg::ref_ptr<osg::Group> load(const std::string& path, const std::string& options = "")
{
    auto rr = read(path, options);
    EXPECT_TRUE(rr.validNode()) << path << ": " << rr.message();
    return rr.validNode() ? dynamic_cast<osg::Group*>(rr.getNode()) : nullptr;
}

class Collect : public osg::NodeVisitor
{
public:
    Collect() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Drawable& d) override
    {
        if (osg::Geometry* g = d.asGeometry()) geometries.push_back(g);
    }
    void apply(osg::Group& g) override
    {
        if (Feature::get(g)) groups[g.getName()] = &g;
        traverse(g);
    }
    std::vector<osg::Geometry*> geometries;
    std::map<std::string, osg::Group*> groups;
};

Collect collect(osg::Node& n)
{
    Collect c;
    n.accept(c);
    return c;
}

unsigned triangleCount(const osg::Geometry& g)
{
    unsigned n = 0;
    for (unsigned i = 0; i < g.getNumPrimitiveSets(); ++i)
        if (g.getPrimitiveSet(i)->getMode() == GL_TRIANGLES) n += g.getPrimitiveSet(i)->getNumIndices() / 3;
    return n;
}

unsigned triangleCount(osg::Node& n)
{
    unsigned t = 0;
    for (osg::Geometry* g : collect(n).geometries)
        t += triangleCount(*g);
    return t;
}

double area(const osg::Geometry& g)
{
    const osg::Vec3Array* v = dynamic_cast<const osg::Vec3Array*>(g.getVertexArray());
    double a = 0.0;
    for (std::size_t i = 0; v && i + 2 < v->size(); i += 3)
    {
        const osg::Vec3d p0((*v)[i]), p1((*v)[i + 1]), p2((*v)[i + 2]);
        a += 0.5 * ((p1 - p0) ^ (p2 - p0)).length();
    }
    return a;
}

osg::Vec3d origin(const osg::Node& n)
{
    osg::Vec3d o(-1, -1, -1);
    EXPECT_TRUE(n.getUserValue("loa.origin", o));
    return o;
}

unsigned counter(const osg::Node& n, const std::string& name)
{
    unsigned v = 12345;
    EXPECT_TRUE(n.getUserValue(name, v)) << name;
    return v;
}

} // namespace

// ---- versions, extensions ----------------------------------------------------------------------

struct VersionCase
{
    const char* name;
    std::string text;
    float lod;
};

TEST(CityJsonReaderTest, ReadsVersions10And11And20)
{
    const std::string dir = loatest::freshDirectory("cityjson-versions");
    const std::string obj =
        R"("b":{"type":"Building","geometry":[{"type":"Solid","lod":LOD,"boundaries":[SHELL]}]})";
    auto object = [&](const std::string& lod)
    {
        std::string s = obj;
        s.replace(s.find("LOD"), 3, lod);
        s.replace(s.find("SHELL"), 5, kCubeShell);
        return s;
    };
    const VersionCase cases[] = {
        // 1.0: no transform (real coordinates), LoD a number.
        {"v10.json",
         cityJson(object("2"), "[[0.0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]", "1.0",
                  "", ""),
         2.0f},
        {"v11.city.json", cityJson(object("\"1.2\""), kCubeVertices, "1.1"), 1.2f},
        {"v20.cityjson", cityJson(object("\"2.2\""), kCubeVertices, "2.0"), 2.2f},
    };
    for (const VersionCase& c : cases)
    {
        SCOPED_TRACE(c.name);
        osg::ref_ptr<osg::Group> root = load(writeFile(dir, c.name, c.text), "recenter=0");
        ASSERT_TRUE(root.valid());
        Collect all = collect(*root);
        ASSERT_EQ(all.groups.count("b"), 1u);
        const Feature* f = Feature::get(*all.groups["b"]);
        EXPECT_FLOAT_EQ(f->getLod(), c.lod);
        EXPECT_EQ(triangleCount(*root), 12u);
        EXPECT_TRUE(f->getBound().valid());
        EXPECT_NEAR(f->getBound().xMax(), 1.0, 1e-6);
    }
}

TEST(CityJsonReaderTest, A11FileWithoutTransformIsAnError)
{
    const std::string dir = loatest::freshDirectory("cityjson-notransform");
    auto rr = read(writeFile(dir, "a.city.json", cityJson("", "[]", "1.1", "", "")));
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("requires \"transform\""), std::string::npos) << rr.message();
}

TEST(CityJsonReaderTest, PlainJsonThatIsNotCityJsonIsLeftToOtherPlugins)
{
    const std::string dir = loatest::freshDirectory("cityjson-otherjson");
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("json");
    ASSERT_NE(rw, nullptr) << "osgdb_json (the CityJSON reader) not found on OSG_LIBRARY_PATH";
    auto rr = rw->readNode(writeFile(dir, "geo.json", R"({"type":"FeatureCollection","features":[]})"));
    EXPECT_EQ(rr.status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED);
    rr = rw->readNode(writeFile(dir, "broken.json", R"({"some": [1, 2)"));
    EXPECT_EQ(rr.status(), osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED);
    // The same text named .cityjson is a clear error.
    rr = rw->readNode(writeFile(dir, "geo.cityjson", R"({"type":"FeatureCollection","features":[]})"));
    EXPECT_EQ(rr.status(), osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE);
    EXPECT_NE(rr.message().find("expected \"CityJSON\""), std::string::npos) << rr.message();
    // A plain .json that is CityJSON is read.
    rr = rw->readNode(writeFile(dir, "city.json", cityJson("", "[]")));
    EXPECT_TRUE(rr.validNode()) << rr.message();
}

TEST(CityJsonReaderTest, AnEmptyCityIsAValidEmptyGroup)
{
    const std::string dir = loatest::freshDirectory("cityjson-empty");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "empty.city.json", cityJson("", "[]")));
    ASSERT_TRUE(root.valid());
    EXPECT_EQ(root->getNumChildren(), 0u);
    EXPECT_EQ(origin(*root), osg::Vec3d(0, 0, 0));
}

// ---- geometry ----------------------------------------------------------------------------------

TEST(CityJsonReaderTest, SquareWithASquareHoleHasTheExactArea)
{
    const std::string dir = loatest::freshDirectory("cityjson-hole");
    // Outer 10 x 10 counter-clockwise, hole 4 x 4 clockwise, in the plane z = 5.
    const std::string text = cityJson(
        R"("p":{"type":"GenericCityObject","geometry":[{"type":"MultiSurface","lod":"1",
            "boundaries":[[[0,1,2,3],[4,5,6,7]]]}]})",
        "[[0,0,5],[10,0,5],[10,10,5],[0,10,5],[3,3,5],[3,7,5],[7,7,5],[7,3,5]]");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "hole.city.json", text));
    ASSERT_TRUE(root.valid());
    Collect all = collect(*root);
    ASSERT_EQ(all.geometries.size(), 1u);
    const osg::Geometry& g = *all.geometries[0];
    EXPECT_NEAR(area(g), 10.0 * 10.0 - 4.0 * 4.0, 1e-9); // outer minus hole
    // 8 vertices, 1 hole: 8 + 2 * 1 - 2 = 8 triangles.
    EXPECT_EQ(triangleCount(g), 8u);
    // Flat normals facing +z; no triangle inside the hole.
    const osg::Vec3Array* n = dynamic_cast<const osg::Vec3Array*>(g.getNormalArray());
    const osg::Vec3Array* v = dynamic_cast<const osg::Vec3Array*>(g.getVertexArray());
    ASSERT_TRUE(n && v);
    const osg::Vec3d o = origin(*root);
    for (std::size_t i = 0; i < n->size(); ++i)
        EXPECT_NEAR(((*n)[i] - osg::Vec3(0, 0, 1)).length(), 0.0f, 1e-6f);
    for (std::size_t i = 0; i + 2 < v->size(); i += 3)
    {
        const osg::Vec3d c =
            (osg::Vec3d((*v)[i]) + osg::Vec3d((*v)[i + 1]) + osg::Vec3d((*v)[i + 2])) / 3.0 + o;
        EXPECT_FALSE(c.x() > 3 && c.x() < 7 && c.y() > 3 && c.y() < 7) << "triangle centroid inside the hole";
        // Counter-clockwise seen from +z.
        const osg::Vec3 cr = ((*v)[i + 1] - (*v)[i]) ^ ((*v)[i + 2] - (*v)[i]);
        EXPECT_GT(cr.z(), 0.0f);
    }
}

TEST(CityJsonReaderTest, ConcavePolygonsAndDegenerateOnesAreHandled)
{
    const std::string dir = loatest::freshDirectory("cityjson-concave");
    // An L shape (area 3), a polygon with two distinct vertices, a collinear one: two skipped.
    const std::string text = cityJson(
        R"("p":{"type":"GenericCityObject","geometry":[{"type":"MultiSurface","lod":"1",
            "boundaries":[[[0,1,2,3,4,5]],[[0,1,0,1]],[[0,1,6]],[[0,0,0]]]}]})",
        "[[0,0,0],[2,0,0],[2,1,0],[1,1,0],[1,2,0],[0,2,0],[4,0,0]]");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "concave.city.json", text));
    ASSERT_TRUE(root.valid());
    Collect all = collect(*root);
    ASSERT_EQ(all.geometries.size(), 1u);
    EXPECT_NEAR(area(*all.geometries[0]), 3.0, 1e-9);
    EXPECT_EQ(triangleCount(*all.geometries[0]), 4u);
    EXPECT_EQ(counter(*root, "cityjson.skippedPolygons"), 3u);
}

struct GeometryTypeCase
{
    const char* type;
    std::string boundaries;
    unsigned triangles;
    GLenum otherMode; ///< GL_POINTS / GL_LINE_STRIP when triangles is 0
    unsigned otherPrimitives;
    const char* drawableName;
};

TEST(CityJsonReaderTest, EveryGeometryType)
{
    const std::string dir = loatest::freshDirectory("cityjson-types");
    const std::string shell = kCubeShell;
    // The second cube: the same shell moved to vertices 8..15.
    const std::string shell2 =
        "[[[8,11,10,9]],[[12,13,14,15]],[[8,9,13,12]],[[9,10,14,13]],[[10,11,15,14]],[[11,8,12,15]]]";
    const std::string vertices = "[[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1],"
                                 "[2,0,0],[3,0,0],[3,1,0],[2,1,0],[2,0,1],[3,0,1],[3,1,1],[2,1,1]]";
    const GeometryTypeCase cases[] = {
        {"MultiPoint", "[0,1,2]", 0, GL_POINTS, 1, "MultiPoint"},
        {"MultiLineString", "[[0,1,2],[4,5]]", 0, GL_LINE_STRIP, 2, "MultiLineString"},
        {"MultiSurface", "[[[0,3,2,1]],[[4,5,6,7]]]", 4, 0, 0, "Surface"},
        {"CompositeSurface", "[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]]]", 6, 0, 0, "Surface"},
        {"Solid", "[" + shell + "]", 12, 0, 0, "Surface"},
        {"MultiSolid", "[[" + shell + "],[" + shell2 + "]]", 24, 0, 0, "Surface"},
        {"CompositeSolid", "[[" + shell + "],[" + shell2 + "]]", 24, 0, 0, "Surface"},
    };
    for (const GeometryTypeCase& c : cases)
    {
        SCOPED_TRACE(c.type);
        const std::string text =
            cityJson(R"("o":{"type":"GenericCityObject","geometry":[{"type":")" + std::string(c.type) +
                         R"(","lod":"1","boundaries":)" + c.boundaries + "}]}",
                     vertices);
        osg::ref_ptr<osg::Group> root = load(writeFile(dir, std::string(c.type) + ".city.json", text));
        ASSERT_TRUE(root.valid());
        Collect all = collect(*root);
        ASSERT_EQ(all.geometries.size(), 1u);
        const osg::Geometry& g = *all.geometries[0];
        EXPECT_EQ(g.getName(), c.drawableName);
        EXPECT_EQ(triangleCount(g), c.triangles);
        if (c.triangles == 0)
        {
            ASSERT_EQ(g.getNumPrimitiveSets(), c.otherPrimitives);
            EXPECT_EQ(g.getPrimitiveSet(0)->getMode(), c.otherMode);
            if (c.otherMode == GL_POINTS)
            {
                EXPECT_EQ(g.getPrimitiveSet(0)->getNumIndices(), 3u);
            }
        }
        else
            EXPECT_NEAR(area(g), c.triangles / 2.0, 1e-9); // unit squares
    }
}

TEST(CityJsonReaderTest, SemanticSurfacesBecomeNamedDrawables)
{
    const std::string dir = loatest::freshDirectory("cityjson-semantics");
    const std::string text = cityJson(
        R"("b":{"type":"Building","geometry":[{"type":"Solid","lod":"2","boundaries":[)" +
            std::string(kCubeShell) +
            R"(],"semantics":{"surfaces":[{"type":"GroundSurface"},{"type":"RoofSurface"},{"type":"WallSurface"}],
            "values":[[0,1,2,2,2,null]]}}]})",
        kCubeVertices);
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "sem.city.json", text));
    ASSERT_TRUE(root.valid());
    std::map<std::string, unsigned> triangles;
    for (osg::Geometry* g : collect(*root).geometries)
        triangles[g->getName()] += triangleCount(*g);
    const std::map<std::string, unsigned> expected = {
        {"GroundSurface", 2}, {"RoofSurface", 2}, {"WallSurface", 6}, {"Surface", 2}};
    EXPECT_EQ(triangles, expected);
    // The roof faces up, the ground down.
    for (osg::Geometry* g : collect(*root).geometries)
    {
        const osg::Vec3Array* n = dynamic_cast<const osg::Vec3Array*>(g->getNormalArray());
        if (g->getName() == "RoofSurface")
        {
            EXPECT_NEAR((*n)[0].z(), 1.0f, 1e-6f);
        }
        if (g->getName() == "GroundSurface")
        {
            EXPECT_NEAR((*n)[0].z(), -1.0f, 1e-6f);
        }
    }
}

// ---- appearance --------------------------------------------------------------------------------

TEST(CityJsonReaderTest, MaterialsBecomeOsgMaterials)
{
    const std::string dir = loatest::freshDirectory("cityjson-materials");
    const std::string appearance = R"(,"appearance":{"materials":[
        {"name":"roofred","diffuseColor":[0.9,0.1,0.2],"ambientIntensity":0.5,"specularColor":[0.3,0.3,0.3],
         "shininess":0.5,"transparency":0.25},
        {"name":"wallgrey","diffuseColor":[0.5,0.5,0.5]}]})";
    const std::string text = cityJson(
        R"("b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]]],
            "semantics":{"surfaces":[{"type":"RoofSurface"},{"type":"WallSurface"}],"values":[1,0,1]},
            "material":{"colours":{"values":[1,0,null]}}}]},
            "c":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,3,2,1]]],
            "material":{"colours":{"value":1}}}]})",
        kCubeVertices, "2.0", appearance);
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "mat.city.json", text));
    ASSERT_TRUE(root.valid());
    std::string theme;
    EXPECT_TRUE(root->getUserValue("cityjson.materialTheme", theme));
    EXPECT_EQ(theme, "colours");
    Collect all = collect(*root);
    std::map<std::string, const osg::Material*> byDrawable;
    for (osg::Geometry* g : collect(*all.groups["b"]).geometries)
    {
        const osg::Material* m = g->getStateSet()
                                     ? dynamic_cast<const osg::Material*>(
                                           g->getStateSet()->getAttribute(osg::StateAttribute::MATERIAL))
                                     : nullptr;
        byDrawable[g->getName() + "/" + (m ? m->getName() : "none")] = m;
    }
    // Surfaces 0 (wall, material 1) and 2 (wall, none) differ in material: two wall drawables.
    ASSERT_EQ(byDrawable.size(), 3u);
    ASSERT_TRUE(byDrawable.count("RoofSurface/roofred"));
    ASSERT_TRUE(byDrawable.count("WallSurface/wallgrey"));
    ASSERT_TRUE(byDrawable.count("WallSurface/none"));
    const osg::Material* red = byDrawable["RoofSurface/roofred"];
    const osg::Vec4 d = red->getDiffuse(osg::Material::FRONT);
    EXPECT_FLOAT_EQ(d.r(), 0.9f);
    EXPECT_FLOAT_EQ(d.g(), 0.1f);
    EXPECT_FLOAT_EQ(d.b(), 0.2f);
    EXPECT_FLOAT_EQ(d.a(), 0.75f); // 1 - transparency
    EXPECT_FLOAT_EQ(red->getAmbient(osg::Material::FRONT).r(), 0.45f);
    EXPECT_FLOAT_EQ(red->getSpecular(osg::Material::FRONT).g(), 0.3f);
    EXPECT_FLOAT_EQ(red->getShininess(osg::Material::FRONT), 64.0f);
    // Transparent: blended in the transparent bin; the opaque one is not.
    for (osg::Geometry* g : collect(*all.groups["b"]).geometries)
    {
        if (!g->getStateSet()) continue;
        const bool transparent = g->getName() == "RoofSurface";
        EXPECT_EQ(g->getStateSet()->getMode(GL_BLEND) == osg::StateAttribute::ON, transparent)
            << g->getName();
        EXPECT_EQ(g->getStateSet()->getRenderingHint() == osg::StateSet::TRANSPARENT_BIN, transparent);
    }
    // "value": one material for the whole geometry.
    Collect c = collect(*all.groups["c"]);
    ASSERT_EQ(c.geometries.size(), 1u);
    const osg::Material* grey = dynamic_cast<const osg::Material*>(
        c.geometries[0]->getStateSet()->getAttribute(osg::StateAttribute::MATERIAL));
    ASSERT_NE(grey, nullptr);
    EXPECT_EQ(grey->getName(), "wallgrey");
    EXPECT_FLOAT_EQ(grey->getDiffuse(osg::Material::FRONT).r(), 0.5f);
}

namespace
{
std::string writeTinyPng(const std::string& path)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (unsigned i = 0; i < 4 * 4 * 3; ++i)
        img->data()[i] = static_cast<unsigned char>(i * 5);
    EXPECT_TRUE(osgDB::writeImageFile(*img, path)) << path;
    return path;
}

/** A quad (z = 0) textured with facade.png; a second quad (z = 1) names a missing texture. */
std::string texturedCity()
{
    const std::string appearance = R"(,"appearance":{
        "materials":[{"name":"brick","diffuseColor":[0.6,0.3,0.2]}],
        "textures":[{"type":"PNG","image":"tex/facade.png"},{"type":"PNG","image":"tex/missing.png","wrapMode":"clamp"}],
        "vertices-texture":[[0,0],[1,0],[1,1],[0,1],[0.25,0.5]]})";
    return cityJson(R"("b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2",
            "boundaries":[[[0,1,2,3]],[[4,5,6,7]]],
            "semantics":{"surfaces":[{"type":"WallSurface"}],"values":[0,0]},
            "material":{"look":{"values":[0,0]}},
            "texture":{"look":{"values":[[[0,0,1,2,4]],[[1,0,1,2,3]]]}}}]})",
                    kCubeVertices, "1.1", appearance);
}

void expectTexturedQuad(osg::Node& root)
{
    Collect all = collect(root);
    const osg::Geometry* textured = nullptr;
    const osg::Geometry* fallback = nullptr;
    for (osg::Geometry* g : all.geometries)
        (g->getTexCoordArray(0) ? textured : fallback) = g;
    ASSERT_NE(textured, nullptr);
    ASSERT_NE(fallback, nullptr) << "the surface whose texture is missing is drawn untextured";
    // The textured one: Texture2D, repeat, mipmapped, image file name kept.
    const osg::Texture2D* tex = dynamic_cast<const osg::Texture2D*>(
        textured->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE));
    ASSERT_NE(tex, nullptr);
    EXPECT_EQ(tex->getWrap(osg::Texture::WRAP_S), osg::Texture::REPEAT);
    EXPECT_EQ(tex->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
    ASSERT_NE(tex->getImage(), nullptr);
    EXPECT_NE(tex->getImage()->getFileName().find("facade.png"), std::string::npos);
    EXPECT_EQ(tex->getImage()->s(), 4);
    // Known vertices carry their texture coordinates: (0,0,0)->(0,0), (1,0,0)->(1,0),
    // (1,1,0)->(1,1), (0,1,0)->(0.25,0.5).
    const osg::Vec3d o = origin(root);
    const osg::Vec3Array* v = dynamic_cast<const osg::Vec3Array*>(textured->getVertexArray());
    const osg::Vec2Array* t = dynamic_cast<const osg::Vec2Array*>(textured->getTexCoordArray(0));
    ASSERT_TRUE(v && t);
    ASSERT_EQ(v->size(), t->size());
    ASSERT_EQ(v->size(), 6u);
    const std::map<std::pair<int, int>, osg::Vec2> expected = {
        {{0, 0}, {0, 0}}, {{1, 0}, {1, 0}}, {{1, 1}, {1, 1}}, {{0, 1}, {0.25f, 0.5f}}};
    for (std::size_t i = 0; i < v->size(); ++i)
    {
        const osg::Vec3d w = osg::Vec3d((*v)[i]) + o;
        const auto key =
            std::make_pair(static_cast<int>(std::lround(w.x())), static_cast<int>(std::lround(w.y())));
        ASSERT_TRUE(expected.count(key));
        EXPECT_NEAR(((*t)[i] - expected.at(key)).length(), 0.0f, 1e-6f);
    }
    // The fallback keeps its material, has no texture.
    EXPECT_EQ(fallback->getStateSet()->getTextureAttribute(0, osg::StateAttribute::TEXTURE), nullptr);
    const osg::Material* m = dynamic_cast<const osg::Material*>(
        fallback->getStateSet()->getAttribute(osg::StateAttribute::MATERIAL));
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(m->getName(), "brick");
    EXPECT_EQ(counter(root, "cityjson.missingTextures"), 1u);
}
} // namespace

TEST(CityJsonReaderTest, TexturesAndTheMissingTextureFallback)
{
    const std::string dir = loatest::freshDirectory("cityjson-textures");
    osgDB::makeDirectory(dir + "/tex");
    writeTinyPng(dir + "/tex/facade.png");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "tex.city.json", texturedCity()));
    ASSERT_TRUE(root.valid());
    expectTexturedQuad(*root);
}

TEST(CityJsonReaderTest, StreamsResolveTexturesAgainstTheDatabasePath)
{
    const std::string dir = loatest::freshDirectory("cityjson-stream");
    osgDB::makeDirectory(dir + "/tex");
    writeTinyPng(dir + "/tex/facade.png");
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("cityjson");
    ASSERT_NE(rw, nullptr);
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options;
    opts->getDatabasePathList().push_back(dir);
    std::istringstream in(texturedCity());
    auto rr = rw->readNode(in, opts.get());
    ASSERT_TRUE(rr.validNode()) << rr.message();
    expectTexturedQuad(*rr.getNode());
}

TEST(CityJsonReaderTest, ThemeOptionSelectsTheTheme)
{
    const std::string dir = loatest::freshDirectory("cityjson-theme");
    const std::string appearance =
        R"(,"appearance":{"materials":[{"name":"summer-green","diffuseColor":[0,1,0]},
        {"name":"winter-white","diffuseColor":[1,1,1]}]})";
    const std::string text = cityJson(
        R"("b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,3,2,1]]],
            "material":{"summer":{"values":[0]},"winter":{"values":[1]}}}]})",
        kCubeVertices, "2.0", appearance);
    const std::string path = writeFile(dir, "theme.city.json", text);
    for (const auto& [option, name] :
         {std::make_pair(std::string(""), std::string("summer-green")),
          std::make_pair(std::string("theme=winter"), std::string("winter-white"))})
    {
        osg::ref_ptr<osg::Group> root = load(path, option);
        ASSERT_TRUE(root.valid());
        Collect all = collect(*root);
        ASSERT_EQ(all.geometries.size(), 1u);
        EXPECT_EQ(all.geometries[0]->getStateSet()->getAttribute(osg::StateAttribute::MATERIAL)->getName(),
                  name);
    }
}

// ---- coordinates -------------------------------------------------------------------------------

TEST(CityJsonReaderTest, TransformIsAppliedAndTheOriginRecorded)
{
    const std::string dir = loatest::freshDirectory("cityjson-transform");
    const std::string text = cityJson(
        R"("o":{"type":"GenericCityObject","geometry":[{"type":"MultiPoint","lod":"0","boundaries":[0,1]}]})",
        "[[2,4,6],[10,20,30]]", "2.0",
        R"(,"metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/7415"})",
        R"("transform":{"scale":[0.5,0.25,2],"translate":[100,200,300]},)");
    const std::string path = writeFile(dir, "transform.city.json", text);
    {
        // recenter=0: world coordinates as they are. (2,4,6) -> (2*0.5+100, 4*0.25+200, 6*2+300).
        osg::ref_ptr<osg::Group> root = load(path, "recenter=0");
        ASSERT_TRUE(root.valid());
        EXPECT_EQ(origin(*root), osg::Vec3d(0, 0, 0));
        const osg::Vec3Array* v =
            dynamic_cast<const osg::Vec3Array*>(collect(*root).geometries[0]->getVertexArray());
        EXPECT_EQ((*v)[0], osg::Vec3(101, 201, 312));
        EXPECT_EQ((*v)[1], osg::Vec3(105, 205, 360));
        std::string crs;
        EXPECT_TRUE(root->getUserValue("loa.crs", crs));
        EXPECT_EQ(crs, "https://www.opengis.net/def/crs/EPSG/0/7415");
    }
    {
        // Default: origin at the centre of the box of the used vertices; world = local + origin.
        osg::ref_ptr<osg::Group> root = load(path);
        ASSERT_TRUE(root.valid());
        const osg::Vec3d o = origin(*root);
        EXPECT_EQ(o, osg::Vec3d(103, 203, 336));
        const osg::Vec3Array* v =
            dynamic_cast<const osg::Vec3Array*>(collect(*root).geometries[0]->getVertexArray());
        EXPECT_EQ(osg::Vec3d((*v)[0]) + o, osg::Vec3d(101, 201, 312));
        EXPECT_EQ((*v)[0], osg::Vec3(-2, -2, -24));
    }
}

TEST(CityJsonReaderTest, LargeCoordinatesKeepMillimetresAfterRecentring)
{
    const std::string dir = loatest::freshDirectory("cityjson-large");
    // Millimetre integers around x = 5,000,000 m, y = 5,500,000 m (as Dutch and UTM data are).
    const std::string text = cityJson(
        R"("o":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2,3]],[[4,5,6]]]}]})",
        "[[1,2,3],[10001,2,3],[10001,12347,3],[1,12347,3],[5003,7007,25001],[6001,7007,25001],[5003,8009,"
        "25003]]",
        "2.0", "",
        R"("transform":{"scale":[0.001,0.001,0.001],"translate":[5000000.123,5500000.456,12.5]},)");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "large.city.json", text));
    ASSERT_TRUE(root.valid());
    const osg::Vec3d o = origin(*root);
    // Box x 5000000.124 .. 5000010.124, y 5500000.458 .. 5500012.803, z 12.503 .. 37.503.
    EXPECT_NEAR(o.x(), 5000005.124, 1e-6);
    EXPECT_NEAR(o.y(), 5500006.6305, 1e-6);
    EXPECT_NEAR(o.z(), 25.003, 1e-9);
    const osg::Vec3d worldOf[] = {{5000000.124, 5500000.458, 12.503},
                                  {5000010.124, 5500000.458, 12.503},
                                  {5000010.124, 5500012.803, 12.503},
                                  {5000000.124, 5500012.803, 12.503}};
    unsigned checked = 0;
    for (osg::Geometry* g : collect(*root).geometries)
    {
        const osg::Vec3Array* v = dynamic_cast<const osg::Vec3Array*>(g->getVertexArray());
        for (const osg::Vec3& p : *v)
            for (const osg::Vec3d& w : worldOf)
                if ((osg::Vec3d(p) + o - w).length() < 0.01)
                {
                    EXPECT_NEAR(p.x(), w.x() - o.x(), 1e-3);
                    EXPECT_NEAR(p.y(), w.y() - o.y(), 1e-3);
                    EXPECT_NEAR(p.z(), w.z() - o.z(), 1e-3);
                    ++checked;
                }
    }
    EXPECT_EQ(checked, 6u); // the quad's two triangles
}

// ---- LoD, hierarchy, types, templates ------------------------------------------------------------

TEST(CityJsonReaderTest, LodSelection)
{
    const std::string dir = loatest::freshDirectory("cityjson-lod");
    const std::string text = cityJson(
        R"("a":{"type":"Building","geometry":[
              {"type":"MultiSurface","lod":"1.2","boundaries":[[[0,3,2,1]]]},
              {"type":"Solid","lod":"2.2","boundaries":[)" +
            std::string(kCubeShell) + R"(]}]},
           "b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1.2","boundaries":[[[4,5,6,7]]]}]})",
        kCubeVertices);
    const std::string path = writeFile(dir, "lod.city.json", text);
    struct Case
    {
        std::string option;
        float lodA, lodB; ///< negative: omitted
        unsigned omitted;
    } cases[] = {{"", 2.2f, 1.2f, 0}, {"lod=2.2", 2.2f, -1.0f, 1}, {"lod=1.2", 1.2f, 1.2f, 0}};
    for (const Case& c : cases)
    {
        SCOPED_TRACE(c.option);
        osg::ref_ptr<osg::Group> root = load(path, c.option);
        ASSERT_TRUE(root.valid());
        Collect all = collect(*root);
        ASSERT_EQ(all.groups.count("a"), 1u);
        EXPECT_FLOAT_EQ(Feature::get(*all.groups["a"])->getLod(), c.lodA);
        EXPECT_EQ(triangleCount(*all.groups["a"]), c.lodA > 2.0f ? 12u : 2u);
        EXPECT_EQ(all.groups.count("b"), c.lodB > 0 ? 1u : 0u);
        if (c.lodB > 0)
        {
            EXPECT_FLOAT_EQ(Feature::get(*all.groups["b"])->getLod(), c.lodB);
        }
        EXPECT_EQ(counter(*root, "cityjson.omittedObjects"), c.omitted);
    }
    auto rr = read(path, "lod=3");
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("no object has LoD 3"), std::string::npos) << rr.message();
    rr = read(path, "lod=two");
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("option lod=two"), std::string::npos) << rr.message();
}

TEST(CityJsonReaderTest, ChildrenNestUnderTheirParentAndFeaturesAreNumberedInFileOrder)
{
    const std::string dir = loatest::freshDirectory("cityjson-children");
    const std::string text = cityJson(
        R"("part1":{"type":"BuildingPart","parents":["bldg"],"geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,3,2,1]]]}]},
           "bldg":{"type":"Building","children":["part1","part2"],"attributes":{"height":12.5,"name":"Town hall","listed":true,"tags":["a",1]}},
           "part2":{"type":"BuildingPart","parents":["bldg"],"geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[4,5,6,7]]]}]},
           "road":{"type":"Road","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,5,4]]]}]})",
        kCubeVertices);
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "children.city.json", text));
    ASSERT_TRUE(root.valid());
    ASSERT_EQ(root->getNumChildren(), 2u); // bldg and road; the parts only under bldg
    Collect all = collect(*root);
    osg::Group* bldg = all.groups["bldg"];
    ASSERT_NE(bldg, nullptr);
    EXPECT_EQ(bldg->getParent(0), root.get());
    EXPECT_EQ(all.groups["part1"]->getParent(0), bldg);
    EXPECT_EQ(all.groups["part2"]->getParent(0), bldg);
    EXPECT_EQ(all.groups["part1"]->getNumParents(), 1u);
    // Ids in file order.
    EXPECT_EQ(Feature::get(*all.groups["part1"])->getId(), 1u);
    EXPECT_EQ(Feature::get(*bldg)->getId(), 2u);
    EXPECT_EQ(Feature::get(*all.groups["part2"])->getId(), 3u);
    EXPECT_EQ(Feature::get(*all.groups["road"])->getId(), 4u);
    EXPECT_EQ(Feature::get(*all.groups["part1"])->getSubType(), "part");
    EXPECT_EQ(Feature::get(*bldg)->getLod(), -1.0f); // no geometry of its own
    // Counts of top-level features; the index knows the nesting; the building's bound covers its parts.
    osgLoA::FeatureIndex index(*root);
    EXPECT_EQ(index.size(), 4u);
    EXPECT_EQ(index.counts().get(FeatureType::Building), 1u);
    EXPECT_EQ(index.counts(false).get(FeatureType::Building), 3u);
    EXPECT_TRUE(Feature::get(*bldg)->getBound().valid());
    // Attributes as user values.
    double height = 0;
    std::string name, tags;
    bool listed = false;
    EXPECT_TRUE(bldg->getUserValue("cityjson.height", height));
    EXPECT_EQ(height, 12.5);
    EXPECT_TRUE(bldg->getUserValue("cityjson.name", name));
    EXPECT_EQ(name, "Town hall");
    EXPECT_TRUE(bldg->getUserValue("cityjson.listed", listed));
    EXPECT_TRUE(listed);
    EXPECT_TRUE(bldg->getUserValue("cityjson.tags", tags));
    EXPECT_EQ(tags, R"(["a",1])");
}

struct TypeCase
{
    const char* cityType;
    const char* attributes;
    FeatureType type;
    const char* subType;
    Feature::Source source;
};

TEST(CityJsonReaderTest, TypeMappingTable)
{
    const TypeCase cases[] = {
        {"Building", "{}", FeatureType::Building, "", Feature::MODEL_DATA},
        {"BuildingPart", "{}", FeatureType::Building, "part", Feature::MODEL_DATA},
        {"BuildingInstallation", "{}", FeatureType::Building, "installation", Feature::MODEL_DATA},
        {"BuildingConstructiveElement", "{}", FeatureType::Building, "element", Feature::MODEL_DATA},
        {"BuildingFurniture", "{}", FeatureType::Building, "furniture", Feature::MODEL_DATA},
        {"BuildingRoom", "{}", FeatureType::Building, "room", Feature::MODEL_DATA},
        {"BuildingStorey", "{}", FeatureType::Building, "storey", Feature::MODEL_DATA},
        {"BuildingUnit", "{}", FeatureType::Building, "unit", Feature::MODEL_DATA},
        {"Road", "{}", FeatureType::Street, "road", Feature::MODEL_DATA},
        {"Railway", "{}", FeatureType::Street, "railway", Feature::MODEL_DATA},
        {"TransportSquare", "{}", FeatureType::Street, "square", Feature::MODEL_DATA},
        {"Tunnel", "{}", FeatureType::Street, "tunnel", Feature::MODEL_DATA},
        {"TunnelPart", "{}", FeatureType::Street, "tunnel", Feature::MODEL_DATA},
        {"TunnelInstallation", "{}", FeatureType::Street, "tunnel", Feature::MODEL_DATA},
        {"Waterway", "{}", FeatureType::Water, "waterway", Feature::MODEL_DATA},
        {"WaterBody", "{}", FeatureType::Water, "", Feature::MODEL_DATA},
        {"WaterBody", R"({"class":"River Maas"})", FeatureType::Water, "river", Feature::MODEL_DATA},
        {"WaterBody", R"({"function":"lake"})", FeatureType::Water, "lake", Feature::MODEL_DATA},
        {"PlantCover", "{}", FeatureType::Green, "plant-cover", Feature::MODEL_DATA},
        {"PlantCover", R"({"class":"Deciduous"})", FeatureType::Green, "deciduous", Feature::MODEL_DATA},
        {"SolitaryVegetationObject", "{}", FeatureType::Green, "tree", Feature::MODEL_DATA},
        {"TINRelief", "{}", FeatureType::Terrain, "relief", Feature::MODEL_DATA},
        {"LandUse", R"({"function":"Public PARK"})", FeatureType::Green, "public park", Feature::MODEL_DATA},
        {"LandUse", R"({"class":"agricultural"})", FeatureType::Green, "agricultural", Feature::MODEL_DATA},
        {"LandUse", R"({"usage":"parking"})", FeatureType::Street, "", Feature::MODEL_DATA},
        {"LandUse", R"({"function":"lake shore water"})", FeatureType::Water, "lake shore water",
         Feature::MODEL_DATA},
        {"LandUse", R"({"function":"1010"})", FeatureType::Terrain, "1010", Feature::MODEL_DATA},
        {"LandUse", "{}", FeatureType::Terrain, "land-use", Feature::MODEL_DATA},
        {"Bridge", "{}", FeatureType::Street, "bridge", Feature::MODEL_DATA},
        {"BridgePart", "{}", FeatureType::Street, "bridge", Feature::MODEL_DATA},
        {"CityFurniture", "{}", FeatureType::Generic, "furniture", Feature::MODEL_DATA},
        {"GenericCityObject", "{}", FeatureType::Generic, "", Feature::MODEL_DATA},
        {"OtherConstruction", "{}", FeatureType::Generic, "construction", Feature::MODEL_DATA},
        {"CityObjectGroup", "{}", FeatureType::Generic, "group", Feature::MODEL_DATA},
        {"+NoiseBarrier", "{}", FeatureType::Generic, "", Feature::UNCLASSIFIED},
        {"SomethingNew", "{}", FeatureType::Generic, "", Feature::UNCLASSIFIED},
    };
    const std::string dir = loatest::freshDirectory("cityjson-typemap");
    std::string objects;
    for (std::size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); ++i)
        objects += std::string(i ? "," : "") + "\"o" + std::to_string(i) + "\":{\"type\":\"" +
                   cases[i].cityType + "\",\"attributes\":" + cases[i].attributes +
                   R"(,"geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2]]]}]})";
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "types.city.json", cityJson(objects, kCubeVertices)));
    ASSERT_TRUE(root.valid());
    Collect all = collect(*root);
    for (std::size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); ++i)
    {
        const TypeCase& c = cases[i];
        SCOPED_TRACE(std::string(c.cityType) + " " + c.attributes);
        osg::Group* g = all.groups["o" + std::to_string(i)];
        ASSERT_NE(g, nullptr);
        const Feature* f = Feature::get(*g);
        EXPECT_EQ(f->getType(), c.type);
        EXPECT_EQ(f->getSubType(), c.subType);
        EXPECT_EQ(f->getSource(), c.source);
        EXPECT_EQ(f->getSourceType(), c.cityType);
        EXPECT_EQ(f->getSourceId(), "o" + std::to_string(i));
        EXPECT_EQ(f->getId(), i + 1);
    }
}

TEST(CityJsonReaderTest, TemplateInstancesArePlacedByReferencePointAndMatrix)
{
    const std::string dir = loatest::freshDirectory("cityjson-templates");
    const std::string templates = R"(,"geometry-templates":{
        "templates":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2,3]]],
                      "semantics":{"surfaces":[{"type":"RoofSurface"}],"values":[0]}}],
        "vertices-templates":[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]})";
    // Scale 2, then move by (1,0,0.5); reference point (10,20,0).
    const std::string text = cityJson(
        R"("tree":{"type":"SolitaryVegetationObject","geometry":[{"type":"GeometryInstance","template":0,"boundaries":[1],
            "transformationMatrix":[2,0,0,1, 0,2,0,0, 0,0,2,0.5, 0,0,0,1]}]})",
        "[[0,0,0],[10,20,0]]", "1.1", templates);
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "tmpl.city.json", text), "recenter=0");
    ASSERT_TRUE(root.valid());
    Collect all = collect(*root);
    ASSERT_EQ(all.geometries.size(), 1u);
    EXPECT_EQ(all.geometries[0]->getName(), "RoofSurface");
    EXPECT_FLOAT_EQ(Feature::get(*all.groups["tree"])->getLod(), 2.0f);
    osg::BoundingBox box;
    for (const osg::Vec3& p : *dynamic_cast<const osg::Vec3Array*>(all.geometries[0]->getVertexArray()))
        box.expandBy(p);
    EXPECT_EQ(box._min, osg::Vec3(11, 20, 0.5f));
    EXPECT_EQ(box._max, osg::Vec3(13, 22, 0.5f));
    EXPECT_NEAR(area(*all.geometries[0]), 4.0, 1e-9);
}

// ---- broken files --------------------------------------------------------------------------------

struct BrokenCase
{
    const char* name;
    std::string text;
    const char* phrase;
};

TEST(CityJsonReaderTest, BrokenFilesAreClearErrors)
{
    const std::string dir = loatest::freshDirectory("cityjson-broken");
    const std::string cube =
        R"("bad-object":{"type":"Building","geometry":[{"type":"Solid","lod":"1","boundaries":[)" +
        std::string(kCubeShell) + "]}]}";
    const std::string quad =
        R"("bad-object":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1",)";
    const BrokenCase cases[] = {
        {"truncated.city.json", cityJson(cube, kCubeVertices).substr(0, 120), "not valid JSON"},
        {"truncated-plain.json", cityJson(cube, kCubeVertices).substr(0, 120), "not valid JSON"},
        {"wrongtype.cityjson", R"({"type":"CityJSONFeature","version":"2.0","CityObjects":{},"vertices":[]})",
         "expected \"CityJSON\""},
        {"toplevel-array.city.json", "[1,2,3]", "not a JSON object"},
        {"version.city.json", cityJson("", "[]", "3.0"), "unsupported CityJSON version \"3.0\""},
        {"noversion.city.json", R"({"type":"CityJSON","CityObjects":{},"vertices":[]})",
         "missing \"version\""},
        {"novertices.city.json",
         R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},"CityObjects":{}})",
         "missing \"vertices\""},
        {"noobjects.city.json",
         R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},"vertices":[]})",
         "missing \"CityObjects\""},
        {"objects-array.city.json",
         R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]},"CityObjects":[],"vertices":[]})",
         "\"CityObjects\" must be an object"},
        {"vertices-object.city.json", cityJson("", "{}"), "\"vertices\" must be an array"},
        {"vertex-short.city.json", cityJson("", "[[1,2]]"), "vertex 0 must be an array of 3 numbers"},
        {"index.city.json", cityJson(quad + R"("boundaries":[[[0,1,9]]]}]})", kCubeVertices),
         "object \"bad-object\" geometry 0 surface 0 ring 0: vertex index 9 out of range (8 vertices)"},
        {"negative-index.city.json", cityJson(quad + R"("boundaries":[[[0,1,-1]]]}]})", kCubeVertices),
         "vertex index -1 out of range"},
        {"index-string.city.json", cityJson(quad + R"("boundaries":[[[0,1,"2"]]]}]})", kCubeVertices),
         "expected a vertex index"},
        {"empty.city.json", cityJson(quad + R"("boundaries":[]}]})", kCubeVertices), "no usable geometry"},
        {"overflow.city.json",
         cityJson(cube, "[[0,0,1e999],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]"),
         "number overflow"},
        {"nonfinite.city.json",
         cityJson(cube, "[[0,0,1e300],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]]", "2.0", "",
                  R"("transform":{"scale":[1,1,1e300],"translate":[0,0,0]},)"),
         "non-finite coordinate in vertex 0"},
        {"boundaries-number.city.json", cityJson(quad + R"("boundaries":5}]})", kCubeVertices),
         "must be an array"},
        {"ring-number.city.json", cityJson(quad + R"("boundaries":[[7]]}]})", kCubeVertices),
         "must be an array"},
        {"geometry-object.city.json",
         cityJson(R"("bad-object":{"type":"Building","geometry":{}})", kCubeVertices),
         "\"geometry\" of object \"bad-object\" must be an array"},
        {"material-index.city.json",
         cityJson(quad + R"("boundaries":[[[0,1,2]]],"material":{"m":{"values":[5]}}}]})", kCubeVertices,
                  "2.0", R"(,"appearance":{"materials":[{"name":"only"}]})"),
         "material index 5 out of range (1 materials)"},
        {"texture-index.city.json",
         cityJson(
             quad + R"("boundaries":[[[0,1,2]]],"texture":{"t":{"values":[[[7,0,1,2]]]}}}]})", kCubeVertices,
             "2.0",
             R"(,"appearance":{"textures":[{"type":"PNG","image":"x.png"}],"vertices-texture":[[0,0]]})"),
         "texture index 7 out of range (1 textures)"},
        {"uv-index.city.json",
         cityJson(
             quad + R"("boundaries":[[[0,1,2]]],"texture":{"t":{"values":[[[0,0,1,9]]]}}}]})", kCubeVertices,
             "2.0",
             R"(,"appearance":{"textures":[{"type":"PNG","image":"x.png"}],"vertices-texture":[[0,0],[1,0]]})"),
         "texture vertex index 9 out of range"},
        {"template-index.city.json",
         cityJson(
             R"("bad-object":{"type":"SolitaryVegetationObject","geometry":[{"type":"GeometryInstance","template":3,
             "boundaries":[0],"transformationMatrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}]})",
             kCubeVertices, "2.0",
             R"(,"geometry-templates":{"templates":[{"type":"MultiPoint","lod":"1","boundaries":[0]}],"vertices-templates":[[0,0,0]]})"),
         "template index 3 out of range"},
    };
    for (const BrokenCase& c : cases)
    {
        SCOPED_TRACE(c.name);
        const std::string path = writeFile(dir, c.name, c.text);
        auto rr = read(path);
        EXPECT_FALSE(rr.validNode());
        EXPECT_EQ(rr.status(), osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE);
        EXPECT_NE(rr.message().find(c.phrase), std::string::npos) << rr.message();
        EXPECT_NE(rr.message().find(c.name), std::string::npos)
            << "the message names the file: " << rr.message();
    }
}

TEST(CityJsonReaderTest, EmptyBoundariesSkipTheObjectWhenOthersRemain)
{
    const std::string dir = loatest::freshDirectory("cityjson-emptyboundaries");
    const std::string text = cityJson(
        R"("empty":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[]}]},
                    "ok":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2]]]}]})",
        kCubeVertices);
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "e.city.json", text));
    ASSERT_TRUE(root.valid());
    Collect all = collect(*root);
    EXPECT_EQ(all.groups.count("empty"), 0u);
    ASSERT_EQ(all.groups.count("ok"), 1u);
    EXPECT_EQ(Feature::get(*all.groups["ok"])->getId(), 1u);
    EXPECT_EQ(counter(*root, "cityjson.skippedObjects"), 1u);
}

// ---- round trip ----------------------------------------------------------------------------------

TEST(CityJsonReaderTest, OsgtWriteReadWriteIsIdentical)
{
    const std::string dir = loatest::freshDirectory("cityjson-roundtrip");
    osgDB::makeDirectory(dir + "/tex");
    writeTinyPng(dir + "/tex/facade.png");
    osg::ref_ptr<osg::Group> root = load(writeFile(dir, "rt.city.json", texturedCity()));
    ASSERT_TRUE(root.valid());
    const std::string first = loatest::toOsgt(*root);
    ASSERT_FALSE(first.empty());
    EXPECT_NE(first.find("osgLoA::Feature"), std::string::npos);
    EXPECT_NE(first.find("loa.origin"), std::string::npos);
    const std::string path = writeFile(dir, "rt.osgt", first);
    osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
    ASSERT_TRUE(back.valid());
    EXPECT_EQ(loatest::toOsgt(*back), first);
    osgLoA::FeatureIndex index(*back);
    ASSERT_EQ(index.size(), 1u);
    EXPECT_EQ(index.entries()[0].feature->getSourceId(), "b");
}
