// osgdb_loa: the level-of-abstraction pseudo-loader and .loa scenario files.
//
//   osgviewer city.osgb.loa                              city.osgb with the default scenario
//   osgviewer -O "scenario=route" city.osgb.loa          a library scenario by name
//   osgviewer -O "scenario=/path/my.osgt" city.osgb.loa  a scenario file
//   osgviewer -O "scenario=route seed=3" demo.loacity.loa  (seed=3 goes on to osgdb_loacity)
//   osgviewer data/demo.loa                              a .loa file (docs/loa-files.md)
//   osgconv demo.loacity.loa city-loa.osgb               a scene that opens with its scenario
//
// A name ending in .loa that exists as a file is a .loa scenario file: JSON naming the models
// and the scenario. Any other X.loa is the pseudo-loader: it reads X (which may itself be a
// pseudo file such as demo.loacity). Either way the models are classified (FeatureClassifier:
// features the model data already carries keep their type; rules and the appearance fallback
// type the rest) and wrapped in one osgLoA::LoANode carrying the scenario.
//
// The option string is split at white space into tokens. "scenario=NAME|FILE",
// "rules=FILE" (added before the built-in rules) and "rules-only=FILE" are this plugin's and are removed;
// every other token is passed on, in order, to the readers of the models. A passed-on token whose key the
// model's reader does not declare (ReaderWriter::supportedOptions) is reported with OSG_WARN, so that a
// misspelt key is never silently ignored; it is passed on all the same.
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/util/BoundedObjectReader>
#include <osgLoA/util/InputLimits>
#include <osgLoA/util/ModelValidation>

#include <osg/Notify>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>
#include <osgDB/fstream>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
const char* const kOwnKeys[] = {"scenario", "rules", "rules-only", "oit"};
const char* const kFileKeys[] = {"models", "scenario", "rules", "options", "description"};

/** A read failure with the ReadResult status it becomes at the plugin boundary. */
struct LoaError
{
    osgDB::ReaderWriter::ReadResult::ReadStatus status;
    std::string message;
};

osgDB::ReaderWriter::ReadResult toResult(const LoaError& e)
{
    osgDB::ReaderWriter::ReadResult rr(e.status);
    rr.message() = "loa: " + e.message;
    return rr;
}

/** The .loa reads in progress on this thread (osgDB reads nested models in the caller's thread):
 *  their depth is bounded by max-depth and a .loa file already being read is a cycle (a file that
 *  names itself, two that name each other, a pseudo-loader chain x.loa.loa... 4,000 long). */
struct ReadStack
{
    static std::vector<std::string>& names()
    {
        thread_local std::vector<std::string> stack;
        return stack;
    }
    ReadStack(const std::string& name, const std::string& file, unsigned maxDepth)
    {
        std::vector<std::string>& stack = names();
        if (stack.size() >= maxDepth)
            throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                           osgLoA::InputLimits::exceeded("'" + name + "'",
                                                         ".loa files and pseudo-loaders nested more than " +
                                                             std::to_string(maxDepth) + " deep",
                                                         "max-depth", maxDepth)};
        if (!file.empty())
        {
            char* real = ::realpath(file.c_str(), nullptr);
            const std::string key = real ? real : file;
            std::free(real);
            if (std::find(stack.begin(), stack.end(), key) != stack.end())
            {
                std::string chain;
                for (const std::string& s : stack)
                    if (!chain.empty() || s == key) chain += osgDB::getSimpleFileName(s) + " -> ";
                throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                               "'" + name + "' is already being read: the .loa files name each other (" +
                                   chain + osgDB::getSimpleFileName(key) + ")"};
            }
            stack.push_back(key);
        }
        else
            stack.push_back("pseudo:" + name);
    }
    ~ReadStack() { names().pop_back(); }
};

std::string keyOf(const std::string& token)
{
    return token.substr(0, token.find('='));
}

bool isOwnKey(const std::string& key)
{
    return std::find(std::begin(kOwnKeys), std::end(kOwnKeys), key) != std::end(kOwnKeys);
}

