#include "OsmFile.h"

#include <osgDB/FileNameUtils>

// GCC 12 reports a strlen over-read inside libosmium 2.19's OSMObjectBuilder::set_user
// (osm_object_builder.hpp:473, inlined into the Assembler here): a false positive in its code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif
#include <osmium/area/assembler.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/sparse_mem_array.hpp>
#include <osmium/io/detail/queue_util.hpp>
#include <osmium/io/pbf_input.hpp>
#include <osmium/io/xml_input.hpp>
#include <osmium/relations/relations_manager.hpp>
#include <osmium/thread/pool.hpp>
#include <osmium/visitor.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <bzlib.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <fstream>
#include <future>
#include <stdexcept>

namespace osmimport
{
namespace
{
/** osmconf.ini's "ignore" keys (every layer): dropped from an object's tags. Keys ending in ':'
 *  are prefixes. */
const char* const kIgnored[] = {"created_by", "converted_by", "source",     "time",  "ele",
                                "note",       "todo",         "openGeoDB:", "fixme", "FIXME"};
/** osmconf.ini's [points] "unsignificant" keys: a node with no other tag is no point. */
const char* const kUnsignificant[] = {"created_by", "converted_by", "source", "time", "ele", "attribution"};

bool ignored(const char* key, bool area)
{
    if (area && std::strcmp(key, "area") == 0) return true; // [multipolygons] ignores area too
    for (const char* k : kIgnored)
    {
        const std::size_t n = std::strlen(k);
        if (k[n - 1] == ':' ? std::strncmp(key, k, n) == 0 : std::strcmp(key, k) == 0) return true;
    }
    return false;
}

Tags tagsOf(const osmium::TagList& list, bool area)
{
    Tags tags;
    for (const osmium::Tag& t : list)
        if (!ignored(t.key(), area)) tags.emplace(t.key(), t.value());
    return tags;
}

bool significantNode(const osmium::TagList& list)
{
    for (const osmium::Tag& t : list)
    {
        if (ignored(t.key(), false)) continue;
        if (std::none_of(std::begin(kUnsignificant), std::end(kUnsignificant),
                         [&](const char* k) { return std::strcmp(k, t.key()) == 0; }))
            return true;
    }
    return false;
}

/** A defined location as (lon, lat); range checks are the scene builder's (it names the object). */
osg::Vec2d lonLat(const osmium::Location& l)
{
    return {l.lon_without_check(), l.lat_without_check()};
}

template <typename Nodes> Ring ringOf(const Nodes& nodes)
{
    Ring r;
    r.reserve(nodes.size());
    for (const osmium::NodeRef& n : nodes)
        if (!n.location().is_undefined()) r.push_back(lonLat(n.location()));
    return r;
}

/** Multipolygon and boundary relations with at least one way member, assembled by libosmium's
 *  Assembler once every member way has been read (GDAL made no area of an incomplete one
 *  either). The areas go to the callback given to handler(). */
class MultipolygonRelations
    : public osmium::relations::RelationsManager<MultipolygonRelations, false, true, false>
{
public:
    explicit MultipolygonRelations(ReadReport& report) : _report(report) {}

    bool new_relation(const osmium::Relation& relation) const
    {
        const char* type = relation.tags().get_value_by_key("type");
        if (!type || (std::strcmp(type, "multipolygon") != 0 && std::strcmp(type, "boundary") != 0))
            return false;
        return std::any_of(relation.members().cbegin(), relation.members().cend(),
                           [](const osmium::RelationMember& m)
                           { return m.type() == osmium::item_type::way; });
    }
    bool new_member(const osmium::Relation&, const osmium::RelationMember& member, std::size_t) const
    {
        return member.type() == osmium::item_type::way;
    }
    void complete_relation(const osmium::Relation& relation)
    {
        std::vector<const osmium::Way*> ways;
        for (const osmium::RelationMember& m : relation.members())
            if (m.ref() != 0) ways.push_back(get_member_way(m.ref()));
        osmium::area::Assembler::config_type config;
        config.create_empty_areas = false;
        try
        {
            osmium::area::Assembler assembler{config};
            if (!assembler(relation, ways, buffer())) ++_report.unassembled;
        }
        catch (const osmium::invalid_location&)
        {
            ++_report.unassembled; // a member node missing from the file
        }
    }

private:
    ReadReport& _report;
};

/** The second pass: points, lines and closed-way areas from nodes and ways (their locations set
 *  by NodeLocationsForWays before), relation areas from the MultipolygonRelations callback. */
class ObjectCollector : public osmium::handler::Handler
{
public:
    ObjectCollector(std::vector<OsmObject>& objects, const osgLoA::InputLimits& limits,
                    const std::string& file, ReadReport& report)
        : _objects(objects), _limits(limits), _file(file), _report(report)
    {
    }

