#include "CommandLine.h"

#include <osgLoA/Version>
#include <osgLoA/filtering/FilterRegistry>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

namespace loa
{

const char* const kGroupModel = "model";
const char* const kGroupCamera = "camera";
const char* const kGroupOutput = "output";
const char* const kGroupClassification = "classification";
const char* const kGroupOptions = "options";

namespace
{
constexpr std::size_t kHelpWidth = 96;  ///< help lines are at most this wide
constexpr std::size_t kNameColumn = 24; ///< where option descriptions start

/** Thrown by --version's callback: parse prints the version and exits 0. */
struct VersionRequest
{
};

/** Wraps text at spaces to lines of at most `width` characters; '\n' starts a new line. */
std::string wrap(const std::string& text, std::size_t width)
{
    std::string out;
    std::istringstream paragraphs(text);
    std::string paragraph;
    bool firstParagraph = true;
    while (std::getline(paragraphs, paragraph))
    {
        if (!firstParagraph) out += '\n';
        firstParagraph = false;
        std::istringstream words(paragraph);
        std::string word, line;
        while (words >> word)
        {
            if (!line.empty() && line.size() + 1 + word.size() > width)
            {
                out += line + '\n';
                line.clear();
            }
            line += (line.empty() ? "" : " ") + word;
        }
        out += line;
    }
    return out;
}

/** The project's help layout: "usage: ...", the description, then the positional arguments,
 *  each option group, the commands and the footer; option descriptions wrapped at kHelpWidth. */
class HelpFormatter : public CLI::Formatter
{
public:
    std::map<const CLI::App*, std::string> usages;    ///< synopsis per app (tool or command)
    std::map<const CLI::App*, std::string> summaries; ///< one line per command, for the list
    std::map<const CLI::App*, std::string> footers;

    std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode) const override
    {
        std::ostringstream out;
        out << "usage: " << lookup(usages, app) << "\n";
        if (!app->get_description().empty()) out << "\n" << app->get_description();
        out << make_positionals(app) << groupsOf(app) << make_subcommands(app, CLI::AppFormatMode::Normal);
        const std::string footer = lookup(footers, app);
        if (!footer.empty()) out << "\n" << footer;
        return out.str();
    }

    std::string make_positionals(const CLI::App* app) const override
    {
        const std::vector<const CLI::Option*> opts =
            app->get_options([](const CLI::Option* opt) { return opt->get_positional(); });
        return opts.empty() ? std::string() : make_group("arguments", true, opts);
    }

    std::string make_group(std::string group, bool isPositional,
                           std::vector<const CLI::Option*> opts) const override
    {
        std::ostringstream out;
        out << "\n" << group << ":\n";
        for (const CLI::Option* opt : opts)
            out << make_option(opt, isPositional);
        return out.str();
    }

    std::string groupsOf(const CLI::App* app) const
    {
        // The shared groups first, in this order, then the tool's own options.
        std::vector<std::string> groups = {kGroupModel, kGroupClassification, kGroupCamera, kGroupOutput};
        for (const std::string& group : app->get_groups())
            if (std::find(groups.begin(), groups.end(), group) == groups.end()) groups.push_back(group);
        std::string out;
        for (const std::string& group : groups)
        {
            const std::vector<const CLI::Option*> opts =
                app->get_options([&group](const CLI::Option* opt)
                                 { return opt->get_group() == group && opt->nonpositional(); });
            if (!group.empty() && !opts.empty()) out += make_group(group, false, opts);
        }
        return out;
    }

    std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode) const override
    {
        const std::vector<const CLI::App*> commands = app->get_subcommands({});
        if (commands.empty()) return std::string();
        std::ostringstream out;
        out << "\ncommands (" << app->get_name() << " COMMAND --help describes each):\n";
        const std::string tool = app->get_name() + " ";
        for (const CLI::App* command : commands)
        {
            std::string usage = lookup(usages, command);
            if (usage.compare(0, tool.size(), tool) == 0) usage = usage.substr(tool.size());
            out << formatEntry(usage, lookup(summaries, command));
        }
        return out.str();
    }