/** Levenshtein distance, for "did you mean" hints on misspelt keys. */
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                               diagonal + (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                                   std::tolower(static_cast<unsigned char>(b[j - 1]))
                                               ? 0
                                               : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

/** What the option string asks of this plugin, and what it passes on to the model readers. */
struct LoaOptions
{
    std::string scenario;   ///< "" when not given
    std::string rules;      ///< "" when not given
    std::string oit;        ///< "" when not given: the renderer's default (stencil-routed)
    bool rulesOnly = false; ///< rules-only=FILE: FILE's rules instead of the built-in ones
    std::vector<std::string> passOn;

    static LoaOptions parse(const osgDB::Options* options)
    {
        LoaOptions o;
        if (!options) return o;
        std::istringstream in(options->getOptionString());
        for (std::string token; in >> token;)
        {
            const std::string key = keyOf(token);
            if (!isOwnKey(key))
                o.passOn.push_back(token);
            else if (token.size() == key.size() + 1 || token.find('=') == std::string::npos)
                throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                               "option '" + token + "' needs a value (" + key + "=...)"};
            else
            {
                const std::string value = token.substr(key.size() + 1);
                if (key == "oit")
                {
                    if (value != "auto")
                    {
                        try
                        {
                            osgLoA::OrderIndependentTransparency::methodFromName(value);
                        }
                        catch (const std::invalid_argument& e)
                        {
                            throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                                           std::string("option oit: ") + e.what() + " or auto"};
                        }
                    }
                    o.oit = value;
                    continue;
                }
                (key == "scenario" ? o.scenario : o.rules) = value;
                if (key != "scenario") o.rulesOnly = key == "rules-only";
            }
        }
        return o;
    }

    std::string passOnString(const std::string& before = std::string()) const
    {
        std::string s = before;
        for (const std::string& t : passOn)
            s += (s.empty() ? "" : " ") + t;
        return s;
    }
};

/** True when the reader lists the key among its supportedOptions() (as a whole word of an
 *  option's name, so "blocksX=N / blocksY=N" declares blocksX and blocksY). */
bool declares(const osgDB::ReaderWriter& rw, const std::string& key)
{
    for (const auto& option : rw.supportedOptions())
    {
        const std::string& name = option.first;
        std::string word;
        for (std::size_t i = 0; i <= name.size(); ++i)
        {
            const char c = i < name.size() ? name[i] : ' ';
            if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')
                word += c;
            else
            {
                if (!word.empty() && word == key) return true;
                word.clear();
            }
        }
    }
    return false;
}

/** Warns (once per key and read) about passed-on keys that no model's reader declares. */
void warnAboutUndeclaredKeys(const LoaOptions& o, const std::vector<std::string>& models,
                             const std::string& context)
{
    if (o.passOn.empty()) return;
    std::vector<osgDB::ReaderWriter*> readers;
    std::string extensions;
    for (const std::string& m : models)
    {
        const std::string ext = osgDB::getLowerCaseFileExtension(m);
        if (ext.empty()) continue;
        if (osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension(ext))
            readers.push_back(rw);
        if (extensions.find("." + ext + "'") == std::string::npos)
            extensions += std::string(extensions.empty() ? "" : ", ") + "'." + ext + "'";
    }
    std::vector<std::string> warned;
    for (const std::string& token : o.passOn)
    {
        const std::string key = keyOf(token);
        if (std::find(warned.begin(), warned.end(), key) != warned.end()) continue;
        if (std::any_of(readers.begin(), readers.end(),
                        [&](const osgDB::ReaderWriter* rw) { return declares(*rw, key); }))
            continue;
        warned.push_back(key);
        std::string hint;
        for (const char* own : kOwnKeys)
            if (editDistance(key, own) <= 2) hint = std::string(" (did you mean '") + own + "='?)";
        OSG_WARN << "loa: " << context << "option '" << key << "' is not a loa option (scenario=, rules=)"
                 << " and the reader for " << extensions << " does not declare it; passed on to it" << hint
                 << std::endl;
    }
}

/** Throws a LoaError listing the scenario's validation errors; reports its warnings. */
void checkScenario(const osgLoA::UsageScenario& s, const std::string& label, const std::string& context)
{
    const osgLoA::UsageScenario::Validation v = s.validate();
    if (!v.ok())
    {
        std::string msg = context + "scenario " + label + " is not valid:";
        for (const std::string& e : v.errors)
            msg += " " + e + ";";
        msg.pop_back();
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE, msg};
    }
    for (const std::string& w : v.warnings)
        OSG_WARN << "loa: " << context << "scenario " << label << ": " << w << std::endl;
}

/** A scenario by name or file; ScenarioError and validation errors become LoaErrors. */
osg::ref_ptr<osgLoA::UsageScenario> loadScenario(const std::string& nameOrPath, const std::string& context)
{
    std::string origin;
    osg::ref_ptr<osgLoA::UsageScenario> s;
    try
    {
        s = osgLoA::ScenarioLibrary::load(nameOrPath, &origin);
    }
    catch (const std::exception& e)
    {
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE, context + e.what()};
    }
    checkScenario(*s, "'" + nameOrPath + "'" + (origin == nameOrPath ? std::string() : " (" + origin + ")"),
                  context);
    OSG_INFO << "loa: scenario '" << s->getName() << "' from " << origin << std::endl;
    return s;
}

