#include <osgLoA/render/ShaderLibrary>

#include "EmbeddedShaders.h"

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/fstream>

#include <algorithm>
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

ShaderLibrary::Source ShaderLibrary::getSource(const std::string& name)
{
    // Only the listed directories: a stray file in the working directory must not win.
    const std::string path = osgDB::findFileInPath(name, osgDB::getDataFilePathList(), osgDB::CASE_SENSITIVE);
    if (!path.empty())
    {
        osgDB::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
        if (!in) throw std::invalid_argument("shader override '" + path + "' exists but cannot be read");
        std::ostringstream text;
        text << in.rdbuf();
        return {name, text.str(), path};
    }
    for (const detail::EmbeddedShader* e = detail::kEmbeddedShaders; e->name; ++e)
        if (name == e->name) return {name, e->source, "embedded"};
    throw std::invalid_argument("no shader named '" + name + "' is embedded or on OSG_FILE_PATH");
}

osg::Shader::Type ShaderLibrary::stageOf(const std::string& name)
{
    // NAME.STAGE.glsl
    const std::string withoutGlsl = osgDB::getNameLessExtension(name);
    const std::string ext = osgDB::getFileExtension(withoutGlsl);
    if (osgDB::getFileExtension(name) == "glsl")
    {
        if (ext == "vert") return osg::Shader::VERTEX;
        if (ext == "frag") return osg::Shader::FRAGMENT;
        if (ext == "geom") return osg::Shader::GEOMETRY;
        if (ext == "comp") return osg::Shader::COMPUTE;
        if (ext == "tesc") return osg::Shader::TESSCONTROL;
        if (ext == "tese") return osg::Shader::TESSEVALUATION;
    }
    throw std::invalid_argument("shader name '" + name +
                                "' does not end in .vert/.frag/.geom/.comp/.tesc/.tese.glsl");
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