    void node(const osmium::Node& node)
    {
        ++_report.nodes;
        if (_report.ways || _report.relations)
            throw std::runtime_error("node " + std::to_string(node.id()) +
                                     " comes after ways or relations; OSM files list nodes, then ways, then "
                                     "relations (`osmium sort` puts a file in that order)");
        if (!significantNode(node.tags()) || node.location().is_undefined()) return;
        OsmObject o;
        o.geometry = OsmObject::Point;
        o.sourceId = "node/" + std::to_string(node.id());
        o.tags = tagsOf(node.tags(), false);
        o.line.push_back(lonLat(node.location()));
        add(std::move(o), 1);
    }

    void way(const osmium::Way& way)
    {
        ++_report.ways;
        if (_report.relations)
            throw std::runtime_error(
                "way " + std::to_string(way.id()) +
                " comes after relations; OSM files list nodes, then ways, then relations "
                "(`osmium sort` puts a file in that order)");
        Tags t = tagsOf(way.tags(), false);
        if (t.empty()) return; // an untagged way (a multipolygon's member): nothing to classify
        Ring r = ringOf(way.nodes());
        if (r.size() < 2)
        {
            ++_report.shortWays; // GDAL's OSM driver dropped these too
            return;
        }
        OsmObject o;
        o.sourceId = "way/" + std::to_string(way.id());
        const std::size_t n = r.size();
        if (way.nodes().size() >= 4 && way.is_closed() && closedWayIsArea(t))
        {
            o.geometry = OsmObject::Area;
            t.erase("area");
            o.polygons.push_back(Polygon{std::move(r)});
        }
        else
        {
            o.geometry = OsmObject::Line;
            o.line = std::move(r);
        }
        o.tags = std::move(t);
        add(std::move(o), n);
    }

    void relation(const osmium::Relation&) { ++_report.relations; }

    void area(const osmium::Area& area)
    {
        OsmObject o;
        o.geometry = OsmObject::Area;
        o.sourceId = "relation/" + std::to_string(area.orig_id());
        o.tags = tagsOf(area.tags(), true); // the relation's tags but type (GDAL kept type)
        std::size_t n = 0;
        for (const osmium::OuterRing& outer : area.outer_rings())
        {
            Polygon p{ringOf(outer)};
            for (const osmium::InnerRing& inner : area.inner_rings(outer))
                p.push_back(ringOf(inner));
            for (const Ring& r : p)
                n += r.size();
            o.polygons.push_back(std::move(p));
        }
        if (!o.polygons.empty()) add(std::move(o), n);
    }

private:
    void add(OsmObject&& o, std::size_t vertices)
    {
        _vertices += vertices;
        if (_vertices > _limits.maxVertices)
            throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                _file, "more than " + std::to_string(_limits.maxVertices) + " vertices", "max-vertices",
                _limits.maxVertices));
        _objects.push_back(std::move(o));
        if (_objects.size() > _limits.maxObjects)
            throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                _file, "more than " + std::to_string(_limits.maxObjects) + " OpenStreetMap elements",
                "max-objects", _limits.maxObjects));
    }

    std::vector<OsmObject>& _objects;
    const osgLoA::InputLimits& _limits;
    const std::string& _file;
    ReadReport& _report;
    std::uint64_t _vertices = 0;
};

