// loa-citygen: writes the built-in demo city to any format osgDB writes.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"

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
const char* kDescription =
    R"(Generates the demo city and writes it to the --out FILE in any format osgDB writes, chosen by
the extension: .osgb, .osgt, .osgx (textures embedded), .obj (with .mtl and the PNG textures
beside it), .ive, ... The write is atomic: FILE and its side files appear complete or not at
all.
)";
const char* kFooter = R"(exit status: 0 written, 1 write failed, 2 bad arguments.
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
            loa::CommandLine cl("loa-citygen", "loa-citygen --out FILE [-O \"K=V ...\"] [--seed N] [--small]",
                                kDescription);
            CLI::App& app = cl.app();
            loa::addReaderOptions(app, city);
            loa::addOutFile(app, output, "the model file to write (required)");
            app.add_option_function<std::string>(
                   "--seed",
                   [&](const std::string& t)
                   { city += " seed=" + std::to_string(loa::parseCount("--seed", t, 4294967295u)); },
                   "shorthand for -O seed=N")
                ->type_name("N");
            app.add_flag("--small", small,
                         "start from the small test city (4x3 blocks) instead of the default");
            cl.footer(kFooter);
            cl.parse(argc, argv);
            if (output.empty()) throw loa::UsageError("no --out FILE given (see --help)");
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
                throw loa::UsageError(std::string("-O (demo city parameters): ") + e.what());
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
