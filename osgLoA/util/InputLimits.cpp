#include <osgLoA/util/InputLimits>

#include <osgDB/ReaderWriter>

#include <sstream>
#include <stdexcept>

namespace osgLoA
{
namespace
{
struct Key
{
    const char* name;
    const char* help;
};
const Key kKeys[] = {
    {"max-depth", "nesting of JSON values, .loa files and pseudo-loader chains (default 64)"},
    {"max-objects", "city objects, OSM elements or .loa models in one file (default 2000000)"},
    {"max-vertices", "vertices in one file (default 100000000)"},
    {"max-ring-vertices", "vertices of one polygon ring (default 100000)"},
    {"max-crossings", "edge crossings within one polygon, which tessellation pays for (default 1000)"},
    {"max-hierarchy", "depth of a parent/child chain of city objects (default 32)"},
    {"max-string", "bytes of one string: a name, an attribute (default 1048576)"},
    {"max-inflated", "bytes a compressed input (.osm.bz2) may inflate to (default 1073741824)"},
    {"max-file", "bytes of one input file (default 4294967296)"},
};

std::uint64_t parseLimit(const std::string& key, const std::string& value)
{
    if (value.empty() || value.size() > 19 || value.find_first_not_of("0123456789") != std::string::npos)
        throw std::invalid_argument("option " + key + "=" + value + ": expected a positive integer");
    const std::uint64_t v = std::stoull(value);
    if (v == 0) throw std::invalid_argument("option " + key + "=0: a limit must be at least 1");
    return v;
}
} // namespace

InputLimits InputLimits::fromOptions(const std::string& optionString)
{
    InputLimits l;
    std::istringstream in(optionString);
    for (std::string token; in >> token;)
    {
        const std::size_t eq = token.find('=');
        if (eq == std::string::npos || token.compare(0, 4, "max-") != 0) continue;
        const std::string key = token.substr(0, eq), value = token.substr(eq + 1);
        const auto small = [&](std::uint64_t v)
        {
            if (v > 0xffffffffu) throw std::invalid_argument("option " + key + "=" + value + ": too large");
            return static_cast<unsigned>(v);
        };
        if (key == "max-depth")
            l.maxDepth = small(parseLimit(key, value));
        else if (key == "max-objects")
            l.maxObjects = parseLimit(key, value);
        else if (key == "max-vertices")
            l.maxVertices = parseLimit(key, value);
        else if (key == "max-ring-vertices")
            l.maxRingVertices = small(parseLimit(key, value));
        else if (key == "max-crossings")
            l.maxCrossings = small(parseLimit(key, value));
        else if (key == "max-hierarchy")
            l.maxHierarchy = small(parseLimit(key, value));
        else if (key == "max-string")
            l.maxStringBytes = parseLimit(key, value);
        else if (key == "max-inflated")
            l.maxInflatedBytes = parseLimit(key, value);
        else if (key == "max-file")
            l.maxFileBytes = parseLimit(key, value);
        // other max-* keys belong to other readers (e.g. loa-prefilter's own options)
    }
    return l;
}

void InputLimits::declareOptions(osgDB::ReaderWriter& reader)
{
    for (const Key& k : kKeys)
        reader.supportsOption(std::string(k.name) + "=N", std::string("limit: ") + k.help);
}

std::string InputLimits::exceeded(const std::string& source, const std::string& what, const char* key,
                                  std::uint64_t limit)
{
    return source + ": " + what + " exceeds the limit " + key + "=" + std::to_string(limit) +
           " (raise it with -O " + key + "=N)";
}

} // namespace osgLoA
