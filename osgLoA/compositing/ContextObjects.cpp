// Deferred deletion of the GL names the order-independent transparency methods create.
#include "ContextObjects.h"

#include <osgLoA/render/GLCapabilities>

#include <osg/ContextData>
#include <osg/GLObjects>
#include <osg/Notify>

namespace osgLoA
{
namespace detail
{

namespace
{
template <int Kind> class NameManager : public osg::GLObjectManager
{
public:
    explicit NameManager(unsigned int contextID)
        : osg::GLObjectManager("osgLoA::detail::NameManager", contextID)
    {
    }
    void deleteGLObject(GLuint name) override
    {
        if (Kind == GL_NAME_TEXTURE)
        {
            glDeleteTextures(1, &name);
            return;
        }
        const char* entry = Kind == GL_NAME_FRAMEBUFFER ? "glDeleteFramebuffers"
                            : Kind == GL_NAME_QUERY     ? "glDeleteQueries"
                                                        : "glDeleteBuffers";
        void(GL_APIENTRY * f)(GLsizei, const GLuint*) = nullptr;
        if (loadGLFunction(f, entry)) f(1, &name);
    }
};
} // namespace

bool usableWithGL45(const char* who, const char* needs, bool loaded, bool& warned)
{
    GLCapabilities caps;
    caps.query();
    const bool usable = caps.versionAtLeast(4, 5) && loaded;
    if (!usable && !warned)
        OSG_WARN << "osgLoA::" << who << ": the context (" << caps.summary() << ") lacks GL 4.5 (" << needs
                 << "); nothing is routed" << std::endl;
    warned = warned || !usable;
    return usable;
}

void scheduleDeletion(GLNameKind kind, unsigned ctx, GLuint name)
{
    if (name == 0) return;
    switch (kind)
    {
    case GL_NAME_TEXTURE:
        osg::get<NameManager<GL_NAME_TEXTURE>>(ctx)->scheduleGLObjectForDeletion(name);
        break;
    case GL_NAME_FRAMEBUFFER:
        osg::get<NameManager<GL_NAME_FRAMEBUFFER>>(ctx)->scheduleGLObjectForDeletion(name);
        break;
    case GL_NAME_QUERY:
        osg::get<NameManager<GL_NAME_QUERY>>(ctx)->scheduleGLObjectForDeletion(name);
        break;
    case GL_NAME_BUFFER:
        osg::get<NameManager<GL_NAME_BUFFER>>(ctx)->scheduleGLObjectForDeletion(name);
        break;
    }
}

} // namespace detail
} // namespace osgLoA
