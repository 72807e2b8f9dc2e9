#include <osgLoA/render/ShaderLibrary>

#include "EmbeddedShaders.h"

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/fstream>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace osgLoA
{

std::string ShaderDiagnostic::message() const
{
    std::string head = stage == "link" ? "program '" + programName + "' failed to link"
                                       : "shader '" + shaderName + "' (" + stage + " stage) of program '" +
                                             programName + "' failed to compile";
    std::string body = log;
    while (!body.empty() && (body.back() == '\n' || body.back() == ' '))
        body.pop_back();
    return head + ": " + (body.empty() ? std::string("(the driver gave no log)") : body);
}

namespace
{
std::string joinMessages(const std::vector<ShaderDiagnostic>& d)
{
    std::string s;
    for (const auto& x : d)
        s += (s.empty() ? "" : "\n") + x.message();
    return s;
}
} // namespace

ShaderError::ShaderError(std::vector<ShaderDiagnostic> diagnostics)
    : std::runtime_error(joinMessages(diagnostics)), _diagnostics(std::move(diagnostics))
{
}

std::vector<std::string> ShaderLibrary::embeddedNames()
{
    std::vector<std::string> names;
    for (const detail::EmbeddedShader* e = detail::kEmbeddedShaders; e->name; ++e)
        names.push_back(e->name);
    std::sort(names.begin(), names.end());
    return names;
}

namespace
{
/** The text of one file: OSG_FILE_PATH first, else embedded; origin says which. */
bool findText(const std::string& name, std::string& text, std::string& origin)
{
    // Only the listed directories: a stray file in the working directory must not win.
    const std::string path = osgDB::findFileInPath(name, osgDB::getDataFilePathList(), osgDB::CASE_SENSITIVE);
    if (!path.empty())
    {
        osgDB::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
        if (!in) throw std::invalid_argument("shader override '" + path + "' exists but cannot be read");
        std::ostringstream all;
        all << in.rdbuf();
        text = all.str();
        origin = path;
        return true;
    }
    for (const detail::EmbeddedShader* e = detail::kEmbeddedShaders; e->name; ++e)
        if (name == e->name)
        {
            text = e->source;
            origin = "embedded";
            return true;
        }
    return false;
}

/** The name in a line `#pragma include "NAME"` (spaces allowed around the words), or "". */
std::string includedName(const std::string& line)
{
    std::istringstream words(line);
    std::string hash, pragma, quoted;
    if (!(words >> hash) || hash != "#pragma") return std::string();
    if (!(words >> pragma) || pragma != "include") return std::string();
    if (!(words >> quoted) || quoted.size() < 3 || quoted.front() != '"' || quoted.back() != '"')
        throw std::invalid_argument("malformed include, expected #pragma include \"NAME\": " + line);
    return quoted.substr(1, quoted.size() - 2);
}

/** The stage NAME.STAGE.glsl denotes, or false when name has no such suffix. */
bool stageFromName(const std::string& name, osg::Shader::Type& type)
{
    if (osgDB::getFileExtension(name) != "glsl") return false;
    const std::string ext = osgDB::getFileExtension(osgDB::getNameLessExtension(name));
    static const std::pair<const char*, osg::Shader::Type> stages[] = {
        {"vert", osg::Shader::VERTEX},      {"frag", osg::Shader::FRAGMENT},
        {"geom", osg::Shader::GEOMETRY},    {"comp", osg::Shader::COMPUTE},
        {"tesc", osg::Shader::TESSCONTROL}, {"tese", osg::Shader::TESSEVALUATION}};
    for (const auto& s : stages)
        if (ext == s.first)
        {
            type = s.second;
            return true;
        }
    return false;
}

constexpr int kMaxIncludeDepth = 16;

/** Appends text to out with its includes replaced; chain: the files being expanded, outermost
 *  first; number: this text's GLSL source string number. */
void expand(const std::string& text, std::vector<std::string>& chain, int number, std::string& out,
            std::vector<std::string>& includes)
{
    std::istringstream lines(text);
    std::string line;
    int lineNumber = 0;
    while (std::getline(lines, line))
    {
        ++lineNumber;
        const std::string name = includedName(line);
        if (name.empty())
        {
            out += line + "\n";
            continue;
        }
        const std::string where = "'" + chain.back() + "' line " + std::to_string(lineNumber);
        if (std::find(chain.begin(), chain.end(), name) != chain.end())
        {
            std::string cycle;
            for (const std::string& c : chain)
                cycle += c + " -> ";
            throw std::invalid_argument("shader include cycle: " + cycle + name + " (at " + where + ")");
        }
        if (int(chain.size()) > kMaxIncludeDepth)
            throw std::invalid_argument("shader includes nest deeper than " +
                                        std::to_string(kMaxIncludeDepth) + " at " + where);
        if (std::find(includes.begin(), includes.end(), name) != includes.end())
        {
            out += "// (" + name + " is included above)\n";
            continue;
        }
        std::string included, origin;
        if (!findText(name, included, origin))
            throw std::invalid_argument("shader include '" + name + "' (at " + where +
                                        ") is not embedded and not on OSG_FILE_PATH");
        includes.push_back(name);
        const int k = int(includes.size());
        out += "#line 1 " + std::to_string(k) + "\n";
        chain.push_back(name);
        expand(included, chain, k, out, includes);
        chain.pop_back();
        out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(number) + "\n";
    }
}
} // namespace

bool ShaderLibrary::isInclude(const std::string& name)
{
    osg::Shader::Type type;
    return osgDB::getFileExtension(name) == "glsl" && !stageFromName(name, type);
}

ShaderLibrary::Source ShaderLibrary::getSource(const std::string& name)
{
    Source src;
    src.name = name;
    std::string text;
    if (!findText(name, text, src.origin))
        throw std::invalid_argument("no shader named '" + name + "' is embedded or on OSG_FILE_PATH");
    if (text.find("#pragma include") == std::string::npos)
    {
        src.text = std::move(text);
        return src;
    }
    std::vector<std::string> chain{name};
    expand(text, chain, 0, src.text, src.includes);
    return src;
}

osg::Shader::Type ShaderLibrary::stageOf(const std::string& name)
{
    osg::Shader::Type type;
    if (!stageFromName(name, type))
        throw std::invalid_argument("shader name '" + name +
                                    "' does not end in .vert/.frag/.geom/.comp/.tesc/.tese.glsl");
    return type;
}

std::string ShaderLibrary::stageName(osg::Shader::Type type)
{
    switch (type)
    {
    case osg::Shader::VERTEX:
        return "vertex";
    case osg::Shader::FRAGMENT:
        return "fragment";
    case osg::Shader::GEOMETRY:
        return "geometry";
    case osg::Shader::COMPUTE:
        return "compute";
    case osg::Shader::TESSCONTROL:
        return "tessellation control";
    case osg::Shader::TESSEVALUATION:
        return "tessellation evaluation";
    default:
        return "unknown";
    }
}

osg::ref_ptr<osg::Shader> ShaderLibrary::createShader(const std::string& name)
{
    const osg::Shader::Type type = stageOf(name);
    Source src = getSource(name);
    osg::ref_ptr<osg::Shader> shader = new osg::Shader(type, src.text);
    shader->setName(name);
    shader->setFileName(src.origin == "embedded" ? name : src.origin);
    return shader;
}

std::string ShaderLibrary::withDefines(const std::string& text, const Defines& defines,
                                       const std::string& name)
{
    if (defines.empty()) return text;
    std::string lines;
    for (const auto& d : defines)
    {
        const bool identifier =
            !d.first.empty() && !std::isdigit(static_cast<unsigned char>(d.first[0])) &&
            std::all_of(d.first.begin(), d.first.end(),
                        [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
        if (!identifier)
            throw std::invalid_argument("ShaderLibrary: '" + d.first + "' is not a preprocessor name (" +
                                        name + ")");
        if (d.second.find_first_of("\r\n") != std::string::npos)
            throw std::invalid_argument("ShaderLibrary: the value of " + d.first + " spans lines (" + name +
                                        ")");
        lines += "#define " + d.first + " " + (d.second.empty() ? std::string("1") : d.second) + "\n";
    }
    // After the #version line (which must come first in GLSL), then back to the file's next line.
    std::string out = text;
    std::size_t at = 0;
    const std::size_t version = out.find("#version");
    if (version != std::string::npos)
    {
        if (out.find('\n', version) == std::string::npos) out += "\n";
        at = out.find('\n', version) + 1;
        const int line = 1 + int(std::count(out.begin(), out.begin() + static_cast<long>(version), '\n'));
        lines += "#line " + std::to_string(line + 1) + " 0\n";
    }
    out.insert(at, lines);
    return out;
}

osg::ref_ptr<osg::Shader> ShaderLibrary::createShader(const std::string& name, const Defines& defines)
{
    osg::ref_ptr<osg::Shader> shader = createShader(name);
    if (defines.empty()) return shader;
    shader->setShaderSource(withDefines(shader->getShaderSource(), defines, name));
    std::string label;
    for (const auto& d : defines)
        label += (label.empty() ? "" : " ") + d.first + (d.second.empty() ? std::string() : "=" + d.second);
    shader->setName(objectLabel(name + "[" + label + "]"));
    return shader;
}

std::string ShaderLibrary::objectLabel(const std::string& name)
{
    constexpr std::size_t kMax = 255;
    if (name.size() <= kMax) return name;
    return name.substr(0, kMax - 3) + "...";
}

osg::ref_ptr<osg::Program> ShaderLibrary::createProgram(const std::string& programName,
                                                        const std::vector<std::string>& shaderNames)
{
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->setName(programName);
    for (const auto& n : shaderNames)
        program->addShader(createShader(n).get());
    return program;
}

std::vector<ShaderDiagnostic> ShaderLibrary::check(const osg::Program& program, osg::State& state)
{
    std::vector<ShaderDiagnostic> out;
    program.compileGLObjects(state);
    osg::Program::PerContextProgram* pcp = program.getPCP(state);
    if (!pcp)
    {
        out.push_back({program.getName(), "(link)", "link", "OSG created no program object in this context"});
        return out;
    }
    if (pcp->isLinked()) return out;
    for (unsigned i = 0; i < program.getNumShaders(); ++i)
    {
        const osg::Shader* shader = program.getShader(i);
        osg::Shader::PerContextShader* pcs = shader->getPCS(state);
        if (pcs && !pcs->isCompiled())
        {
            std::string log;
            pcs->getInfoLog(log);
            out.push_back({program.getName(), shader->getName(), stageName(shader->getType()), log});
        }
    }
    if (out.empty())
    {
        std::string log;
        pcp->getInfoLog(log);
        out.push_back({program.getName(), "(link)", "link", log});
    }
    return out;
}

} // namespace osgLoA