    std::string make_option(const CLI::Option* opt, bool isPositional) const override
    {
        return formatEntry(isPositional ? positionalName(*opt) : optionUsage(*opt), opt->get_description());
    }

private:
    static std::string lookup(const std::map<const CLI::App*, std::string>& map, const CLI::App* app)
    {
        const auto it = map.find(app);
        return it == map.end() ? std::string() : it->second;
    }

    static std::string positionalName(const CLI::Option& opt)
    {
        // "FILE_EDIT" shows as "FILE EDIT..." (CLI11 names have no spaces).
        std::string name = opt.get_name();
        std::replace(name.begin(), name.end(), '_', ' ');
        return name + (opt.get_items_expected_max() > 1 ? "..." : "");
    }

    /** "  NAME" padded to the description column (or on a line of its own when longer), then the
     *  description wrapped, its continuation lines indented to the column. */
    static std::string formatEntry(const std::string& name, const std::string& description)
    {
        std::string out = "  " + name;
        if (description.empty()) return out + "\n";
        if (out.size() + 2 > kNameColumn)
            out += "\n" + std::string(kNameColumn, ' ');
        else
            out += std::string(kNameColumn - out.size(), ' ');
        const std::string text = wrap(description, kHelpWidth - kNameColumn);
        for (const char c : text)
        {
            out += c;
            if (c == '\n') out += std::string(kNameColumn, ' ');
        }
        return out + "\n";
    }
};

std::shared_ptr<HelpFormatter> formatterOf(const CLI::App& app)
{
    return std::static_pointer_cast<HelpFormatter>(app.get_formatter());
}

/** The option name of a CLI11 message such as "--size: 1 required TEXT missing". */
std::string optionOfMessage(const std::string& what)
{
    const auto colon = what.find(':');
    return colon == std::string::npos ? std::string() : what.substr(0, colon);
}

/** Throws UsageError for the first argument no option or positional took. */
void rejectExtras(const CLI::App& app)
{
    const std::vector<const CLI::App*> commands = app.get_subcommands({});
    if (!commands.empty() && app.get_subcommands().empty() && !app.remaining().empty() &&
        app.remaining().front()[0] != '-')
    {
        std::string known;
        for (const CLI::App* c : commands)
            known += (known.empty() ? "" : ", ") + c->get_name();
        throw UsageError("unknown command '" + app.remaining().front() + "' (" + known + "; see --help)");
    }
    for (const std::string& extra : app.remaining())
    {
        if (extra.size() > 1 && extra[0] == '-')
            throw UsageError("unknown option '" + extra + "' (see --help)");
        throw UsageError("unexpected argument '" + extra + "' (see --help)");
    }
    for (const CLI::App* command : app.get_subcommands())
        rejectExtras(*command);
}
} // namespace

std::string optionUsage(const CLI::Option& option)
{
    std::string names;
    for (const std::string& s : option.get_snames())
        names += (names.empty() ? "-" : ", -") + s;
    for (const std::string& l : option.get_lnames())
        names += (names.empty() ? "--" : ", --") + l;
    if (option.get_expected_max() == 0 || option.get_type_size_max() == 0) return names;
    return names + " " + option.get_type_name();
}

CommandLine::CommandLine(const char* tool, const std::string& usage, const std::string& description)
    : _tool(tool), _app(new CLI::App(description, tool))
{
    auto formatter = std::make_shared<HelpFormatter>();
    formatter->usages[_app.get()] = usage;
    _app->formatter(formatter);
    _app->allow_extras();
    _app->fallthrough(); // a command takes the tool's own options too (--version after a command)
    _app->option_defaults()->group(kGroupOptions);
    _app->set_help_flag("-h,--help", "print this help and exit")->group(kGroupOptions);
    _app->add_flag_callback(
            "--version", [] { throw VersionRequest(); }, "print the version and exit")
        ->group(kGroupOptions)
        ->trigger_on_parse();
    _app->add_flag_callback(
            "--verbose", [] { setVerbose(true); },
            "show the libraries' notices too (OpenSceneGraph, GDAL); without it only warnings and errors")
        ->group(kGroupOptions)
        ->trigger_on_parse();
}

