#include <osgLoA/util/ModelValidation>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/Notify>
#include <osg/PositionAttitudeTransform>
#include <osg/StateSet>
#include <osg/Texture>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <malloc.h>
#include <set>
#include <sstream>
#include <strings.h>
#include <unordered_map>

namespace osgLoA
{
namespace
{
std::string nameOf(const osg::Object& o, const char* kind)
{
    return o.getName().empty() ? std::string("an unnamed ") + kind
                               : std::string(kind) + " '" + o.getName() + "'";
}

/** An array's binding as the number stored: a file can store any number there, and loading a
 *  value outside osg::Array::Binding is undefined behaviour (UBSan; ModelFuzzer found 32772).
 *  The member's bytes are copied into an int instead: no enum value is loaded. */
struct BindingPeek : osg::Array
{
    static int of(const osg::Array& a)
    {
        static_assert(sizeof(osg::Array::Binding) == sizeof(int), "osg::Array::Binding is an int");
        int value = 0;
        std::memcpy(&value, &(a.*(&BindingPeek::_binding)), sizeof value);
        return value;
    }
};

/** A texture's wrap and filter modes as the numbers stored: OSG's serializers store any number
 *  a file holds in these enums (no fixed underlying type), and loading one outside the enum is
 *  undefined behaviour (UBSan; ModelFuzzer found a wrap mode of 16764417). */
struct TexturePeek : osg::Texture
{
    static int wrap(const osg::Texture& t, int which)
    {
        static_assert(sizeof(osg::Texture::WrapMode) == sizeof(int), "osg::Texture::WrapMode is an int");
        const osg::Texture::WrapMode* p = which == 0   ? &(t.*(&TexturePeek::_wrap_s))
                                          : which == 1 ? &(t.*(&TexturePeek::_wrap_t))
                                                       : &(t.*(&TexturePeek::_wrap_r));
        int value = 0;
        std::memcpy(&value, p, sizeof value);
        return value;
    }
    static int filter(const osg::Texture& t, bool mag)
    {
        static_assert(sizeof(osg::Texture::FilterMode) == sizeof(int), "osg::Texture::FilterMode is an int");
        int value = 0;
        std::memcpy(&value, mag ? &(t.*(&TexturePeek::_mag_filter)) : &(t.*(&TexturePeek::_min_filter)),
                    sizeof value);
        return value;
    }
};

bool knownWrap(int w)
{
    return w == osg::Texture::CLAMP || w == osg::Texture::CLAMP_TO_EDGE ||
           w == osg::Texture::CLAMP_TO_BORDER || w == osg::Texture::REPEAT || w == osg::Texture::MIRROR;
}

bool knownFilter(int f)
{
    return f == osg::Texture::LINEAR || f == osg::Texture::LINEAR_MIPMAP_LINEAR ||
           f == osg::Texture::LINEAR_MIPMAP_NEAREST || f == osg::Texture::NEAREST ||
           f == osg::Texture::NEAREST_MIPMAP_LINEAR || f == osg::Texture::NEAREST_MIPMAP_NEAREST;
}

/** Wrap and filter modes that are no GL mode, repaired to OSG's defaults with a warning. */
void repairModes(osg::Texture& t, const std::string& source)
{
    const struct
    {
        const char* name;
        osg::Texture::WrapParameter parameter;
    } wraps[] = {
        {"WRAP_S", osg::Texture::WRAP_S}, {"WRAP_T", osg::Texture::WRAP_T}, {"WRAP_R", osg::Texture::WRAP_R}};
    for (int w = 0; w < 3; ++w)
        if (!knownWrap(TexturePeek::wrap(t, w)))
        {
            OSG_WARN << source << ": " << nameOf(t, "texture") << " " << wraps[w].name << " "
                     << TexturePeek::wrap(t, w) << " is no wrap mode; CLAMP used" << std::endl;
            t.setWrap(wraps[w].parameter, osg::Texture::CLAMP);
        }
    const struct
    {
        const char* name;
        bool mag;
        osg::Texture::FilterParameter parameter;
        osg::Texture::FilterMode fallback;
        const char* fallbackName;
    } filters[] = {{"MIN_FILTER", false, osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR,
                    "LINEAR_MIPMAP_LINEAR"},
                   {"MAG_FILTER", true, osg::Texture::MAG_FILTER, osg::Texture::LINEAR, "LINEAR"}};
    for (const auto& f : filters)
        if (!knownFilter(TexturePeek::filter(t, f.mag)))
        {
            OSG_WARN << source << ": " << nameOf(t, "texture") << " " << f.name << " "
                     << TexturePeek::filter(t, f.mag) << " is no filter mode; " << f.fallbackName << " used"
                     << std::endl;
            t.setFilter(f.parameter, f.fallback);
        }
}

int storedBinding(const osg::Array& a)
{
    return BindingPeek::of(a);
}

bool knownBinding(int b)
{
    return b == osg::Array::BIND_UNDEFINED || b == osg::Array::BIND_OFF || b == osg::Array::BIND_OVERALL ||
           b == osg::Array::BIND_PER_PRIMITIVE_SET || b == osg::Array::BIND_PER_VERTEX;
}

/** Why geometry cannot be drawn safely, or "". */
/** Finite and within MAX_COORDINATE (NaN fails the comparison): a value that can place geometry. */
bool plausibleCoordinate(double x)
{
    return std::abs(x) <= ModelValidation::MAX_COORDINATE;
}

std::string geometryProblem(const osg::Geometry& g)
{
    const osg::Array* vertices = g.getVertexArray();
    const unsigned n = vertices ? vertices->getNumElements() : 0u;
    if (g.getNumPrimitiveSets() > 0 && !vertices) return "primitives without a vertex array";
    // Vertex coordinates, of whatever array type: finite, and within MAX_COORDINATE (a vertex
    // at 3e38 overflowed the bounding sphere's float arithmetic to infinity; ModelFuzzer found
    // it).
    if (vertices && vertices->getNumElements() > 0)
    {
        const std::size_t count = vertices->getTotalDataSize();
        const auto bad = [](double x) { return !plausibleCoordinate(x); };
        if (vertices->getDataType() == GL_FLOAT)
        {
            const auto* f = static_cast<const float*>(vertices->getDataPointer());
            for (std::size_t i = 0; i < count / sizeof(float); ++i)
                if (bad(f[i]))
                    return "a vertex coordinate (" + std::to_string(f[i]) +
                           ") that is not finite or beyond 1e15";
        }
        else if (vertices->getDataType() == GL_DOUBLE)
        {
            const auto* d = static_cast<const double*>(vertices->getDataPointer());
            for (std::size_t i = 0; i < count / sizeof(double); ++i)
                if (bad(d[i]))
                    return "a vertex coordinate (" + std::to_string(d[i]) +
                           ") that is not finite or beyond 1e15";
        }
    }
    // Per-vertex arrays as long as the vertex array.
    std::vector<const osg::Array*> arrays = {g.getNormalArray(), g.getColorArray(),
                                             g.getSecondaryColorArray(), g.getFogCoordArray()};
    for (unsigned u = 0; u < g.getNumTexCoordArrays(); ++u)
        arrays.push_back(g.getTexCoordArray(u));
    for (unsigned a = 0; a < g.getNumVertexAttribArrays(); ++a)
        arrays.push_back(g.getVertexAttribArray(a));
    if (vertices) arrays.push_back(vertices);
    for (const osg::Array* a : arrays)
        if (a && !knownBinding(storedBinding(*a)))
            return "an array binding " + std::to_string(storedBinding(*a)) + " that is no binding";
    if (vertices) arrays.pop_back();
    for (const osg::Array* a : arrays)
        if (a && storedBinding(*a) == osg::Array::BIND_PER_VERTEX && a->getNumElements() < n)
            return "a per-vertex array of " + std::to_string(a->getNumElements()) + " elements for " +
                   std::to_string(n) + " vertices";
    // Texture coordinates that are not finite (the texture tools size their work by the
    // coordinates' range; ModelFuzzer found a nan).
    for (unsigned u = 0; u < g.getNumTexCoordArrays(); ++u)
        if (const auto* t2 = dynamic_cast<const osg::Vec2Array*>(g.getTexCoordArray(u)))
            for (const osg::Vec2& t : *t2)
                if (!std::isfinite(t.x()) || !std::isfinite(t.y()))
                    return "texture coordinates on unit " + std::to_string(u) + " that are not finite";
    for (unsigned i = 0; i < g.getNumPrimitiveSets(); ++i)
    {
        const osg::PrimitiveSet* p = g.getPrimitiveSet(i);
        if (!p) return "an empty primitive set";
        if (const auto* da = dynamic_cast<const osg::DrawArrays*>(p))
        {
            if (da->getFirst() < 0 || da->getCount() < 0 ||
                static_cast<unsigned long long>(da->getFirst()) +
                        static_cast<unsigned long long>(da->getCount()) >
                    n)
                return "DrawArrays " + std::to_string(da->getFirst()) + "+" + std::to_string(da->getCount()) +
                       " past " + std::to_string(n) + " vertices";
        }
        else if (const auto* dal = dynamic_cast<const osg::DrawArrayLengths*>(p))
        {
            unsigned long long end = static_cast<unsigned long long>(std::max(0, dal->getFirst()));
            for (GLsizei len : *dal)
                end += static_cast<unsigned long long>(std::max<GLsizei>(0, len));
            if (dal->getFirst() < 0 || end > n)
                return "DrawArrayLengths past " + std::to_string(n) + " vertices";
        }
        else if (const auto* de = dynamic_cast<const osg::DrawElements*>(p))
        {
            for (unsigned k = 0; k < de->getNumIndices(); ++k)
                if (de->index(k) >= n)
                    return "index " + std::to_string(de->index(k)) + " past " + std::to_string(n) +
                           " vertices";
        }
        else if (p->getNumIndices() > 0 && n == 0)
            return "primitives without vertices";
    }
    return std::string();
}

std::string hex(unsigned v)
{
    char text[16];
    std::snprintf(text, sizeof text, "%x", v);
    return text;
}

/** Why an image's data cannot hold its stated size, or "". */
std::string imageProblem(const osg::Image& image)
{
    if (image.s() == 0 || image.t() == 0 || image.r() == 0)
    {
        if (!image.data()) return std::string(); // already empty
        // OSG's reads of such an image step by the stated row size: a 4x4x0 image with a packing
        // of 4,521,985 stated 0 bytes and made getColor read megabytes past its data (ModelFuzzer).
        return "states " + std::to_string(image.s()) + "x" + std::to_string(image.t()) + "x" +
               std::to_string(image.r()) + " with data";
    }
    if (!image.data())
        return "no data for a " + std::to_string(image.s()) + "x" + std::to_string(image.t()) + " image";
    // A pixel format and data type OSG gives no size: nothing can be read or hashed row by row
    // (an image of 0-byte rows and 2e9 of them kept FilterCache::imageHash busy for minutes;
    // ModelFuzzer found it).
    const unsigned bits = osg::Image::computePixelSizeInBits(image.getPixelFormat(), image.getDataType());
    if (bits == 0 && !image.isCompressed())
        return "pixel format 0x" + hex(image.getPixelFormat()) + " with data type 0x" +
               hex(image.getDataType()) + " has no pixel size";
    // Rows are aligned to the packing (GL_UNPACK_ALIGNMENT: 1, 2, 4 or 8) and may be longer than
    // the width (the row length); OSG steps through the data by both.
    const unsigned packing = image.getPacking();
    if (packing != 1 && packing != 2 && packing != 4 && packing != 8)
        return "a row alignment (packing) of " + std::to_string(packing) + ", not 1, 2, 4 or 8";
    if (image.getRowLength() != 0 && image.getRowLength() < image.s())
        return "a row length of " + std::to_string(image.getRowLength()) +
               " pixels, shorter than its width " + std::to_string(image.s());
    // OSG's own size is an unsigned int, which 65536x65536x4 overflows: the base level in 64 bits.
    const unsigned long long rowPixels = image.getRowLength() ? image.getRowLength() : image.s();
    const unsigned long long rowBytes = ((rowPixels * bits + 7) / 8 + packing - 1) / packing * packing;
    const unsigned long long base = rowBytes * image.t() * image.r();
    const unsigned long long stated = std::max<unsigned long long>(
        image.getTotalSizeInBytesIncludingMipmaps(), image.isCompressed() ? 0 : base);
    if (image.getAllocationMode() == osg::Image::USE_NEW_DELETE ||
        image.getAllocationMode() == osg::Image::USE_MALLOC_FREE)
    {
        const unsigned long long held = ::malloc_usable_size(const_cast<unsigned char*>(image.data()));
        if (stated > held)
            return "states " + std::to_string(image.s()) + "x" + std::to_string(image.t()) + "x" +
                   std::to_string(image.r()) + " (" + std::to_string(stated) + " bytes) but holds " +
                   std::to_string(held) + " bytes";
    }
    return std::string();
}

class Validator : public osg::NodeVisitor
{
public:
    Validator(ModelValidation& result, const std::string& source)
        : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), _result(result), _source(source)
    {
    }

