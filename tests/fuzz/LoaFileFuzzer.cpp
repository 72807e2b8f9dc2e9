// libFuzzer target: arbitrary bytes as a .loa file (JSON: models, scenario, rules, options), read
// through osgDB by the .loa plugin (osgdb_loa from the build's lib/, instrumented in the fuzz
// build) as osgviewer reads one (issue 22 items 1, 5). (Not compiled in: osgDB would load the
// module as well when a read fails, and two copies of the plugin keep two read stacks, whose
// nesting guards then let a pseudo-loader chain branch at every level.) The file lies in a scratch folder
// beside a small model (city.osgb, named parts, no features) and a rule set (rules.osgt), so the inputs that
// name them reach classification, scenario binding and the LoA node; the nesting and cycle
// guards meet inputs that name the .loa file itself (input.loa, input.loa.loa, ...). A read must
// give a LoA node whose bound is finite, or fail with a message.
//
// Build and run: scripts/fuzz (FUZZ_TARGETS=LoaFileFuzzer). Seed corpus: tests/fuzz/corpus/loa.
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/transitions/LoANode>

#include <osg/Notify>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include "FuzzSupport.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <sys/stat.h>

namespace
{
const char* const kTarget = "LoaFileFuzzer";

std::string folder()
{
    static const std::string dir = []
    {
        const std::string d = fuzz::scratch("loa");
        ::mkdir(d.c_str(), 0700);
        if (!osgDB::writeNodeFile(*fuzz::smallCity(false), d + "/city.osgb"))
            fuzz::fail(kTarget, "cannot write the scratch model " + d + "/city.osgb");
        osgLoA::ClassificationRuleSet::assemble({}, false, false)->write(d + "/rules.osgt");
        return d;
    }();
    return dir;
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    osg::setNotifyLevel(osg::FATAL);
    if (!osgDB::Registry::instance()->getReaderWriterForExtension("loa"))
        fuzz::fail(kTarget, "no .loa reader (is OSG_LIBRARY_PATH the build's lib?)");
    folder();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string path = folder() + "/input.loa";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    osgDB::Registry::instance()->clearObjectCache();
    osgDB::ReaderWriter::ReadResult rr = osgDB::Registry::instance()->readNode(path, nullptr, false);
    if (!rr.validNode())
    {
        if (rr.message().empty()) fuzz::fail(kTarget, "a failed read without a message");
        return 0;
    }
    if (!dynamic_cast<osgLoA::LoANode*>(rr.getNode())) fuzz::fail(kTarget, "the read gave no LoA node");
    fuzz::requireFiniteBound(kTarget, *rr.getNode());
    return 0;
}