CLI::App* CommandLine::command(const std::string& name, const std::string& usage, const std::string& summary,
                               const std::string& description)
{
    CLI::App* command = _app->add_subcommand(name, description);
    auto formatter = formatterOf(*_app);
    formatter->usages[command] = std::string(_tool) + " " + usage;
    formatter->summaries[command] = summary;
    command->formatter(formatter);
    command->allow_extras();
    command->option_defaults()->group(kGroupOptions);
    command->get_help_ptr()->group(kGroupOptions);
    return command;
}

void CommandLine::footer(const std::string& text)
{
    formatterOf(*_app)->footers[_app.get()] = text;
}

void CommandLine::parse(int argc, char** argv)
{
    try
    {
        _app->parse(argc, argv);
    }
    catch (const VersionRequest&)
    {
        std::cout << _tool << " " << osgLoAGetVersion() << "\n";
        std::exit(kOk);
    }
    catch (const CLI::CallForHelp&)
    {
        std::cout << _app->help();
        std::exit(kOk);
    }
    catch (const CLI::ArgumentMismatch& e)
    {
        rejectExtras(*_app);
        const std::string what = e.what(), option = optionOfMessage(what);
        if (what.find("missing") != std::string::npos) throw UsageError(option + " needs a value");
        if (what.find("At Most") != std::string::npos || what.find("at most") != std::string::npos)
            throw UsageError(option + " given more than once");
        throw UsageError(what);
    }
    catch (const CLI::RequiredError& e)
    {
        rejectExtras(*_app);
        std::string what = e.what();
        if (what == "A subcommand is required")
        {
            std::string known;
            for (const CLI::App* c : _app->get_subcommands({}))
                known += (known.empty() ? "" : ", ") + c->get_name();
            what = "no COMMAND given (" + known + "; see --help)";
        }
        throw UsageError(what + (what.find("--help") == std::string::npos ? " (see --help)" : ""));
    }
    catch (const CLI::ParseError& e)
    {
        rejectExtras(*_app);
        throw UsageError(e.what());
    }
    rejectExtras(*_app);
}

CLI::Option* addModels(CLI::App& app, std::vector<std::string>& models, const std::string& description)
{
    return app.add_option("MODEL", models, description)->group(kGroupModel);
}

CLI::Option* addCount(CLI::App& app, const std::string& name, unsigned& value, unsigned min, unsigned max,
                      const std::string& description)
{
    return app
        .add_option_function<std::string>(
            name,
            [name, &value, min, max](const std::string& text)
            {
                value = parseCount(name, text, max);
                if (value < min) throw UsageError(name + " must be at least " + std::to_string(min));
            },
            description)
        ->type_name("N");
}

void addListFilters(CLI::App& app, const std::string& description)
{
    app.add_flag_callback(
           "--list-filters",
           []
           {
               for (const std::string& n : osgLoA::FilterRegistry::names())
                   std::cout << n << "  " << osgLoA::FilterRegistry::description(n) << "\n";
               std::exit(kOk);
           },
           description)
        ->trigger_on_parse();
}

void addReaderOptions(CLI::App& app, std::string& readerOptions)
{
    app.add_option_function<std::vector<std::string>>(
           "-O,--options",
           [&readerOptions](const std::vector<std::string>& texts)
           {
               for (const std::string& t : texts)
                   readerOptions += (readerOptions.empty() ? "" : " ") + t;
           },
           "options for the models' readers, an osgDB option string (repeatable): \"seed=7 blocksX=6\" "
           "for the demo city (keys: docs/demo-city.md), \"lod=1 theme=summer\" for CityGML, "
           "\"lod=2.2\" for CityJSON")
        ->type_name("TEXT")
        ->allow_extra_args(false)
        ->group(kGroupModel);
}