    void apply(osg::Node& node) override
    {
        check(node.getStateSet());
        checkBound(node);
        traverse(node);
    }

    void apply(osg::MatrixTransform& t) override
    {
        if (!finite(t.getMatrix().ptr(), 16))
        {
            repaired(t, "a matrix that is not finite", "identity");
            t.setMatrix(osg::Matrix::identity());
        }
        apply(static_cast<osg::Node&>(t));
    }

    void apply(osg::PositionAttitudeTransform& t) override
    {
        const double v[] = {t.getPosition().x(),   t.getPosition().y(),   t.getPosition().z(),
                            t.getPivotPoint().x(), t.getPivotPoint().y(), t.getPivotPoint().z(),
                            t.getScale().x(),      t.getScale().y(),      t.getScale().z(),
                            t.getAttitude().x(),   t.getAttitude().y(),   t.getAttitude().z(),
                            t.getAttitude().w()};
        if (!finite(v, 13))
        {
            repaired(t, "a position, pivot, scale or attitude that is not finite", "identity");
            t.setPosition(osg::Vec3d());
            t.setPivotPoint(osg::Vec3d());
            t.setScale(osg::Vec3d(1, 1, 1));
            t.setAttitude(osg::Quat());
        }
        apply(static_cast<osg::Node&>(t));
    }

