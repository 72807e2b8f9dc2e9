// loa-citygen: writes the built-in demo city to any format osgDB writes.
#include "../common/AppSupport.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>
#include <osgLoA/util/SceneStatistics>
#include <osgLoA/util/StateSetVisitor>

#include <osgDB/FileNameUtils>
#include <osgDB/Registry>

#include <iostream>
#include <set>

namespace
{
const char* kHelp = R"(usage: loa-citygen OUTPUT [--city "K=V ..."] [--seed N] [--small]

Generates the demo city and writes it to OUTPUT in any format osgDB writes, chosen by the
extension: .osgb, .osgt, .osgx (textures embedded), .obj (with .mtl and the PNG textures
beside it), .ive, ... The write is atomic: OUTPUT and its side files appear complete or not
at all.

options:
  --city "K=V ..."  generator parameters, e.g. "seed=7 blocksX=6 blocksY=4 river=false"
                    (all keys: docs/demo-city.md)
  --seed N          shorthand for --city seed=N
  --small           start from the small test city (4x3 blocks) instead of the default
  --help            this text

exit status: 0 written, 1 write failed, 2 bad arguments.
)";

} // namespace

int main(int argc, char** argv)
{
    return loa::runTool(
        "loa-citygen",
        [&]() -> int
        {
            std::string output, city;
            bool small = false;
            loa::Args args(argc, argv);
            while (!args.empty())
            {
                const std::string a = args.next();
                loa::exitOnHelpOrVersion(a, "loa-citygen", kHelp);
                if (a == "--city")
                    city += " " + args.value(a);
                else if (a == "--seed")
                    city += " seed=" + std::to_string(loa::parseCount(a, args.value(a), 4294967295u));
                else if (a == "--small")
                    small = true;
                else if (!a.empty() && a[0] == '-')
                    throw loa::UsageError("unknown option '" + a + "' (see --help)");
                else if (output.empty())
                    output = a;
                else
                    throw loa::UsageError("more than one output given");
            }
            if (output.empty()) throw loa::UsageError("no OUTPUT file given (see --help)");
            const std::string ext = osgDB::getLowerCaseFileExtension(output);
            osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension(ext);
            if (!rw || !(rw->supportedFeatures() & osgDB::ReaderWriter::FEATURE_WRITE_NODE))
                throw loa::UsageError("no osgDB plugin writes '." + ext + "' scene files");

            osgLoA::CityParameters params =
                small ? osgLoA::CityParameters::small() : osgLoA::CityParameters();
            try
            {
                params.parse(city);
                params.validate();
            }
            catch (const std::invalid_argument& e)
            {
                throw loa::UsageError(std::string("--city: ") + e.what());
            }
            osg::ref_ptr<osg::Group> scene = osgLoA::CityGenerator(params).generate();
            const osgLoA::SceneStatistics stats = osgLoA::SceneStatistics::collect(*scene);

            osg::ref_ptr<osgDB::Options> options = new osgDB::Options;
            const bool native = ext == "osgb" || ext == "osgt" || ext == "osgx" || ext == "ive";
            if (native) options->setOptionString(ext == "ive" ? "" : "WriteImageHint=IncludeData");
            options->setPluginStringData("fileNameOnly", "true");
            const std::set<osg::Image*> images = osgLoA::StateSetVisitor::textureImages(*scene);
            osgLoA::AtomicFile::write(
                output,
                [&](const std::string& temp)
                {
                    if (!native) // formats that reference textures by file name get them beside the model
                        for (osg::Image* img : images)
                            osgLoA::ImageFile::write(
                                osgDB::concatPaths(osgDB::getFilePath(temp), img->getFileName()), *img);
                    return osgDB::Registry::instance()->writeNode(*scene, temp, options.get()).success();
                });
            std::cout << "wrote " << output << ": " << stats.summary() << "\n"
                      << "parameters: " << params.toString() << "\n";
            return loa::kOk;
        });
}
