// The CityJSON 1.0 / 1.1 / 2.0 reader behind osgdb_cityjson (docs/cityjson.md): a parsed
// document in, an osg::Group of feature-carrying object Groups out.
#ifndef OSGLOA_PLUGINS_CITYJSON_CITYJSONREADER_H
#define OSGLOA_PLUGINS_CITYJSON_CITYJSONREADER_H 1

#include <osg/Group>
#include <osgDB/Options>

#include <osgLoA/util/InputLimits>

#include "IndexedOrderedMap.h"

#include <stdexcept>
#include <string>

namespace loacityjson
{

/** A problem that makes the file unreadable; the message names it (object id, index). */
class Error : public std::runtime_error
{
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/** What the option string asks for ("recenter=0 lod=2.2 theme=summer"). */
struct Settings
{
    bool recenter = true;
    std::string lod;            ///< empty: each object's highest LoD
    std::string theme;          ///< empty: the file's default theme, else the first one found
    osgLoA::InputLimits limits; ///< max-depth, max-objects, max-vertices, ... (docs/reliability.md)
    /** Parses the option string; throws Error for a malformed value. */
    void parse(const std::string& optionString);
};

/** Parses JSON within the limits: nesting deeper than limits.maxDepth or a string longer than
 *  limits.maxStringBytes throws osgLoA::InputLimitError naming `source` and the limit before
 *  anything deeper is built; malformed JSON throws nlohmann::json::exception. */
Json parseJson(std::istream& in, const std::string& source, const osgLoA::InputLimits& limits);

/** Builds the scene of a parsed CityJSON document. `sourceName` names the file in messages
 *  (the stream reader passes "<stream>"); `textureDirs` are searched, in order, for texture
 *  images before osgDB's data path. Throws Error. */
osg::ref_ptr<osg::Group> buildScene(const Json& doc, const std::string& sourceName, const Settings& settings,
                                    const osgDB::FilePathList& textureDirs, const osgDB::Options* options);

} // namespace loacityjson

#endif