    void apply(osg::Geode& geode) override
    {
        check(geode.getStateSet());
        checkBound(geode);
        for (unsigned i = geode.getNumDrawables(); i-- > 0;)
        {
            osg::Drawable* d = geode.getDrawable(i);
            if (!d) continue;
            check(d->getStateSet());
            const osg::BoundingBox& ib = d->getInitialBound();
            if (ib.valid() && !(finite(ib._min.ptr(), 3) && finite(ib._max.ptr(), 3)))
            {
                repaired(*d, "an initial bound that is not finite", "none");
                d->setInitialBound(osg::BoundingBox());
            }
            const osg::Geometry* g = d->asGeometry();
            const std::string why = g ? geometryProblem(*g) : std::string();
            if (why.empty()) continue;
            const std::string what = nameOf(*d, "drawable") + " in " + nameOf(geode, "Geode") + ": " + why;
            OSG_WARN << _source << ": " << what << "; dropped" << std::endl;
            _result.removedDrawables.push_back(what);
            geode.removeDrawables(i, 1);
        }
        traverse(geode);
    }

private:
    template <typename T> static bool finite(const T* v, int n)
    {
        for (int i = 0; i < n; ++i)
            if (!plausibleCoordinate(v[i])) return false;
        return true;
    }

    void repaired(osg::Object& o, const char* what, const char* now)
    {
        const std::string text = nameOf(o, o.className()) + ": " + what;
        OSG_WARN << _source << ": " << text << "; set to " << now << std::endl;
        _result.repairedValues.push_back(text);
    }

