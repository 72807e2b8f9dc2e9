// Private: compiling and linking raw GL programs for the code that drives GL directly
// (GpuFilterEngine's compute passes, TextureHistogram's texture-space pass).
#ifndef OSGLOA_RENDER_GLPROGRAMBUILD_H
#define OSGLOA_RENDER_GLPROGRAMBUILD_H 1

#include <osg/GLExtensions>

#include <string>
#include <vector>

namespace osgLoA
{
namespace detail
{

/** Compiles one shader stage; on failure deletes it, returns 0 and sets log to the driver's. */
GLuint compileShaderStage(osg::GLExtensions* ext, GLenum type, const std::string& source, std::string& log);

/** Links the compiled stages into a program and deletes the stages; on failure deletes the
 *  program, returns 0 and sets log. */
GLuint linkProgram(osg::GLExtensions* ext, const std::vector<GLuint>& stages, std::string& log);

} // namespace detail
} // namespace osgLoA

#endif
