// libFuzzer target: arbitrary bytes as an OpenStreetMap file, in process (issue 22 item 5). The
// OSM importer's sources are compiled into the fuzzer, so its reader registers itself with osgDB
// (REGISTER_OSGPLUGIN) and osgDB reads the input through it as osgconv would, within the default
// InputLimits. The first input byte chooses the form (its value modulo 3): 0, XML (map.osm);
// 1, the rest compressed with bzip2 here (map.osm.bz2), so that the fuzzer's mutations of the XML
// reach the inflater and the XML path both; 2, the rest is a .osm.bz2 file as it is (a bzip2
// bomb: tests/fuzz/crashes/osm/). A read
// must succeed or fail with a message; the scene is validated (osgLoA::ModelValidation) and its
// bound must be finite. Seed corpus: tests/fuzz/corpus/osm.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=OsmFuzzer).
#include <osgLoA/util/ModelValidation>

#include <osg/Notify>
#include <osgDB/Registry>

#include <bzlib.h>
#include <cmath>
#include <cpl_conv.h>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
std::string scratch(const char* name)
{
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp && *tmp ? tmp : "/tmp") + "/osgloa-osmfuzz-" + std::to_string(::getpid()) + "-" +
           name;
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    // GDAL's OSM driver sets up a 100 MB in-memory node index per file by default; a small one
    // (spilling to a temporary file beyond 1 MB, which a fuzz input never reaches) is what
    // makes thousands of opens a minute possible.
    CPLSetConfigOption("OSM_MAX_TMPFILE_SIZE", "1");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1) return 0;
    const int form = data[0] % 3;
    std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
    const std::string path = scratch(form ? "map.osm.bz2" : "map.osm");
    if (form == 1)
    {
        std::vector<char> out(bytes.size() + bytes.size() / 100 + 700);
        unsigned int outSize = static_cast<unsigned int>(out.size());
        if (BZ2_bzBuffToBuffCompress(out.data(), &outSize, bytes.data(),
                                     static_cast<unsigned int>(bytes.size()), 1, 0, 0) != BZ_OK)
            return 0;
        bytes.assign(out.data(), outSize);
    }
    std::ofstream(path, std::ios::binary) << bytes;
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options("max-inflated=50000000");
    osgDB::ReaderWriter::ReadResult rr = osgDB::Registry::instance()->readNode(path, options.get());
    std::remove(path.c_str());
    if (!rr.validNode())
    {
        if (rr.message().empty() && rr.status() != osgDB::ReaderWriter::ReadResult::FILE_NOT_HANDLED &&
            rr.status() != osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND)
            std::abort(); // a failure must say why
        return 0;
    }
    osgLoA::ModelValidation::validate(*rr.getNode(), path);
    const osg::BoundingSphere bs = rr.getNode()->getBound();
    if (bs.valid() && !(std::isfinite(bs.radius()) && std::isfinite(bs.center().length()))) std::abort();
    return 0;
}
