// Serializer wrapper for osgLoA::GraphicStyle (.osgt/.osgb/.osgx). The parameter StateSet is
// written by OSG's own StateSet serializer (uniforms, modes, attributes); a parameters object of
// another class fails the read (CheckedObjectSerializer). The fragment shader name and the
// edge and unsharp-mask numbers are user serializers so that a bad value fails the read with a
// message instead of being clamped or thrown out of osgDB.
#include <osgLoA/styles/GraphicStyle>

#include "BoundedListSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <cmath>
#include <stdexcept>

namespace
{
typedef osgLoA::GraphicStyle Style;

/** A shader file name through the style's checked setter; its error ends the read. */
bool readShaderName(osgDB::InputStream& is, Style& s, void (Style::*set)(const std::string&))
{
    std::string name;
    is.readWrappedString(name);
    if (is.getException()) return false;
    try
    {
        (s.*set)(name);
    }
    catch (const std::invalid_argument& e)
    {
        is.throwException(std::string("GraphicStyle: ") + e.what());
        return false;
    }
    return true;
}

bool writeShaderName(osgDB::OutputStream& os, const std::string& name)
{
    os.writeWrappedString(name);
    os << std::endl;
    return true;
}

bool checkFragmentShader(const Style& s)
{
    return !s.getFragmentShader().empty();
}

bool readFragmentShader(osgDB::InputStream& is, Style& s)
{
    return readShaderName(is, s, &Style::setFragmentShader);
}

bool writeFragmentShader(osgDB::OutputStream& os, const Style& s)
{
    return writeShaderName(os, s.getFragmentShader());
}

bool checkGeometryShader(const Style& s)
{
    return !s.getGeometryShader().empty();
}

bool readGeometryShader(osgDB::InputStream& is, Style& s)
{
    return readShaderName(is, s, &Style::setGeometryShader);
}

bool writeGeometryShader(osgDB::OutputStream& os, const Style& s)
{
    return writeShaderName(os, s.getGeometryShader());
}

bool checkEdgeColor(const Style& s)
{
    return s.getEdgeColor() != osg::Vec3f(0.0f, 0.0f, 0.0f);
}

bool readEdgeColor(osgDB::InputStream& is, Style& s)
{
    osg::Vec3f c;
    is >> c;
    if (is.getException()) return false;
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > 1.0f)
        {
            is.throwException("GraphicStyle: EdgeColor components must be in [0, 1]");
            return false;
        }
    s.setEdgeColor(c);
    return true;
}

bool writeEdgeColor(osgDB::OutputStream& os, const Style& s)
{
    os << s.getEdgeColor() << std::endl;
    return true;
}

/** Reads a float in [lo, hi] or fails the read naming the property. */
bool readChecked(osgDB::InputStream& is, const char* name, float lo, float hi, float& v)
{
    is >> v;
    if (is.getException()) return false;
    if (!std::isfinite(v) || v < lo || v > hi)
    {
        is.throwException(std::string("GraphicStyle: ") + name + " " + std::to_string(v) +
                          " is out of range");
        return false;
    }
    return true;
}

bool checkEdgeStrength(const Style& s)
{
    return s.getEdgeStrength() != 0.0f;
}

bool readEdgeStrength(osgDB::InputStream& is, Style& s)
{
    float v = 0.0f;
    if (!readChecked(is, "EdgeStrength", 0.0f, 1.0f, v)) return false;
    s.setEdgeStrength(v);
    return true;
}

bool writeEdgeStrength(osgDB::OutputStream& os, const Style& s)
{
    os << s.getEdgeStrength() << std::endl;
    return true;
}

bool checkUnsharpMaskStrength(const Style& s)
{
    return s.getUnsharpMaskStrength() != 0.0f;
}

bool readUnsharpMaskStrength(osgDB::InputStream& is, Style& s)
{
    float v = 0.0f;
    if (!readChecked(is, "UnsharpMaskStrength", 0.0f, 1.0e6f, v)) return false;
    s.setUnsharpMaskStrength(v);
    return true;
}

bool writeUnsharpMaskStrength(osgDB::OutputStream& os, const Style& s)
{
    os << s.getUnsharpMaskStrength() << std::endl;
    return true;
}

bool checkUnsharpMaskRadius(const Style& s)
{
    return s.getUnsharpMaskRadius() != 8.0f;
}

bool readUnsharpMaskRadius(osgDB::InputStream& is, Style& s)
{
    float v = 0.0f;
    if (!readChecked(is, "UnsharpMaskRadius", 0.0f, 1.0e4f, v)) return false;
    s.setUnsharpMaskRadius(v);
    return true;
}

bool writeUnsharpMaskRadius(osgDB::OutputStream& os, const Style& s)
{
    os << s.getUnsharpMaskRadius() << std::endl;
    return true;
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_GraphicStyle, new osgLoA::GraphicStyle, osgLoA::GraphicStyle,
                        "osg::Object osgLoA::GraphicStyle")
{
    ADD_STRING_SERIALIZER(Description, "");
    ADD_USER_SERIALIZER(FragmentShader);
    ADD_CHECKED_OBJECT_SERIALIZER(Parameters, osg::StateSet, NULL);
    ADD_BOOL_SERIALIZER(Visible, true);
    ADD_BOOL_SERIALIZER(Opaque, false);
    ADD_BOOL_SERIALIZER(UsesTexture, true);
    ADD_USER_SERIALIZER(EdgeColor);
    ADD_USER_SERIALIZER(EdgeStrength);
    ADD_USER_SERIALIZER(UnsharpMaskStrength);
    ADD_USER_SERIALIZER(UnsharpMaskRadius);
    // Issue 19 (tree silhouettes): after the older fields.
    ADD_USER_SERIALIZER(GeometryShader);
}
