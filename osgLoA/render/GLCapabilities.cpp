#include <osgLoA/render/GLCapabilities>
#include <osgLoA/util/JsonString>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <sstream>

namespace osgLoA
{
namespace
{
std::string glString(GLenum name)
{
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : std::string();
}

int glInt(GLenum name)
{
    GLint v = 0;
    glGetIntegerv(name, &v);
    while (glGetError() != GL_NO_ERROR)
        v = 0; // an enum the context does not know: report 0, never garbage
    return v;
}

std::mutex& lastRendererMutex()
{
    static std::mutex m;
    return m;
}

std::string& lastRenderer()
{
    static std::string r;
    return r;
}

} // namespace

std::string GLCapabilities::lastQueriedRenderer()
{
    std::lock_guard<std::mutex> lock(lastRendererMutex());
    return lastRenderer();
}

void GLCapabilities::query()
{
    while (glGetError() != GL_NO_ERROR)
    {
    }
    vendor = glString(GL_VENDOR);
    renderer = glString(GL_RENDERER);
    {
        std::lock_guard<std::mutex> lock(lastRendererMutex());
        lastRenderer() = renderer;
    }
    version = glString(GL_VERSION);
    glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
    majorVersion = glInt(GL_MAJOR_VERSION);
    minorVersion = glInt(GL_MINOR_VERSION);
    if (majorVersion == 0)
    {
        // GL before 3.0 has no GL_MAJOR_VERSION: parse the string.
        std::istringstream in(version);
        char dot = 0;
        in >> majorVersion >> dot >> minorVersion;
    }

    extensions.clear();
    if (majorVersion >= 3)
    {
        const int n = glInt(GL_NUM_EXTENSIONS);
        for (int i = 0; i < n; ++i)
        {
            const GLubyte* e = glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
            if (e) extensions.insert(reinterpret_cast<const char*>(e));
        }
    }
    else
    {
        std::istringstream in(glString(GL_EXTENSIONS));
        std::string e;
        while (in >> e)
            extensions.insert(e);
    }

    compatibilityProfile = true;
    if (versionAtLeast(3, 2))
    {
        const int mask = glInt(GL_CONTEXT_PROFILE_MASK);
        compatibilityProfile = (mask & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT) != 0;
    }

    maxSamples = glInt(GL_MAX_SAMPLES);
    maxColorTextureSamples = glInt(GL_MAX_COLOR_TEXTURE_SAMPLES);
    maxDepthTextureSamples = glInt(GL_MAX_DEPTH_TEXTURE_SAMPLES);
    maxTextureSize = glInt(GL_MAX_TEXTURE_SIZE);
    maxArrayTextureLayers = glInt(GL_MAX_ARRAY_TEXTURE_LAYERS);
    maxColorAttachments = glInt(GL_MAX_COLOR_ATTACHMENTS);
    maxDrawBuffers = glInt(GL_MAX_DRAW_BUFFERS);
    maxTextureImageUnits = glInt(GL_MAX_TEXTURE_IMAGE_UNITS);

    computeShaders = versionAtLeast(4, 3) || hasExtension("GL_ARB_compute_shader");
    if (computeShaders)
    {
        maxComputeWorkGroupInvocations = glInt(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
        for (GLuint i = 0; i < 3; ++i)
        {
            GLint v = 0;
            glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, i, &v);
            maxComputeWorkGroupSize[i] = glGetError() == GL_NO_ERROR ? v : 0;
        }
    }
    shaderStorageBuffers = versionAtLeast(4, 3) || hasExtension("GL_ARB_shader_storage_buffer_object");
    if (shaderStorageBuffers)
    {
        GLint64 v = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v);
        maxShaderStorageBlockSize = glGetError() == GL_NO_ERROR ? static_cast<long long>(v) : 0;
    }
    shaderImageLoadStore = versionAtLeast(4, 2) || hasExtension("GL_ARB_shader_image_load_store");
    bindlessTextures = hasExtension("GL_ARB_bindless_texture");
    sampleShading = versionAtLeast(4, 0) || hasExtension("GL_ARB_sample_shading");
    shaderStencilExport = hasExtension("GL_ARB_shader_stencil_export");
    fragmentShaderInterlock = hasExtension("GL_ARB_fragment_shader_interlock");
    timerQuery = versionAtLeast(3, 3) || hasExtension("GL_ARB_timer_query");
    while (glGetError() != GL_NO_ERROR)
    {
    }
}

bool GLCapabilities::isSoftwareRenderer() const
{
    std::string r = renderer;
    std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return std::tolower(c); });
    return r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
           r.find("swrast") != std::string::npos;
}

std::string GLCapabilities::summary() const
{
    return renderer + " (" + vendor + "), GL " + version;
}

std::string GLCapabilities::report() const
{
    std::ostringstream o;
    o << "GL vendor:       " << vendor << "\n"
      << "GL renderer:     " << renderer << "\n"
      << "GL version:      " << version << (compatibilityProfile ? " (compatibility)" : " (core)") << "\n"
      << "GLSL version:    " << glslVersion << "\n"
      << "max samples:     " << maxSamples << " (colour textures " << maxColorTextureSamples << ", depth "
      << maxDepthTextureSamples << ")\n"
      << "max texture:     " << maxTextureSize << ", array layers " << maxArrayTextureLayers << "\n"
      << "colour attach.:  " << maxColorAttachments << ", draw buffers " << maxDrawBuffers << "\n"
      << "compute:         " << (computeShaders ? "yes" : "no") << ", invocations "
      << maxComputeWorkGroupInvocations << "\n"
      << "SSBO:            " << (shaderStorageBuffers ? "yes" : "no") << ", block "
      << maxShaderStorageBlockSize << " bytes\n"
      << "image ld/st:     " << (shaderImageLoadStore ? "yes" : "no") << "\n"
      << "bindless tex.:   " << (bindlessTextures ? "yes" : "no") << "\n"
      << "sample shading:  " << (sampleShading ? "yes" : "no") << "\n"
      << "stencil export:  " << (shaderStencilExport ? "yes" : "no") << "\n"
      << "frag. interlock: " << (fragmentShaderInterlock ? "yes" : "no") << "\n"
      << "extensions:      " << extensions.size() << "\n";
    return o.str();
}

std::string GLCapabilities::toJson() const
{
    std::ostringstream o;
    auto b = [](bool v) { return v ? "true" : "false"; };
    o << "{\"vendor\": \"" << jsonEscape(vendor) << "\", \"renderer\": \"" << jsonEscape(renderer)
      << "\", \"version\": \"" << jsonEscape(version) << "\", \"glsl_version\": \"" << jsonEscape(glslVersion)
      << "\", \"major\": " << majorVersion << ", \"minor\": " << minorVersion
      << ", \"compatibility_profile\": " << b(compatibilityProfile) << ", \"max_samples\": " << maxSamples
      << ", \"max_texture_size\": " << maxTextureSize << ", \"compute_shaders\": " << b(computeShaders)
      << ", \"ssbo\": " << b(shaderStorageBuffers) << ", \"image_load_store\": " << b(shaderImageLoadStore)
      << ", \"bindless_textures\": " << b(bindlessTextures) << ", \"sample_shading\": " << b(sampleShading)
      << ", \"shader_stencil_export\": " << b(shaderStencilExport) << "}";
    return o.str();
}

} // namespace osgLoA
