/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include "GLProgramBuild.h"

#include <algorithm>

namespace osgLoA
{
namespace detail
{

GLuint compileShaderStage(osg::GLExtensions* ext, GLenum type, const std::string& source, std::string& log)
{
    GLuint sh = ext->glCreateShader(type);
    const char* text = source.c_str();
    ext->glShaderSource(sh, 1, &text, nullptr);
    ext->glCompileShader(sh);
    GLint ok = 0;
    ext->glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok) return sh;
    GLint len = 0;
    ext->glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
    std::string text2(std::size_t(std::max(len, 1)), '\0');
    ext->glGetShaderInfoLog(sh, len, nullptr, &text2[0]);
    log = text2.c_str();
    ext->glDeleteShader(sh);
    return 0;
}

GLuint linkProgram(osg::GLExtensions* ext, const std::vector<GLuint>& stages, std::string& log)
{
    GLuint p = ext->glCreateProgram();
    for (GLuint s : stages)
        ext->glAttachShader(p, s);
    ext->glLinkProgram(p);
    for (GLuint s : stages)
        ext->glDeleteShader(s);
    GLint ok = 0;
    ext->glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (ok) return p;
    GLint len = 0;
    ext->glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
    std::string text(std::size_t(std::max(len, 1)), '\0');
    ext->glGetProgramInfoLog(p, len, nullptr, &text[0]);
    log = text.c_str();
    ext->glDeleteProgram(p);
    return 0;
}

} // namespace detail
} // namespace osgLoA