osg::ref_ptr<osgLoA::ClassificationRuleSet> loadRules(const std::string& path, bool rulesOnly,
                                                      const std::string& context)
{
    try
    {
        // As every tool classifies: the file's rules before the built-in ones (or alone).
        return osgLoA::ClassificationRuleSet::assemble(
            path.empty() ? std::vector<std::string>() : std::vector<std::string>{path}, rulesOnly, false);
    }
    catch (const std::exception& e)
    {
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                       context + "classification rules '" + path + "': " + e.what()};
    }
}

osg::ref_ptr<osg::Node> readModel(const std::string& name, const osgDB::Options* options,
                                  const std::string& context)
{
    typedef osgDB::ReaderWriter::ReadResult RR;
    // A device or FIFO (/dev/zero, a link to it) would be read forever.
    const std::string found = osgDB::findDataFile(name, options);
    struct stat st;
    if (!found.empty() && ::stat(found.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
        throw LoaError{RR::ERROR_IN_READING_FILE,
                       context + "model '" + name + "' is not a regular file (a device or FIFO)"};
    if (!found.empty() &&
        osgLoA::BoundedObjectReader::handlesExtension(osgDB::getLowerCaseFileExtension(found)))
    {
        // OSG's own .osgt/.osgb readers loop forever on a truncated or bit-flipped file and trust
        // the sizes it states: read with the work bounded by the file's size instead.
        osg::ref_ptr<osg::Node> node;
        try
        {
            node = osgLoA::BoundedObjectReader::readNodeFile(found, options);
        }
        catch (const osgLoA::MalformedFileError& e)
        {
            throw LoaError{RR::ERROR_IN_READING_FILE,
                           context + "cannot read model '" + name + "': " + e.what()};
        }
        osgLoA::ModelValidation::validate(*node, name);
        return node;
    }
    RR rr = osgDB::Registry::instance()->readNode(name, options);
    if (rr.validNode())
    {
        osgLoA::ModelValidation::validate(*rr.getNode(), name);
        return rr.getNode();
    }
    const bool onDisk = !osgDB::findDataFile(name, options).empty();
    if (rr.status() == RR::FILE_NOT_FOUND || (rr.status() == RR::FILE_NOT_HANDLED && !onDisk))
        throw LoaError{RR::FILE_NOT_FOUND,
                       context + "model '" + name + "' not found" +
                           (rr.message().empty() ? std::string() : " (" + rr.message() + ")")};
    std::string why = rr.message();
    if (why.empty())
        why = rr.status() == RR::FILE_NOT_HANDLED ? "no reader accepted it (does it hold a scene graph node?)"
                                                  : rr.statusMessage();
    throw LoaError{RR::ERROR_IN_READING_FILE, context + "cannot read model '" + name + "': " + why};
}

/** What a .loa file or a pseudo file name asks for. */
struct Request
{
    std::string context;             ///< "'x.loa': " for messages, or ""
    std::vector<std::string> models; ///< paths to read
    std::string scenario;            ///< "" for the default
    std::string rules;               ///< "" for the built-in rules
    std::string modelOptions;        ///< option string for the model readers (before -O's)
    std::string directory;           ///< prepended to the database path, or ""
};

/** Resolves a path of a .loa file against its directory. */
std::string relativeTo(const std::string& directory, const std::string& path)
{
    if (path.empty() || directory.empty() || osgDB::isAbsolutePath(path)) return path;
    return osgDB::concatPaths(directory, path);
}

Request parseLoaFile(const std::string& path, const osgLoA::InputLimits& limits)
{
    Request r;
    r.context = "'" + path + "': ";
    r.directory = osgDB::getFilePath(path);
    osgDB::ifstream in(path.c_str());
    if (!in)
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE, r.context + "cannot open"};
    std::string text;
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    {
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (text.size() > limits.maxStringBytes)
            throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                           osgLoA::InputLimits::exceeded("'" + path + "'",
                                                         "a .loa file of more than " +
                                                             std::to_string(limits.maxStringBytes) + " bytes",
                                                         "max-string", limits.maxStringBytes)};
    }
    nlohmann::json j;
    try
    {
        const nlohmann::json::parser_callback_t depth =
            [&](int d, nlohmann::json::parse_event_t, nlohmann::json&)
        {
            if (d > static_cast<int>(limits.maxDepth))
                throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                               osgLoA::InputLimits::exceeded("'" + path + "'",
                                                             "JSON nested deeper than " +
                                                                 std::to_string(limits.maxDepth) + " levels",
                                                             "max-depth", limits.maxDepth)};
            return true;
        };
        j = nlohmann::json::parse(text, depth, true, true); // comments allowed
    }
    catch (const nlohmann::json::parse_error& e)
    {
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE,
                       r.context + "not valid JSON (" + e.what() + ")"};
    }
    auto fail = [&](const std::string& what) {
        throw LoaError{osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE, r.context + what};
    };
    if (!j.is_object())
        fail("expected a JSON object like {\"models\": [\"city.osgb\"], \"scenario\": \"route\"}");
    for (const auto& item : j.items())
        if (std::find(std::begin(kFileKeys), std::end(kFileKeys), item.key()) == std::end(kFileKeys))
            fail("unknown key '" + item.key() + "' (known: models, scenario, rules, options, description)");
    auto text_ = [&](const char* key) -> std::string
    {
        if (!j.contains(key)) return std::string();
        if (!j[key].is_string() || j[key].get<std::string>().empty())
            fail(std::string("'") + key + "' must be a non-empty string");
        return j[key].get<std::string>();
    };

    if (!j.contains("models")) fail("no 'models' (a list of model files, relative to the .loa file)");
    const nlohmann::json& models = j["models"];
    std::vector<std::string> names;
    if (models.is_string())
        names.push_back(models.get<std::string>());
    else if (models.is_array())
        for (const auto& m : models)
        {
            if (!m.is_string()) fail("'models' must list file names (strings), not " + m.dump());
            names.push_back(m.get<std::string>());
        }
    else
        fail("'models' must be a list of file names, not " + models.dump());
    if (names.empty()) fail("'models' is empty");
    if (names.size() > limits.maxObjects)
        fail(osgLoA::InputLimits::exceeded("models", std::to_string(names.size()), "max-objects",
                                           limits.maxObjects));
    for (const std::string& m : names)
    {
        if (m.empty()) fail("'models' holds an empty file name");
        r.models.push_back(relativeTo(r.directory, m));
    }

    // A scenario value with a scenario file extension or a '/' is a file (relative to the .loa
    // file); anything else is a library name.
    r.scenario = text_("scenario");
    if (osgLoA::ScenarioLibrary::isScenarioFile(r.scenario) || r.scenario.find('/') != std::string::npos)
        r.scenario = relativeTo(r.directory, r.scenario);
    r.rules = relativeTo(r.directory, text_("rules"));
    r.modelOptions = text_("options");
    text_("description");
    return r;
}

