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
    if (form == 1)
    {
        std::vector<char> out(bytes.size() + bytes.size() / 100 + 700);
        unsigned int outSize = static_cast<unsigned int>(out.size());
        if (BZ2_bzBuffToBuffCompress(out.data(), &outSize, bytes.data(),
                                     static_cast<unsigned int>(bytes.size()), 1, 0, 0) != BZ_OK)
            return 0;
        out.resize(outSize);
        bytes.swap(out);
    }
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