/** The format by the osgDB extension (libosmium would look at the name's suffixes, case and all). */
bool isPbf(const std::string& path)
{
    return osgDB::getLowerCaseFileExtension(path) == "pbf";
}

/** libosmium 2.19 reads a coordinate's exponent into a 64-bit integer without an overflow check
 *  (string_to_location_coordinate: lat="4.8e20" is signed overflow, undefined behaviour, and the
 *  wrapped value can pass its range check: OsmFuzzer's 600 s campaign found it). OSM writes
 *  coordinates as plain decimals, so a lat or lon attribute value with an exponent (or a
 *  character reference, which expat would turn into one) is refused before libosmium parses it.
 *  A scan of the XML bytes, fed in pieces: an attribute is " lat" or " lon" (after white space),
 *  white space, '=', white space, and a quoted value. */
class CoordinateScan
{
public:
    explicit CoordinateScan(const std::string& name) : _name(name) {}

    void feed(const char* p, std::size_t n)
    {
        for (std::size_t i = 0; i < n; ++i, ++_at)
        {
            const char c = p[i];
            const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
            switch (_state)
            {
            case Outside:
                if (_lastSpace && c == 'l') _state = L;
                break;
            case L:
                _state = c == 'a' ? LA : c == 'o' ? LO : Outside;
                break;
            case LA:
            case LO:
                _state = (c == (_state == LA ? 't' : 'n')) ? Name : Outside;
                _attribute = _state == Name ? (c == 't' ? "lat" : "lon") : "";
                break;
            case Name:
                if (c == '=')
                    _state = Equals;
                else if (!space)
                    _state = Outside;
                break;
            case Equals:
                if (c == '"' || c == '\'')
                    _quote = c, _state = Value, _value.clear(), _start = _at + 1, _bad = false;
                else if (!space)
                    _state = Outside;
                break;
            case Value:
                if (c == _quote)
                {
                    if (_bad)
                        throw std::runtime_error(
                            "'" + _name + "' has the coordinate " + _attribute + "=\"" + _value +
                            "\" (byte " + std::to_string(_start) +
                            "), written with an exponent or a character reference: OSM coordinates are plain "
                            "decimals (libosmium 2.19 overflows on large exponents)");
                    _state = Outside;
                }
                else
                {
                    _bad = _bad || c == 'e' || c == 'E' || c == '&';
                    if (_value.size() < 40) _value += c;
                }
                break;
            }
            _lastSpace = space;
        }
    }

private:
    enum State
    {
        Outside,
        L,
        LA,
        LO,
        Name,
        Equals,
        Value
    } _state = Outside;
    std::string _name, _value;
    const char* _attribute = "";
    char _quote = '"';
    bool _lastSpace = false, _bad = false;
    std::uint64_t _at = 0, _start = 0;
};

/** The coordinates of an XML source checked by CoordinateScan: the bytes in memory, or the file
 *  read once in pieces (libosmium then streams it). PBF stores integers: nothing to check. */
void checkCoordinates(const OsmSource& source)
{
    CoordinateScan scan(source.name);
    if (source.data)
    {
        scan.feed(source.data->data(), source.data->size());
        return;
    }
    if (isPbf(source.path)) return;
    std::ifstream in(source.path, std::ios::binary);
    std::vector<char> chunk(1 << 16);
    while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
        scan.feed(chunk.data(), static_cast<std::size_t>(in.gcount()));
}

} // namespace