    /** A node's stored initial bound (InitialBound in .osgt/.osgb) replaces the computed one:
     *  a centre at infinity made the whole scene's bound infinite (ModelFuzzer). */
    void checkBound(osg::Node& node)
    {
        const osg::BoundingSphere& ib = node.getInitialBound();
        if (ib.valid() && !(finite(ib._center.ptr(), 3) && finite(&ib._radius, 1)))
        {
            repaired(node, "an initial bound that is not finite", "none");
            node.setInitialBound(osg::BoundingSphere());
        }
    }

    void check(osg::StateSet* ss)
    {
        if (!ss || !_seen.insert(ss).second) return;
        for (unsigned u = 0; u < ss->getTextureAttributeList().size(); ++u)
        {
            auto* t = dynamic_cast<osg::Texture*>(ss->getTextureAttribute(u, osg::StateAttribute::TEXTURE));
            if (!t) continue;
            repairModes(*t, _source);
            for (unsigned i = 0; i < t->getNumImages(); ++i)
            {
                osg::Image* image = t->getImage(i);
                if (!image) continue;
                const std::string why = imageProblem(*image);
                if (why.empty()) continue;
                const std::string name = image->getFileName().empty()
                                             ? nameOf(*image, "image")
                                             : "image '" + image->getFileName() + "'";
                OSG_WARN << _source << ": " << name << " " << why << "; left empty" << std::endl;
                _result.emptiedImages.push_back(name + ": " + why);
                const std::string fileName = image->getFileName();
                image->setImage(0, 0, 0, image->getInternalTextureFormat(), image->getPixelFormat(),
                                image->getDataType(), nullptr, osg::Image::NO_DELETE);
                image->setFileName(fileName);
            }
        }
    }