class ReaderWriterLoa : public osgDB::ReaderWriter
{
public:
    ReaderWriterLoa()
    {
        supportsExtension("loa", "osgLoA level-of-abstraction pseudo-loader (X.loa) and scenario files");
        supportsOption("scenario=NAME|FILE",
                       "usage scenario: a library name (default 'distance') or a .osgt/.osgb/.osgx file");
        supportsOption("rules=FILE",
                       "classification rule set (.osgt/.osgb/.osgx) tried before the built-in rules");
        supportsOption("rules-only=FILE", "classification rule set used instead of the built-in rules");
        supportsOption("oit=NAME", "order-independent transparency of what fused styles cannot draw: "
                                   "stencil-routed (default; where its routing is approximate, on llvmpipe, "
                                   "linked-list unless named), linked-list, weighted-blended or auto");
        osgLoA::InputLimits::declareOptions(*this);
    }
    const char* className() const override { return "osgLoA level-of-abstraction pseudo-loader"; }

    ReadResult readObject(const std::string& fileName, const Options* options) const override
    {
        return readNode(fileName, options);
    }

    ReadResult readNode(const std::string& fileName, const Options* options) const override
    {
        if (!acceptsExtension(osgDB::getLowerCaseFileExtension(fileName)))
            return ReadResult::FILE_NOT_HANDLED;
        try
        {
            return read(fileName, options).get();
        }
        catch (const LoaError& e)
        {
            return toResult(e);
        }
        catch (const std::exception& e)
        {
            return ReadResult("loa: '" + fileName + "': " + e.what());
        }
        catch (...)
        {
            return ReadResult("loa: '" + fileName + "': unknown error");
        }
    }

private:
    static osg::ref_ptr<osgLoA::LoANode> read(const std::string& fileName, const Options* options)
    {
        const LoaOptions opts = LoaOptions::parse(options);

        const osgLoA::InputLimits limits =
            osgLoA::InputLimits::fromOptions(options ? options->getOptionString() : std::string());
        Request request;
        const std::string file = osgDB::findDataFile(fileName, options);
        const bool isFile = !file.empty() && osgDB::fileType(file) == osgDB::REGULAR_FILE;
        const ReadStack guard(fileName, isFile ? file : std::string(), limits.maxDepth);
        if (isFile)
            request = parseLoaFile(file, limits);
        else
        {
            const std::string inner = osgDB::getNameLessExtension(fileName);
            if (inner.empty() || osgDB::getFileExtension(inner).empty())
                throw LoaError{ReadResult::FILE_NOT_FOUND,
                               "no .loa file '" + fileName + "', and '" + inner +
                                   "' has no extension, so it names no model to wrap (use city.osgb.loa)"};
            request.models.push_back(inner);
        }
        // The option string overrides what a .loa file says.
        if (!opts.scenario.empty()) request.scenario = opts.scenario;
        if (!opts.rules.empty()) request.rules = opts.rules;
        const bool rulesOnly = !opts.rules.empty() && opts.rulesOnly;

        // Options for the model readers: this plugin's keys removed, the .loa file's first.
        osg::ref_ptr<Options> modelOptions =
            options ? static_cast<Options*>(options->clone(osg::CopyOp::SHALLOW_COPY)) : new Options;
        modelOptions->setOptionString(opts.passOnString(request.modelOptions));
        if (!request.directory.empty()) modelOptions->getDatabasePathList().push_front(request.directory);
        warnAboutUndeclaredKeys(opts, request.models, request.context);

        osg::ref_ptr<osgLoA::ClassificationRuleSet> rules =
            loadRules(request.rules, rulesOnly, request.context);
        osg::ref_ptr<osgLoA::UsageScenario> scenario;
        if (!request.scenario.empty()) scenario = loadScenario(request.scenario, request.context);

        // A model that is itself a LoA node (a saved `osgconv X.loa Y.osgb`) is not wrapped
        // again: a single one is used as it is and keeps its scenario unless one is given; with
        // several models its children join the new node.
        osg::ref_ptr<osgLoA::LoANode> loa;
        std::vector<osg::ref_ptr<osg::Node>> models;
        for (const std::string& m : request.models)
            models.push_back(readModel(m, modelOptions.get(), request.context));
        if (models.size() == 1) loa = dynamic_cast<osgLoA::LoANode*>(models.front().get());
        if (loa.valid())
        {
            if (!scenario && loa->getScenario())
            {
                checkScenario(*loa->getScenario(),
                              "'" + loa->getScenario()->getName() + "' saved in the model", request.context);
                scenario = loa->getScenario();
            }
        }
        else
        {
            loa = new osgLoA::LoANode;
            for (const auto& model : models)
            {
                osgLoA::LoANode* saved = dynamic_cast<osgLoA::LoANode*>(model.get());
                if (!saved)
                    loa->addChild(model.get());
                else
                    for (unsigned i = 0; i < saved->getNumChildren(); ++i)
                        loa->addChild(saved->getChild(i));
            }
        }
        if (!scenario) scenario = loadScenario(osgLoA::ScenarioLibrary::defaultName(), request.context);

        // One classification over all models, so that new feature ids do not collide.
        const osgLoA::FeatureClassifier::Report report =
            osgLoA::FeatureClassifier(rules.get()).classify(*loa);
        OSG_INFO << "loa: " << request.context << "classifier: " << report.summary() << std::endl;
        if (request.models.size() > 1)
        {
            const std::vector<unsigned> duplicates = osgLoA::FeatureIndex(*loa).duplicateIds();
            if (!duplicates.empty())
                OSG_WARN << "loa: " << request.context << duplicates.size()
                         << " feature ids occur in more than one place (first: " << duplicates.front()
                         << "); per-feature interest and the focus feature apply to each of them"
                         << std::endl;
        }
        loa->setScenario(scenario.get());
        // The stock osgviewer frames a city edge-on from its bounding sphere; the node gives
        // the viewer's manipulator the oblique home view of loa-viewer in its first event.
        loa->setHomeViewPending(true);
        if (!opts.oit.empty())
        {
            osgLoA::TransitionRenderer::Settings rs = loa->getRenderer()->getSettings();
            rs.oitAuto = opts.oit == "auto";
            if (!rs.oitAuto) rs.oit = osgLoA::OrderIndependentTransparency::methodFromName(opts.oit);
            // A method named is the method used, even where stencil routing is approximate.
            rs.approximateStencilRouting = !rs.oitAuto;
            loa->getRenderer()->setSettings(rs);
        }
        return loa;
    }
};
} // namespace

REGISTER_OSGPLUGIN(loa, ReaderWriterLoa)