std::vector<char> inflateBz2(const std::vector<char>& compressed, const std::string& name,
                             const osgLoA::InputLimits& limits)
{
    if (compressed.empty()) throw std::runtime_error("'" + name + "' is empty, not a bzip2 file");
    std::vector<char> out;
    std::size_t consumed = 0;
    char chunk[1 << 16];
    do // one bzip2 stream per round
    {
        bz_stream z{};
        if (BZ2_bzDecompressInit(&z, 0, 0) != BZ_OK) throw std::runtime_error("bzip2: out of memory");
        int rc = BZ_OK;
        for (;;)
        {
            if (z.avail_in == 0 && consumed < compressed.size())
            {
                const std::size_t n = std::min<std::size_t>(compressed.size() - consumed, 1u << 30);
                z.next_in = const_cast<char*>(compressed.data() + consumed);
                z.avail_in = static_cast<unsigned>(n);
                consumed += n;
            }
            z.next_out = chunk;
            z.avail_out = sizeof chunk;
            rc = BZ2_bzDecompress(&z);
            const std::size_t n = sizeof chunk - z.avail_out;
            if (out.size() + n > limits.maxInflatedBytes)
            {
                BZ2_bzDecompressEnd(&z);
                throw osgLoA::InputLimitError(osgLoA::InputLimits::exceeded(
                    name,
                    "bzip2 data inflating to more than " + std::to_string(limits.maxInflatedBytes) + " bytes",
                    "max-inflated", limits.maxInflatedBytes));
            }
            out.insert(out.end(), chunk, chunk + n);
            if (rc != BZ_OK || (n == 0 && z.avail_in == 0 && consumed == compressed.size())) break;
        }
        consumed -= z.avail_in; // what the stream did not use starts the next one
        BZ2_bzDecompressEnd(&z);
        if (rc != BZ_STREAM_END)
            throw std::runtime_error("'" + name + "' is " +
                                     (rc == BZ_DATA_ERROR_MAGIC && out.empty()
                                          ? std::string("not a bzip2 file")
                                      : rc == BZ_OK ? std::string("not valid bzip2 data (cut short)")
                                                    : std::string("not valid bzip2 data")));
    } while (consumed < compressed.size());
    if (out.empty()) throw std::runtime_error("'" + name + "' is not valid bzip2 data (nothing in it)");
    return out;
}

bool closedWayIsArea(const Tags& tags)
{
    const auto area = tags.find("area");
    if (area != tags.end())
    {
        if (area->second == "yes") return true;
        if (area->second == "no") return false;
    }
    static const char* const keys[] = {"aeroway",  "amenity", "boundary", "building", "craft",   "geological",
                                       "historic", "landuse", "leisure",  "military", "natural", "office",
                                       "place",    "shop",    "sport",    "tourism"};
    for (const char* k : keys)
        if (tags.count(k)) return true;
    const auto is = [&](const char* k, const char* v)
    {
        const auto it = tags.find(k);
        return it != tags.end() && it->second == v;
    };
    return is("highway", "platform") || is("public_transport", "platform");
}

namespace
{
/** The file at source.path, read by libosmium's reader (a reading and a parsing thread). */
std::vector<osmium::memory::Buffer> readFile(const OsmSource& source)
{
    std::vector<osmium::memory::Buffer> buffers;
    osmium::io::Reader reader(osmium::io::File(source.path, isPbf(source.path) ? "pbf" : "osm"),
                              osmium::io::read_meta::no);
    while (osmium::memory::Buffer buffer = reader.read())
        buffers.push_back(std::move(buffer));
    reader.close();
    return buffers;
}

/** XML in memory, parsed on this thread by the XML parser libosmium's reader runs (its
 *  osmium::io::detail::XMLParser, fed and drained through the queues the reader would use). The
 *  reader's two threads cost more than the parse of a small file: their start and exit were a
 *  quarter of OsmFuzzer's time under ASan. Errors come out as the reader's do (osmium::xml_error
 *  and the like, from the output queue). */
std::vector<osmium::memory::Buffer> parseXml(const std::vector<char>& xml)
{
    namespace detail = osmium::io::detail;
    detail::future_string_queue_type input(0, "raw_input"); // 0: unbounded, nothing waits
    detail::future_buffer_queue_type output(0, "parser_results");
    if (!xml.empty()) detail::add_to_queue(input, std::string(xml.data(), xml.size()));
    detail::add_end_of_data_to_queue(input);
    std::promise<osmium::io::Header> header;
    std::atomic<std::size_t> offset{0};
    detail::parser_arguments arguments{osmium::thread::Pool::default_instance(),
                                       -1,
                                       input,
                                       output,
                                       header,
                                       &offset,
                                       osmium::osm_entity_bits::all,
                                       osmium::io::read_meta::no,
                                       osmium::io::buffers_type::any,
                                       false};
    detail::XMLParser(arguments).parse(); // catches what it throws and queues it
    std::vector<osmium::memory::Buffer> buffers;
    for (;;)
    {
        std::future<osmium::memory::Buffer> next;
        output.wait_and_pop(next);
        osmium::memory::Buffer buffer = next.get(); // rethrows the parser's error
        if (!buffer) break;                         // end of data
        buffers.push_back(std::move(buffer));
    }
    return buffers;
}
} // namespace