    ModelValidation& _result;
    std::string _source;
    std::set<const osg::StateSet*> _seen;
};
} // namespace

namespace
{
/** Every node's and drawable's bound recomputed on next use (dirtyBound() reaches parents only). */
void dirtyBounds(osg::Node& scene)
{
    struct Dirty : osg::NodeVisitor
    {
        Dirty() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Node& n) override
        {
            n.dirtyBound();
            traverse(n);
        }
    } dirty;
    scene.accept(dirty);
}

std::string nodeLabel(const osg::Node& n)
{
    return std::string(n.libraryName()) + "::" + n.className() +
           (n.getName().empty() ? std::string() : " '" + n.getName() + "'");
}

/** Depth-first over groups' children with an explicit stack: a child already on the stack is a
 *  cycle; a stack deeper than the limit is refused. A node reached again by another path (a
 *  shared subgraph) is not entered twice. */
void checkStructure(osg::Node& scene, const std::string& source)
{
    struct Frame
    {
        osg::Group* group;
        unsigned next;
    };
    std::unordered_map<const osg::Node*, char> state; // 1 on the stack, 2 done
    std::vector<Frame> stack;
    const auto enter = [&](osg::Node& n)
    {
        state[&n] = 1;
        if (stack.size() >= ModelValidation::MAX_SCENE_DEPTH)
            throw ModelStructureError(source + ": the scene graph is deeper than " +
                                      std::to_string(ModelValidation::MAX_SCENE_DEPTH) + " levels (at " +
                                      nodeLabel(n) + ")");
        if (osg::Group* g = n.asGroup())
            stack.push_back({g, 0});
        else
            state[&n] = 2;
    };
    enter(scene);
    while (!stack.empty())
    {
        Frame& f = stack.back();
        if (f.next >= f.group->getNumChildren())
        {
            state[f.group] = 2;
            stack.pop_back();
            continue;
        }
        osg::Node* child = f.group->getChild(f.next++);
        if (!child) continue;
        const auto it = state.find(child);
        if (it == state.end())
            enter(*child);
        else if (it->second == 1)
        {
            // The edge that closes the cycle is cut: its references would keep the graph alive
            // after the caller lets go of it.
            const osg::ref_ptr<osg::Node> keep = child;
            f.group->removeChild(child);
            throw ModelStructureError(source + ": the scene graph has a cycle: " + nodeLabel(*child) +
                                      " is its own ancestor");
        }
    }
}
} // namespace

ModelValidation ModelValidation::validate(osg::Node& scene, const std::string& source)
{
    checkStructure(scene, source);
    ModelValidation result;
    Validator v(result, source);
    scene.accept(v);
    if (!result.removedDrawables.empty() || !result.repairedValues.empty()) dirtyBounds(scene);
    // What no repair above reaches (a node kind with numbers of its own) is refused: nothing
    // infinite goes on to the tools.
    const osg::BoundingSphere bs = scene.getBound();
    if (bs.valid() && !(std::isfinite(bs.radius()) && std::isfinite(bs.center().length())))
        throw ModelStructureError(source + ": the scene's bounding sphere is not finite (" +
                                  nodeLabel(scene) + " and below)");
    return result;
}