void addCamera(CLI::App& app, CameraChoice& c)
{
    app.add_option_function<std::string>(
           "--camera",
           [&c](const std::string& name)
           {
               if (!osgLoA::CityCameras::isName(name))
                   throw UsageError("unknown camera '" + name + "' (known: street, oblique, top, horizon)");
               c.name = name;
           },
           "a named view: street, oblique, top, horizon, computed from the model's buildings and "
           "streets (docs/demo-city.md). Without a camera option the view frames the model's "
           "bounding sphere")
        ->type_name("NAME")
        ->group(kGroupCamera);
    app.add_option_function<std::string>(
           "--eye", [&c](const std::string& v) { c.eye = parseVec3("--eye", v), c.haveEye = true; },
           "an explicit look-at camera: the eye (with --center)")
        ->type_name("X,Y,Z")
        ->group(kGroupCamera);
    app.add_option_function<std::string>(
           "--center",
           [&c](const std::string& v) { c.center = parseVec3("--center", v), c.haveCenter = true; },
           "the point looked at (with --eye)")
        ->type_name("X,Y,Z")
        ->group(kGroupCamera);
    app.add_option_function<std::string>(
           "--up", [&c](const std::string& v) { c.up = parseVec3("--up", v), c.haveUp = true; },
           "the up direction of --eye/--center (default 0,0,1)")
        ->type_name("X,Y,Z")
        ->group(kGroupCamera);
}

void addSize(CLI::App& app, int& width, int& height, const std::string& what)
{
    app.add_option_function<std::string>(
           "--size", [&width, &height](const std::string& text) { parseSize(text, width, height); },
           "size of " + what + " in pixels (default " + std::to_string(kDefaultWidth) + "x" +
               std::to_string(kDefaultHeight) + ")")
        ->type_name("WxH")
        ->group(kGroupCamera);
}

void addRules(CLI::App& app, RulesChoice& rules)
{
    const auto take = [&rules](bool only)
    {
        return [&rules, only](const std::vector<std::string>& files)
        {
            if (!rules.files.empty() && rules.only != only)
                throw UsageError(
                    "--rules adds to the built-in rules and --rules-only replaces them: use one of them");
            rules.only = only;
            rules.files.insert(rules.files.end(), files.begin(), files.end());
        };
    };
    app.add_option_function<std::vector<std::string>>(
           "--rules", take(false),
           "classification rules (.osgt/.osgb/.osgx holding an "
           "osgLoA::ClassificationRuleSet) tried before the built-in "
           "rules; repeatable, the first file's rules first")
        ->type_name("FILE")
        ->allow_extra_args(false)
        ->group(kGroupClassification);
    app.add_option_function<std::vector<std::string>>(
           "--rules-only", take(true), "classify with FILE's rules instead of the built-in ones (repeatable)")
        ->type_name("FILE")
        ->allow_extra_args(false)
        ->group(kGroupClassification);
    app.add_flag("--override", rules.overrideModelData,
                 "let the rules replace types the model data gives (never a user's)")
        ->group(kGroupClassification);
}

CLI::Option* addScenario(CLI::App& app, std::string& scenario, const std::string& description)
{
    return app.add_option("--scenario", scenario, description)->type_name("NAME|FILE")->group(kGroupModel);
}

CLI::Option* addOutFile(CLI::App& app, std::string& file, const std::string& description)
{
    return app.add_option("--out", file, description)->type_name("FILE")->group(kGroupOutput);
}

CLI::Option* addOutDir(CLI::App& app, std::string& dir, const std::string& description)
{
    return app.add_option("--out-dir", dir, description)->type_name("DIR")->group(kGroupOutput);
}

} // namespace loa
