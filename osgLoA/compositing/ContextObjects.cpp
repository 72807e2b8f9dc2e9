// Deferred deletion of the GL names the order-independent transparency methods create.
#include "ContextObjects.h"

#include <osg/ContextData>
#include <osg/GLExtensions>
#include <osg/GLObjects>

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
        using Delete = void(GL_APIENTRY*)(GLsizei, const GLuint*);
        if (Kind == GL_NAME_TEXTURE)
        {
            glDeleteTextures(1, &name);
            return;
        }
        const char* entry = Kind == GL_NAME_FRAMEBUFFER ? "glDeleteFramebuffers"
                            : Kind == GL_NAME_QUERY     ? "glDeleteQueries"
                                                        : "glDeleteBuffers";
        if (const Delete f = reinterpret_cast<Delete>(osg::getGLExtensionFuncPtr(entry))) f(1, &name);
    }
};
} // namespace

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