std::vector<OsmObject> readOsmFile(const OsmSource& source, const osgLoA::InputLimits& limits,
                                   ReadReport& report)
{
    std::vector<OsmObject> objects;
    checkCoordinates(source);
    try
    {
        // The file is parsed once (XML in memory on this thread, a path by libosmium's reader)
        // and its buffers kept, in memory about the size of the XML: the relations' first pass
        // and the collection both run over them. Reading the file twice, once for
        // the relations as osmium::relations::read_relations does, cost two more threads and a
        // second parse. Without a relation the relation manager (its 1 MB buffers) is not made.
        std::vector<osmium::memory::Buffer> buffers = source.data ? parseXml(*source.data) : readFile(source);
        bool relationsPresent = false;
        for (const osmium::memory::Buffer& buffer : buffers)
            for (const osmium::OSMEntity& e : buffer.select<osmium::OSMEntity>())
                relationsPresent = relationsPresent || e.type() == osmium::item_type::relation;

        using Index = osmium::index::map::SparseMemArray<osmium::unsigned_object_id_type, osmium::Location>;
        Index positive, negative; // JOSM's new objects have negative ids
        osmium::handler::NodeLocationsForWays<Index, Index> locations(positive, negative);
        locations.ignore_errors(); // a node missing from an extract: the way keeps the others

        ObjectCollector collector(objects, limits, source.name, report);
        if (!relationsPresent)
        {
            for (osmium::memory::Buffer& buffer : buffers)
                osmium::apply(buffer, locations, collector);
            return objects;
        }
        MultipolygonRelations relations(report);
        for (osmium::memory::Buffer& buffer : buffers)
            osmium::apply(buffer, relations); // first pass: the relations and their member ways
        relations.prepare_for_lookup();
        auto& second = relations.handler([&collector](osmium::memory::Buffer&& areas)
                                         { osmium::apply(areas, collector); });
        for (osmium::memory::Buffer& buffer : buffers)
            osmium::apply(buffer, locations, collector, second); // flushes the areas made
        relations.for_each_incomplete_relation([&](const osmium::relations::RelationHandle&)
                                               { ++report.incompleteRelations; });
    }
    catch (const osgLoA::InputLimitError&)
    {
        throw;
    }
    catch (const osmium::xml_error& e)
    {
        // expat's errors have a position (at 1:0, no XML at all: not OSM); libosmium's own (an
        // element where it does not belong) have none ("Unknown top-level element": not OSM).
        const bool positioned = e.line > 0;
        const bool notOsm =
            positioned ? e.line == 1 && e.column == 0 : e.error_string.rfind("Unknown top-level", 0) == 0;
        const std::string what = positioned ? "XML error at line " + std::to_string(e.line) + ", column " +
                                                  std::to_string(e.column) + ": " + e.error_string
                                            : "XML error: " + e.error_string;
        throw std::runtime_error(
            "'" + source.name + "' " +
            (notOsm ? "is not an OpenStreetMap file (" + what + ")" : "is malformed: " + what));
    }
    catch (const std::exception& e)
    {
        throw std::runtime_error("'" + source.name + "' is malformed: " + e.what());
    }
    return objects;
}

} // namespace osmimport
