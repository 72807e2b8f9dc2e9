// Serializer wrapper for osgLoA::PaletteHierarchy (.osgt/.osgb/.osgx). The linkage reads by name
// only (EnumByNameSerializer); the colour table is "Colors N { r g b weight ... }" and the
// merges "Merges N-1 { first second distance ... }", counts bounded (kMaxListValues). The merged
// colours and weights are not written: setMerges recomputes them from the table, and refuses a
// merge list that is not a tree over the table (the read fails with its message).
#include <osgLoA/palette/PaletteHierarchy>

#include "BoundedListSerializer.h"
#include "EnumByNameSerializer.h"

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <stdexcept>

namespace
{
typedef osgLoA::PaletteHierarchy Hierarchy;

bool checkColors(const Hierarchy& h)
{
    return !h.getColors().empty();
}

bool readColors(osgDB::InputStream& is, Hierarchy& h)
{
    const unsigned size = is.readSize();
    if (is.getException()) return false;
    if (size > osgLoA::kMaxListValues)
    {
        is.throwException("PaletteHierarchy: Colors count " + std::to_string(size) +
                          " is above the limit of " + std::to_string(osgLoA::kMaxListValues));
        return false;
    }
    Hierarchy::Colors colors(size);
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
        is >> colors[i].rgb >> colors[i].weight;
    if (is.getException())
    {
        if (!is.isBinary()) is.advanceToCurrentEndBracket();
        return false;
    }
    is >> is.END_BRACKET;
    try
    {
        h.setColors(colors);
    }
    catch (const std::invalid_argument& e)
    {
        is.throwException(std::string("PaletteHierarchy: ") + e.what());
        return false;
    }
    return true;
}

bool writeColors(osgDB::OutputStream& os, const Hierarchy& h)
{
    const Hierarchy::Colors& colors = h.getColors();
    os.writeSize(static_cast<unsigned int>(colors.size()));
    os << os.BEGIN_BRACKET << std::endl;
    for (const osgLoA::WeightedColor& c : colors)
        os << c.rgb << c.weight << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}

bool checkMerges(const Hierarchy& h)
{
    return !h.getMerges().empty();
}

bool readMerges(osgDB::InputStream& is, Hierarchy& h)
{
    const unsigned size = is.readSize();
    if (is.getException()) return false;
    if (size > osgLoA::kMaxListValues)
    {
        is.throwException("PaletteHierarchy: Merges count " + std::to_string(size) +
                          " is above the limit of " + std::to_string(osgLoA::kMaxListValues));
        return false;
    }
    Hierarchy::Merges merges(size);
    is >> is.BEGIN_BRACKET;
    for (unsigned i = 0; i < size && !is.getException(); ++i)
        is >> merges[i].first >> merges[i].second >> merges[i].distance;
    if (is.getException())
    {
        if (!is.isBinary()) is.advanceToCurrentEndBracket();
        return false;
    }
    is >> is.END_BRACKET;
    try
    {
        h.setMerges(merges);
    }
    catch (const std::invalid_argument& e)
    {
        is.throwException(std::string("PaletteHierarchy: ") + e.what());
        return false;
    }
    return true;
}

bool writeMerges(osgDB::OutputStream& os, const Hierarchy& h)
{
    const Hierarchy::Merges& merges = h.getMerges();
    os.writeSize(static_cast<unsigned int>(merges.size()));
    os << os.BEGIN_BRACKET << std::endl;
    for (const Hierarchy::Merge& m : merges)
        os << m.first << m.second << m.distance << std::endl;
    os << os.END_BRACKET << std::endl;
    return true;
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_PaletteHierarchy, new osgLoA::PaletteHierarchy, osgLoA::PaletteHierarchy,
                        "osg::Object osgLoA::PaletteHierarchy")
{
    BEGIN_ENUM_BY_NAME_SERIALIZER(Linkage, WARD);
    ADD_ENUM_VALUE(WARD);
    ADD_ENUM_VALUE(CENTROID);
    END_ENUM_SERIALIZER();
    ADD_USER_SERIALIZER(Colors); // before Merges: setColors clears the merges
    ADD_USER_SERIALIZER(Merges);
}
