// The command line every tool shares (issue 18 item 6), on CLI11 (Debian's libcli11-dev): one
// option group per concept, defined once, so that every tool spells the same thing the same way
// and its --help is made from the options it really accepts.
//
// Spelling rules (docs/command-line.md):
//   MODEL...            input models are positional, several allowed (one scene)
//   -O, --options TEXT  options for the models' readers, demo-city parameters included
//   --camera, --eye, --center, --up   the view;  --size WxH (default 1280x720)
//   --out FILE          the one file a tool makes;  --out-dir DIR  the folder of a tool that makes
//                       several files;  --image/--stats/--save FILE  further outputs beside them
//   --scenario NAME|FILE, --rules/--rules-only/--override   LoA scenario and classification
#ifndef OSGLOA_APPS_COMMANDLINE_H
#define OSGLOA_APPS_COMMANDLINE_H 1

#include "AppSupport.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace loa
{

/** The image size of every rendering tool unless --size says otherwise. */
constexpr int kDefaultWidth = 1280;
constexpr int kDefaultHeight = 720;

/** A tool's command line: a CLI11 App with the project's help layout and error messages. */
class CommandLine
{
public:
    /** usage: the synopsis after "usage: "; description: the text under it (printed as written). */
    CommandLine(const char* tool, const std::string& usage, const std::string& description);

    CLI::App& app() { return *_app; }

    /** A command of a tool with commands (loa-scenario): a CLI11 subcommand laid out the same way. */
    CLI::App* command(const std::string& name, const std::string& usage, const std::string& summary,
                      const std::string& description);

    /** Text printed after the options (exit status, notes), as written. */
    void footer(const std::string& text);

    /** Parses argv. --help prints the help (of the command given, if any) and --version the
     *  version, and both exit 0; every other problem is a UsageError with one clear sentence:
     *  "unknown option '--x' (see --help)", "--size needs a value", "--size given twice", ... */
    void parse(int argc, char** argv);

private:
    const char* _tool;
    std::unique_ptr<CLI::App> _app;
};

/** The help layout's per-option usage line, e.g. "--size WxH". */
std::string optionUsage(const CLI::Option& option);

// The shared option groups. Each adds its options to `app` (the tool or one of its commands)
// under a group heading, with the same names, value names, descriptions and checks everywhere.

/** MODEL... positional: the input models, drawn or classified as one scene. */
CLI::Option* addModels(CLI::App& app, std::vector<std::string>& models, const std::string& description);
/** -O/--options TEXT (repeatable, joined with spaces). */
void addReaderOptions(CLI::App& app, std::string& readerOptions);
/** --camera NAME, --eye/--center/--up X,Y,Z; checkCameraOptions runs after the parse. */
void addCamera(CLI::App& app, CameraChoice& choice);
/** --size WxH into width/height (the caller sets the default, normally kDefaultWidth x
 *  kDefaultHeight); `what` names the image ("the image", "the debug image"). */
void addSize(CLI::App& app, int& width, int& height, const std::string& what);
/** --rules FILE, --rules-only FILE (repeatable, not mixed), --override. */
void addRules(CLI::App& app, RulesChoice& rules);
/** --scenario NAME|FILE. */
CLI::Option* addScenario(CLI::App& app, std::string& scenario, const std::string& description);
/** --out FILE or --out-dir DIR in the output group. */
CLI::Option* addOutFile(CLI::App& app, std::string& file, const std::string& description);
CLI::Option* addOutDir(CLI::App& app, std::string& dir, const std::string& description);

/** An unsigned option NAME N checked by parseCount (at most max) and at least min
 *  ("NAME must be at least MIN" otherwise). */
CLI::Option* addCount(CLI::App& app, const std::string& name, unsigned& value, unsigned min, unsigned max,
                      const std::string& description);
/** --list-filters: prints every registered image filter with its description and exits 0. */
void addListFilters(CLI::App& app, const std::string& description);

/** Group headings. */
extern const char* const kGroupModel;
extern const char* const kGroupCamera;
extern const char* const kGroupOutput;
extern const char* const kGroupClassification;
extern const char* const kGroupOptions;

} // namespace loa

#endif
