// libFuzzer target: arbitrary bytes as an OpenStreetMap file, in process (issue 22 item 5), through
// the steps osgdb_osm takes after it has read the file's bytes: inflateBz2 for .osm.bz2,
// readOsmFile (libosmium's XML parser, our element collector and multipolygon assembly) and
// buildScene, within the default InputLimits but max-inflated=50000000. The first input byte
// chooses the form (its value modulo 3): 0, XML; 1, the rest compressed with bzip2 here, so that
// the fuzzer's mutations of the XML reach the inflater and the XML path both; 2, the rest is
// .osm.bz2 data as it is (a bzip2 bomb: tests/fuzz/crashes/osm/). A read must succeed or fail
// with an exception (the plugin's message); the scene is validated (osgLoA::ModelValidation) and
// its bound must be finite. Seed corpus: tests/fuzz/corpus/osm. The file reading itself (the
// plugin's readWhole, libosmium's read thread for a plain .osm) is not fuzzed: it does not look
// at the bytes.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=OsmFuzzer).
#include <osgLoA/util/ModelValidation>

#include <osg/Notify>

#include "../../plugins/osm/OsmFile.h"
#include "../../plugins/osm/OsmScene.h"
#include "FuzzSupport.h"

#include <bzlib.h>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace
{
/** bzip2's work memory for compress(), kept between inputs: compressing at block size 1 takes
 *  1.1 MB of it, which malloc'ed and freed for every input (BZ2_bzBuffToBuffCompress) cost this
 *  target a sixth of its time in page faults under ASan. Only the harness compresses here; the
 *  reader's inflateBz2 allocates as it does in the plugin. */
alignas(16) unsigned char workMemory[3u << 20];
std::size_t workUsed = 0;

void* workAlloc(void*, int items, int size)
{
    const std::size_t n = (std::size_t(items) * std::size_t(size) + 15) & ~std::size_t(15);
    if (items < 0 || size < 0 || n > sizeof workMemory - workUsed) return nullptr; // BZ_MEM_ERROR
    void* p = workMemory + workUsed;
    workUsed += n;
    return p;
}
void workFree(void*, void*) {}

/** bytes compressed with bzip2 (block size 1), in place; false when bzip2 fails. */
bool compress(std::vector<char>& bytes)
{
    std::vector<char> out(bytes.size() + bytes.size() / 100 + 700);
    bz_stream s{};
    s.bzalloc = workAlloc;
    s.bzfree = workFree;
    workUsed = 0;
    if (BZ2_bzCompressInit(&s, 1, 0, 0) != BZ_OK) return false;
    s.next_in = bytes.data();
    s.avail_in = static_cast<unsigned int>(bytes.size());
    s.next_out = out.data();
    s.avail_out = static_cast<unsigned int>(out.size());
    const int status = BZ2_bzCompress(&s, BZ_FINISH);
    BZ2_bzCompressEnd(&s);
    if (status != BZ_STREAM_END) return false;
    out.resize(out.size() - s.avail_out);
    bytes.swap(out);
    return true;
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1) return 0;
    const int form = data[0] % 3;
    std::vector<char> bytes(reinterpret_cast<const char*>(data + 1),
                            reinterpret_cast<const char*>(data + size));
    if (form == 1 && !compress(bytes)) return 0;
    const osgLoA::InputLimits limits = osgLoA::InputLimits::fromOptions("max-inflated=50000000");
    osg::ref_ptr<osg::Group> scene;
    try
    {
        std::vector<char> xml =
            form ? osmimport::inflateBz2(bytes, "<fuzz>.osm.bz2", limits) : std::move(bytes);
        osmimport::OsmSource source;
        source.name = "<fuzz>";
        source.data = &xml;
        osmimport::ReadReport read;
        std::vector<osmimport::OsmObject> objects = osmimport::readOsmFile(source, limits, read);
        osmimport::ImportReport report;
        scene = osmimport::buildScene(objects, osmimport::ImportOptions(), report);
    }
    catch (const std::exception& e)
    {
        if (!*e.what()) fuzz::fail("OsmFuzzer", "an error without a message"); // a failure must say why
        return 0;
    }
    osgLoA::ModelValidation::validate(*scene, "<fuzz>");
    fuzz::requireFiniteBound("OsmFuzzer", *scene);
    return 0;
}
