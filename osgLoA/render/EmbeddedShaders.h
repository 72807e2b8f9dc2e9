// Private: the table the build generates from shaders/*.glsl (cmake/EmbedShadersScript.cmake).
#ifndef OSGLOA_RENDER_EMBEDDEDSHADERS_H
#define OSGLOA_RENDER_EMBEDDEDSHADERS_H 1

namespace osgLoA
{
namespace detail
{
struct EmbeddedShader
{
    const char* name;
    const char* source;
};
/** Terminated by {nullptr, nullptr}. */
extern const EmbeddedShader kEmbeddedShaders[];
} // namespace detail
} // namespace osgLoA

#endif
