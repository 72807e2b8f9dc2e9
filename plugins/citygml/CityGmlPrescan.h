// A streaming pass over a CityGML file before libcitygml parses it (issue 22 item 1): libcitygml
// builds its objects as it parses, and a hostile file can make it work without bound (20,000
// nested BuildingParts did not finish in a minute). The pass checks, in one read of the file with
// constant memory, the InputLimits that apply before parsing: the file's size (max-file), the
// nesting of XML elements (max-depth), the coordinates of one gml:posList (max-ring-vertices)
// and of the whole file (max-vertices). It is no validating XML parser: comments, CDATA,
// processing instructions and declarations are skipped, attribute values may hold '>'.
#ifndef OSGLOA_PLUGINS_CITYGML_CITYGMLPRESCAN_H
#define OSGLOA_PLUGINS_CITYGML_CITYGMLPRESCAN_H 1

#include <osgLoA/util/InputLimits>

#include <cstdint>
#include <string>

namespace citygmlimport
{

struct PrescanResult
{
    unsigned maxDepth = 0;         ///< deepest element nesting
    std::uint64_t elements = 0;    ///< start tags
    std::uint64_t coordinates = 0; ///< numbers inside gml:posList and gml:pos
    std::uint64_t longestList = 0; ///< numbers in the longest gml:posList
};

/** Throws osgLoA::InputLimitError (InputLimits::exceeded's message, naming `label`) at the
 *  first limit exceeded, std::runtime_error when the file cannot be read. Vertices are counted
 *  as three coordinates each (srsDimension 3, CityGML's usual; a 2D list counts 2/3 of its
 *  points). */
PrescanResult prescan(const std::string& path, const std::string& label, const osgLoA::InputLimits& limits);

} // namespace citygmlimport

#endif
