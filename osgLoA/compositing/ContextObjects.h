/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
// Internal: GL names that the order-independent transparency methods create per context with
// direct state access (outside OSG's own texture and buffer objects): a sampler binding them, and
// their deferred deletion in their context.
#ifndef OSGLOA_COMPOSITING_CONTEXTOBJECTS_H
#define OSGLOA_COMPOSITING_CONTEXTOBJECTS_H 1

#include <osg/GL>
#include <osg/GLExtensions>
#include <osg/State>
#include <osg/Texture>

#include <vector>

namespace osgLoA
{
namespace detail
{

/** A sampler binding a per-context texture name of the given target, owned by its creator. */
class ContextTexture : public osg::Texture
{
public:
    ContextTexture() = default;
    explicit ContextTexture(GLenum target) : _target(target) {}
    ContextTexture(const ContextTexture& o, const osg::CopyOp& op = osg::CopyOp::SHALLOW_COPY)
        : osg::Texture(o, op), _target(o._target), _names(o._names)
    {
    }
    META_StateAttribute(osgLoA, ContextTexture, TEXTURE);

    int compare(const osg::StateAttribute& sa) const override
    {
        if (this == &sa) return 0;
        const int t = compareTexture(static_cast<const osg::Texture&>(sa));
        if (t != 0) return t;
        return this < &sa ? -1 : 1;
    }
    GLenum getTextureTarget() const override { return _target; }
    bool getModeUsage(osg::StateAttribute::ModeUsage&) const override { return false; }
    void setImage(unsigned int, osg::Image*) override {}
    osg::Image* getImage(unsigned int) override { return nullptr; }
    const osg::Image* getImage(unsigned int) const override { return nullptr; }
    unsigned int getNumImages() const override { return 0; }
    void allocateMipmap(osg::State&) const override {}
    void computeInternalFormat() const override {}
    void releaseGLObjects(osg::State* = nullptr) const override {} // the creator owns the names

    void apply(osg::State& state) const override
    {
        const unsigned ctx = state.getContextID();
        glBindTexture(_target, ctx < _names.size() ? _names[ctx] : 0);
    }

    void setTextureName(unsigned ctx, GLuint name)
    {
        if (_names.size() <= ctx) _names.resize(ctx + 1, 0);
        _names[ctx] = name;
    }

private:
    GLenum _target = GL_TEXTURE_2D;
    std::vector<GLuint> _names;
};

enum GLNameKind
{
    GL_NAME_TEXTURE,
    GL_NAME_FRAMEBUFFER,
    GL_NAME_QUERY,
    GL_NAME_BUFFER
};

/** Loads a GL entry point of the current context into f; false where the driver lacks it. */
template <typename F> bool loadGLFunction(F& f, const char* name)
{
    f = reinterpret_cast<F>(osg::getGLExtensionFuncPtr(name));
    return f != nullptr;
}

/** Whether the current context offers GL 4.5 and loaded holds (every entry point a method needs
 *  was found); the first time it does not, one OSG_WARN names who, the context and what is
 *  missing (warned remembers it). */
bool usableWithGL45(const char* who, const char* needs, bool loaded, bool& warned);

/** Deletes the name in context ctx at its next osg::flushDeletedGLObjects (any thread). */
void scheduleDeletion(GLNameKind kind, unsigned ctx, GLuint name);

} // namespace detail
} // namespace osgLoA

#endif