std::string ModelValidation::checkOsgtStructure(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot be opened";
    std::ostringstream text;
    text << in.rdbuf();
    return checkOsgtText(text.str());
}

std::string ModelValidation::checkOsgtText(const std::string& text)
{
    // One pass, in runs: a table lookup per character skips the word characters between
    // delimiters and the plain characters inside strings (the text is NUL-terminated, and NUL is
    // a stop: a NUL inside the text ends a run and is refused below as a control character). Per
    // character the loop used to make half a dozen comparisons, each a callback under the
    // fuzzers' coverage instrumentation.
    struct Stops
    {
        bool outside[256] = {}, inString[256] = {};
        Stops()
        {
            for (int c = 0; c < 0x20; ++c)
                outside[c] = inString[c] = c != '\t' && c != '\n' && c != '\r';
            for (unsigned char c : {' ', '\t', '\n', '\r', '{', '}', '"'})
                outside[c] = true;
            inString[static_cast<unsigned char>('"')] = inString[static_cast<unsigned char>('\\')] = true;
        }
    };
    static const Stops stops;
    const char* const p = text.c_str();
    const std::size_t n = text.size();
    bool inString = false, sawObject = false;
    long depth = 0;
    char last = 0;
    // A word outside strings that spells a non-finite number: OSG's text reader takes "nan" and
    // "inf" as 0 (a scenario's "Near nan" validated as 0), so they are refused here.
    const auto nonFinite = [&](std::size_t start, std::size_t end) -> std::string
    {
        std::size_t b = start;
        if (b < end && (p[b] == '-' || p[b] == '+')) ++b;
        const std::size_t len = end - b;
        if (len < 3 || ((p[b] | 0x20) != 'n' && (p[b] | 0x20) != 'i')) return std::string();
        const auto is = [&](const char* w, std::size_t k) { return strncasecmp(p + b, w, k) == 0; };
        if ((len == 3 && (is("nan", 3) || is("inf", 3))) || (len == 8 && is("infinity", 8)) ||
            (len >= 4 && is("nan(", 4)))
            return "the text holds a number that is not finite ('" + text.substr(start, end - start) +
                   "' at byte " + std::to_string(start) + ")";
        return std::string();
    };
    std::size_t i = 0;
    for (;;)
    {
        const bool* const stop = inString ? stops.inString : stops.outside;
        std::size_t at = i; // the delimiter, or n
        while (!stop[static_cast<unsigned char>(p[at])])
            ++at;
        const std::size_t run = at - i;
        const unsigned char u = static_cast<unsigned char>(p[at]);
        if (at < n && u < 0x20 && u != '\t' && u != '\n' && u != '\r')
        {
            // OSG's reader can loop on them too, and no writer puts them in a text file.
            std::ostringstream s;
            s << "the text contains the control character 0x" << std::hex << int(u) << " at byte " << std::dec
              << at;
            return s.str();
        }
        if (!inString && run > 0)
        {
            last = p[at - 1];
            const std::string bad = nonFinite(i, at);
            if (!bad.empty()) return bad;
        }
        i = at;
        if (i >= n) break;
        const char c = p[i];
        if (inString)
        {
            if (c == '\\')
                i = std::min(i + 2, n); // an escaped character, whatever it is
            else
                inString = false, ++i; // the closing quote
            continue;
        }
        if (c == '"')
            inString = true;
        else if (c == '{')
            ++depth, sawObject = true;
        else if (c == '}' && --depth < 0)
            return "a '}' closes no object";
        if (c != ' ' && c != '\t' && c != '\n' && c != '\r') last = c;
        ++i;
    }
    if (inString) return "the text ends inside a quoted string";
    if (depth != 0) return "the text ends inside an object ('{' and '}' do not match)";
    if (!sawObject) return "the text holds no object";
    if (last != '}') return "the text does not end with its last object's '}'";
    return std::string();
}

} // namespace osgLoA
