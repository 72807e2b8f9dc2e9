/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterImage>
#include <osgLoA/palette/TextureHistogram>

#include "../render/GLProgramBuild.h"
#include <osgLoA/render/ShaderLibrary>

#include <osg/GLExtensions>
#include <osg/NodeVisitor>
#include <osg/Texture2D>
#include <osg/TriangleIndexFunctor>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace osgLoA
{

namespace
{

/** Fill rule for texel centres on an edge, in window coordinates with y up and the triangle
 *  counter-clockwise: an edge of direction d is included when d.y < 0 (a left edge) or when
 *  d.y == 0 and d.x > 0 (a bottom edge). Measured on llvmpipe (TextureHistogramGLTest). */
bool edgeIncluded(std::int64_t dx, std::int64_t dy)
{
    return dy < 0 || (dy == 0 && dx > 0);
}

const int kSubPixel = 256;           // 8 sub-pixel bits
const int kMaxVirtualAxis = 1 << 20; // texels per axis of the virtual target

/** Reads component c (0..3) of element i of a float or double array of 2-4 components. */
class ArrayReader
{
public:
    ArrayReader(const osg::Array* a, const std::string& what)
    {
        if (!a || a->getNumElements() == 0) throw std::invalid_argument("TextureHistogram: no " + what);
        const GLenum type = a->getDataType();
        _size = int(a->getDataSize());
        if ((type != GL_FLOAT && type != GL_DOUBLE) || _size < 2 || _size > 4)
            throw std::invalid_argument("TextureHistogram: " + what +
                                        " must hold 2 to 4 float or double components per element");
        _double = type == GL_DOUBLE;
        _data = static_cast<const unsigned char*>(a->getDataPointer());
        _count = a->getNumElements();
    }
    unsigned count() const { return _count; }
    int size() const { return _size; }
    double get(unsigned i, int c) const
    {
        if (c >= _size) return 0.0;
        if (_double) return reinterpret_cast<const double*>(_data)[std::size_t(i) * _size + c];
        return reinterpret_cast<const float*>(_data)[std::size_t(i) * _size + c];
    }

private:
    const unsigned char* _data = nullptr;
    unsigned _count = 0;
    int _size = 0;
    bool _double = false;
};

struct TriangleCollector
{
    std::vector<unsigned> indices;
    void operator()(unsigned a, unsigned b, unsigned c)
    {
        indices.push_back(a);
        indices.push_back(b);
        indices.push_back(c);
    }
};

/** A geometry's triangles: vertex indices (three per triangle), checked against the vertex
 *  and texcoord arrays, and readers of both arrays. */
struct GeometryTriangles
{
    std::unique_ptr<ArrayReader> vertices, texcoords;
    std::vector<unsigned> indices;

    GeometryTriangles(const osg::Geometry& g, unsigned unit)
    {
        const osg::Array* va = g.getVertexArray();
        if (!va || va->getNumElements() == 0)
            throw std::invalid_argument("TextureHistogram: the geometry has no vertex array");
        const osg::Array* ta = g.getTexCoordArray(unit);
        if (!ta || ta->getNumElements() == 0)
            throw std::invalid_argument("TextureHistogram: the geometry has no texture coordinates on unit " +
                                        std::to_string(unit));
        if (ta->getNumElements() != va->getNumElements())
            throw std::invalid_argument("TextureHistogram: texcoord count " +
                                        std::to_string(ta->getNumElements()) + " on unit " +
                                        std::to_string(unit) + " does not match vertex count " +
                                        std::to_string(va->getNumElements()));
        vertices.reset(new ArrayReader(va, "vertex array"));
        texcoords.reset(new ArrayReader(ta, "texcoord array of unit " + std::to_string(unit)));
        osg::TriangleIndexFunctor<TriangleCollector> f;
        const_cast<osg::Geometry&>(g).accept(f);
        for (unsigned i : f.indices)
            if (i >= va->getNumElements())
                throw std::invalid_argument("TextureHistogram: triangle index " + std::to_string(i) +
                                            " past the vertex array of " +
                                            std::to_string(va->getNumElements()));
        indices.swap(f.indices);
    }
};

std::string rangeText(const TextureHistogram::TexCoordRange& r)
{
    return "u [" + std::to_string(r.uMin) + ", " + std::to_string(r.uMax) + "], v [" +
           std::to_string(r.vMin) + ", " + std::to_string(r.vMax) + "]";
}

/** A triangle in snapped virtual-target coordinates (1/256 texel) with its weight. */
struct SnappedTriangle
{
    std::int64_t x[3], y[3];
    double weight;
};

/** Everything both versions need: the virtual target and the snapped weighted triangles. */
struct Setup
{
    TextureHistogram::TexCoordRange range;
    int targetW = 0, targetH = 0;
    std::vector<SnappedTriangle> triangles;
};

Setup prepare(const osg::Geometry& g, int width, int height, unsigned unit)
{
    if (width < 1) throw std::invalid_argument("TextureHistogram: width " + std::to_string(width) + " < 1");
    if (height < 1)
        throw std::invalid_argument("TextureHistogram: height " + std::to_string(height) + " < 1");
    Setup s;
    const std::vector<TextureHistogram::TriangleAreas> tris = TextureHistogram::triangleAreas(g, unit);
    s.range = TextureHistogram::texCoordRange(g, unit);
    if (!s.range.valid) return s;
    const double tw = double(s.range.periodsU()) * width, th = double(s.range.periodsV()) * height;
    if (tw > kMaxVirtualAxis || th > kMaxVirtualAxis)
        throw std::invalid_argument("TextureHistogram: texture coordinate range " + rangeText(s.range) +
                                    " of a " + std::to_string(width) + "x" + std::to_string(height) +
                                    " texture needs more than 2^20 texels per axis");
    s.targetW = int(tw);
    s.targetH = int(th);
    for (const auto& t : tris)
    {
        const double w = t.objectProportion * t.textureProportion;
        if (!(w > 0)) continue;
        SnappedTriangle st;
        for (int k = 0; k < 3; ++k)
        {
            st.x[k] = std::llround((t.uv[k].x() - s.range.u0) * width * kSubPixel);
            st.y[k] = std::llround((t.uv[k].y() - s.range.v0) * height * kSubPixel);
        }
        st.weight = w;
        const std::int64_t area2 =
            (st.x[1] - st.x[0]) * (st.y[2] - st.y[0]) - (st.y[1] - st.y[0]) * (st.x[2] - st.x[0]);
        if (area2 == 0) continue;
        if (area2 < 0)
        {
            std::swap(st.x[1], st.x[2]);
            std::swap(st.y[1], st.y[2]);
        }
        s.triangles.push_back(st);
    }
    return s;
}

/** Calls visit(i, j) for every virtual texel whose centre the (counter-clockwise) triangle
 *  covers under the fill rule. */
template <class Visit> void rasterize(const SnappedTriangle& t, int targetW, int targetH, Visit visit)
{
    const std::int64_t minX = std::min({t.x[0], t.x[1], t.x[2]}), maxX = std::max({t.x[0], t.x[1], t.x[2]});
    const std::int64_t minY = std::min({t.y[0], t.y[1], t.y[2]}), maxY = std::max({t.y[0], t.y[1], t.y[2]});
    const std::int64_t half = kSubPixel / 2;
    // centre of texel i is i * 256 + 128: i in [ceil((min - 128) / 256), floor((max - 128) / 256)]
    auto floorDiv = [](std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
    const std::int64_t i0 = std::max<std::int64_t>(0, -floorDiv(-(minX - half), kSubPixel));
    const std::int64_t i1 = std::min<std::int64_t>(targetW - 1, floorDiv(maxX - half, kSubPixel));
    const std::int64_t j0 = std::max<std::int64_t>(0, -floorDiv(-(minY - half), kSubPixel));
    const std::int64_t j1 = std::min<std::int64_t>(targetH - 1, floorDiv(maxY - half, kSubPixel));
    std::int64_t dx[3], dy[3];
    bool incl[3];
    for (int e = 0; e < 3; ++e)
    {
        const int n = (e + 1) % 3;
        dx[e] = t.x[n] - t.x[e];
        dy[e] = t.y[n] - t.y[e];
        incl[e] = edgeIncluded(dx[e], dy[e]);
    }
    for (std::int64_t j = j0; j <= j1; ++j)
    {
        const std::int64_t py = j * kSubPixel + half;
        for (std::int64_t i = i0; i <= i1; ++i)
        {
            const std::int64_t px = i * kSubPixel + half;
            bool inside = true;
            for (int e = 0; e < 3 && inside; ++e)
            {
                const std::int64_t f = dx[e] * (py - t.y[e]) - dy[e] * (px - t.x[e]);
                inside = f > 0 || (f == 0 && incl[e]);
            }
            if (inside) visit(int(i), int(j));
        }
    }
}

} // namespace

std::vector<TextureHistogram::TriangleAreas> TextureHistogram::triangleAreas(const osg::Geometry& g,
                                                                             unsigned unit)
{
    const GeometryTriangles gt(g, unit);
    const std::vector<unsigned>& idx = gt.indices;
    const ArrayReader* v = gt.vertices.get();
    const ArrayReader* t = gt.texcoords.get();
    std::vector<TriangleAreas> out(idx.size() / 3);
    double sumO = 0, sumT = 0;
    for (std::size_t k = 0; k < out.size(); ++k)
    {
        osg::Vec3d p[3];
        for (int c = 0; c < 3; ++c)
        {
            const unsigned i = idx[3 * k + c];
            p[c].set(v->get(i, 0), v->get(i, 1), v->size() >= 3 ? v->get(i, 2) : 0.0);
            out[k].uv[c].set(t->get(i, 0), t->get(i, 1));
        }
        out[k].objectArea = 0.5 * ((p[1] - p[0]) ^ (p[2] - p[0])).length();
        const osg::Vec2d a = out[k].uv[1] - out[k].uv[0], b = out[k].uv[2] - out[k].uv[0];
        out[k].textureArea = 0.5 * std::fabs(a.x() * b.y() - a.y() * b.x());
        sumO += out[k].objectArea;
        sumT += out[k].textureArea;
    }
    for (auto& tri : out)
    {
        tri.objectProportion = sumO > 0 ? tri.objectArea / sumO : 0.0;
        tri.textureProportion = sumT > 0 ? tri.textureArea / sumT : 0.0;
    }
    return out;
}

TextureHistogram::TexCoordRange TextureHistogram::texCoordRange(const osg::Geometry& g, unsigned unit)
{
    const GeometryTriangles gt(g, unit);
    const std::vector<unsigned>& idx = gt.indices;
    const ArrayReader* t = gt.texcoords.get();
    TexCoordRange r;
    for (unsigned i : idx)
    {
        const double u = t->get(i, 0), w = t->get(i, 1);
        if (!r.valid)
        {
            r.uMin = r.uMax = u;
            r.vMin = r.vMax = w;
            r.valid = true;
        }
        r.uMin = std::min(r.uMin, u);
        r.uMax = std::max(r.uMax, u);
        r.vMin = std::min(r.vMin, w);
        r.vMax = std::max(r.vMax, w);
    }
    if (!r.valid) return r;
    if (!std::isfinite(r.uMin) || !std::isfinite(r.uMax) || !std::isfinite(r.vMin) ||
        !std::isfinite(r.vMax) || std::fabs(r.uMin) > 1e9 || std::fabs(r.uMax) > 1e9 ||
        std::fabs(r.vMin) > 1e9 || std::fabs(r.vMax) > 1e9)
        throw std::invalid_argument("TextureHistogram: texture coordinate range " + rangeText(r) +
                                    " is not finite or too large");
    r.u0 = int(std::floor(r.uMin));
    r.u1 = std::max(r.u0 + 1, int(std::ceil(r.uMax)));
    r.v0 = int(std::floor(r.vMin));
    r.v1 = std::max(r.v0 + 1, int(std::ceil(r.vMax)));
    return r;
}

std::vector<double> TextureHistogram::texelWeights(const osg::Geometry& g, int width, int height,
                                                   const ImageBorder& border, unsigned unit)
{
    const Setup s = prepare(g, width, height, unit);
    std::vector<double> out(std::size_t(width) * std::size_t(height), 0.0);
    const int gx = s.range.u0 * width, gy = s.range.v0 * height;
    for (const SnappedTriangle& t : s.triangles)
        rasterize(t, s.targetW, s.targetH,
                  [&](int i, int j)
                  {
                      const int x = wrapIndex(gx + i, width, border.s),
                                y = wrapIndex(gy + j, height, border.t);
                      out[std::size_t(y) * std::size_t(width) + std::size_t(x)] += t.weight;
                  });
    return out;
}

namespace
{

GLuint compileStage(osg::GLExtensions* ext, GLenum type, const std::string& name)
{
    std::string log;
    const GLuint sh = detail::compileShaderStage(ext, type, ShaderLibrary::getSource(name).text, log);
    if (!sh) throw std::runtime_error("TextureHistogram: shader '" + name + "' failed to compile: " + log);
    return sh;
}

GLuint histogramProgram(osg::GLExtensions* ext)
{
    GLuint vs = compileStage(ext, GL_VERTEX_SHADER, "loa_palette_histogram.vert.glsl");
    GLuint fs = 0;
    try
    {
        fs = compileStage(ext, GL_FRAGMENT_SHADER, "loa_palette_histogram.frag.glsl");
    }
    catch (...)
    {
        ext->glDeleteShader(vs);
        throw;
    }
    std::string log;
    const GLuint p = detail::linkProgram(ext, {vs, fs}, log);
    if (!p) throw std::runtime_error("TextureHistogram: histogram program failed to link: " + log);
    return p;
}

/** Saves the GL state texelWeightsGpu touches and restores it on destruction. */
class SavedGLState
{
public:
    explicit SavedGLState(osg::GLExtensions* ext) : _ext(ext)
    {
        glGetIntegerv(GL_CURRENT_PROGRAM, &_program);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &_drawFbo);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &_readFbo);
        glGetIntegerv(GL_VIEWPORT, _viewport);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &_vao);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &_vbo);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &_texture);
        glGetIntegerv(GL_BLEND_SRC_RGB, &_blend[0]);
        glGetIntegerv(GL_BLEND_DST_RGB, &_blend[1]);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &_blend[2]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &_blend[3]);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &_equation);
        glGetIntegerv(GL_PACK_ALIGNMENT, &_packAlign);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &_packRow);
        glGetFloatv(GL_COLOR_CLEAR_VALUE, _clear);
        for (int k = 0; k < kCaps; ++k)
            _enabled[k] = glIsEnabled(caps()[k]);
    }
    ~SavedGLState()
    {
        _ext->glUseProgram(GLuint(_program));
        _ext->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(_drawFbo));
        _ext->glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(_readFbo));
        glViewport(_viewport[0], _viewport[1], _viewport[2], _viewport[3]);
        _ext->glBindVertexArray(GLuint(_vao));
        _ext->glBindBuffer(GL_ARRAY_BUFFER, GLuint(_vbo));
        glBindTexture(GL_TEXTURE_2D, GLuint(_texture));
        _ext->glBlendFuncSeparate(GLenum(_blend[0]), GLenum(_blend[1]), GLenum(_blend[2]), GLenum(_blend[3]));
        _ext->glBlendEquation(GLenum(_equation));
        glPixelStorei(GL_PACK_ALIGNMENT, _packAlign);
        glPixelStorei(GL_PACK_ROW_LENGTH, _packRow);
        glClearColor(_clear[0], _clear[1], _clear[2], _clear[3]);
        for (int k = 0; k < kCaps; ++k)
            _enabled[k] ? glEnable(caps()[k]) : glDisable(caps()[k]);
    }
    SavedGLState(const SavedGLState&) = delete;
    SavedGLState& operator=(const SavedGLState&) = delete;

    static const int kCaps = 6;
    static const GLenum* caps()
    {
        static const GLenum c[kCaps] = {GL_BLEND,        GL_DEPTH_TEST, GL_STENCIL_TEST,
                                        GL_SCISSOR_TEST, GL_CULL_FACE,  GL_MULTISAMPLE};
        return c;
    }

private:
    osg::GLExtensions* _ext;
    GLint _program = 0, _drawFbo = 0, _readFbo = 0, _viewport[4] = {0, 0, 0, 0}, _vao = 0, _vbo = 0,
          _texture = 0;
    GLint _blend[4] = {GL_ONE, GL_ZERO, GL_ONE, GL_ZERO}, _equation = GL_FUNC_ADD, _packAlign = 4,
          _packRow = 0;
    GLfloat _clear[4] = {0, 0, 0, 0};
    GLboolean _enabled[kCaps] = {};
};

/** GL objects of one texelWeightsGpu call, deleted on destruction. */
struct GLObjects
{
    osg::GLExtensions* ext;
    GLuint program = 0, vao = 0, vbo = 0, fbo = 0, texture = 0;
    explicit GLObjects(osg::GLExtensions* e) : ext(e) {}
    ~GLObjects()
    {
        if (program) ext->glDeleteProgram(program);
        if (vao) ext->glDeleteVertexArrays(1, &vao);
        if (vbo) ext->glDeleteBuffers(1, &vbo);
        if (fbo) ext->glDeleteFramebuffers(1, &fbo);
        if (texture) glDeleteTextures(1, &texture);
    }
    GLObjects(const GLObjects&) = delete;
    GLObjects& operator=(const GLObjects&) = delete;
};

} // namespace

std::vector<float> TextureHistogram::texelWeightsGpu(osg::State& state, const osg::Geometry& g, int width,
                                                     int height, const ImageBorder& border, unsigned unit,
                                                     int maxTileSize)
{
    const Setup s = prepare(g, width, height, unit);
    std::vector<double> folded(std::size_t(width) * std::size_t(height), 0.0);
    if (!s.triangles.empty())
    {
        if (!state.get<osg::GLExtensions>()) state.initializeExtensionProcs();
        osg::GLExtensions* ext = state.get<osg::GLExtensions>();
        if (!ext) throw std::runtime_error("TextureHistogram: no GL extensions for the current context");
        for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
        {
        } // errors left by the caller are not ours to report
        GLint maxTexture = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
        int tile = maxTileSize > 0 ? maxTileSize : std::min(4096, int(maxTexture));
        tile = std::max(1, std::min(tile, int(maxTexture)));
        const int tileW = std::min(tile, s.targetW), tileH = std::min(tile, s.targetH);

        SavedGLState saved(ext);
        GLObjects obj(ext);
        obj.program = histogramProgram(ext);
        glGenTextures(1, &obj.texture);
        glBindTexture(GL_TEXTURE_2D, obj.texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, tileW, tileH, 0, GL_RED, GL_FLOAT, nullptr);
        ext->glGenFramebuffers(1, &obj.fbo);
        ext->glBindFramebuffer(GL_FRAMEBUFFER, obj.fbo);
        ext->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, obj.texture, 0);
        const GLenum status = ext->glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("TextureHistogram: R32F framebuffer incomplete (status " +
                                     std::to_string(status) + ")");
        ext->glGenVertexArrays(1, &obj.vao);
        ext->glBindVertexArray(obj.vao);
        ext->glGenBuffers(1, &obj.vbo);
        ext->glBindBuffer(GL_ARRAY_BUFFER, obj.vbo);
        ext->glEnableVertexAttribArray(0);
        ext->glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        ext->glEnableVertexAttribArray(1);
        ext->glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 3 * sizeof(float),
                                   reinterpret_cast<const void*>(2 * sizeof(float)));
        ext->glUseProgram(obj.program);
        const GLint sizeLocation = ext->glGetUniformLocation(obj.program, "loa_viewportSize");
        for (int k = 0; k < SavedGLState::kCaps; ++k)
            glDisable(SavedGLState::caps()[k]);
        glEnable(GL_BLEND);
        ext->glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
        ext->glBlendEquation(GL_FUNC_ADD);
        glClearColor(0, 0, 0, 0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);

        // Exact path: one viewport of power-of-two size covering the whole virtual target,
        // offset by -tile origin, so no vertex leaves the clip volume (no clipping) and the
        // viewport transform of the 1/256-snapped positions is exact in float. Fallback when
        // that viewport exceeds GL_MAX_VIEWPORT_DIMS or GL_VIEWPORT_BOUNDS_RANGE: a viewport per
        // tile, positions relative to the tile (GL clips at the tile edges).
        auto pow2 = [](int n)
        {
            int p = 1;
            while (p < n)
                p *= 2;
            return p;
        };
        const int vpW = pow2(s.targetW), vpH = pow2(s.targetH);
        GLint maxViewport[2] = {0, 0};
        GLfloat bounds[2] = {0, 0};
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
        glGetFloatv(GL_VIEWPORT_BOUNDS_RANGE, bounds);
        if (glGetError() != GL_NO_ERROR) bounds[0] = 0; // GL < 4.1: assume no negative origin
        const bool exact = vpW <= maxViewport[0] && vpH <= maxViewport[1] && vpW <= (1 << 15) &&
                           vpH <= (1 << 15) && -double(s.targetW - 1) >= bounds[0] &&
                           -double(s.targetH - 1) >= bounds[0];
        if (exact)
            ext->glUniform2f(sizeLocation, float(vpW), float(vpH));
        else
            ext->glUniform2f(sizeLocation, float(tileW), float(tileH));

        std::vector<float> vertices;
        vertices.reserve(s.triangles.size() * 9);
        std::vector<float> pixels(std::size_t(tileW) * std::size_t(tileH));
        const int gx = s.range.u0 * width, gy = s.range.v0 * height;
        bool uploaded = false;
        for (int ty = 0; ty < s.targetH; ty += tileH)
            for (int tx = 0; tx < s.targetW; tx += tileW)
            {
                // Positions in texels relative to the origin (0 or the tile's): multiples of
                // 1/256, exact in float below 2^15 texels.
                const std::int64_t ox = exact ? 0 : std::int64_t(tx) * kSubPixel;
                const std::int64_t oy = exact ? 0 : std::int64_t(ty) * kSubPixel;
                if (!exact || !uploaded)
                {
                    vertices.clear();
                    for (const SnappedTriangle& t : s.triangles)
                    {
                        if (!exact)
                        {
                            const std::int64_t minX = std::min({t.x[0], t.x[1], t.x[2]}) - ox;
                            const std::int64_t maxX = std::max({t.x[0], t.x[1], t.x[2]}) - ox;
                            const std::int64_t minY = std::min({t.y[0], t.y[1], t.y[2]}) - oy;
                            const std::int64_t maxY = std::max({t.y[0], t.y[1], t.y[2]}) - oy;
                            if (maxX < 0 || maxY < 0 || minX > std::int64_t(tileW) * kSubPixel ||
                                minY > std::int64_t(tileH) * kSubPixel)
                                continue;
                        }
                        for (int c = 0; c < 3; ++c)
                        {
                            vertices.push_back(float(double(t.x[c] - ox) / kSubPixel));
                            vertices.push_back(float(double(t.y[c] - oy) / kSubPixel));
                            vertices.push_back(float(t.weight));
                        }
                    }
                    if (!vertices.empty())
                        ext->glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)),
                                          vertices.data(), GL_STREAM_DRAW);
                    uploaded = true;
                }
                if (vertices.empty()) continue;
                if (exact)
                    glViewport(-tx, -ty, vpW, vpH);
                else
                    glViewport(0, 0, tileW, tileH);
                glClear(GL_COLOR_BUFFER_BIT);
                glDrawArrays(GL_TRIANGLES, 0, GLsizei(vertices.size() / 3));
                glReadPixels(0, 0, tileW, tileH, GL_RED, GL_FLOAT, pixels.data());
                const GLenum err = glGetError();
                if (err != GL_NO_ERROR)
                    throw std::runtime_error("TextureHistogram: GL error " + std::to_string(err) +
                                             " while drawing the histogram");
                const int w = std::min(tileW, s.targetW - tx), h = std::min(tileH, s.targetH - ty);
                for (int j = 0; j < h; ++j)
                {
                    const int y = wrapIndex(gy + ty + j, height, border.t);
                    for (int i = 0; i < w; ++i)
                    {
                        const float p = pixels[std::size_t(j) * std::size_t(tileW) + std::size_t(i)];
                        if (p == 0.0f) continue;
                        const int x = wrapIndex(gx + tx + i, width, border.s);
                        folded[std::size_t(y) * std::size_t(width) + std::size_t(x)] += p;
                    }
                }
            }
    }
    return std::vector<float>(folded.begin(), folded.end());
}

std::vector<TextureHistogram::ColorEntry> TextureHistogram::colorTable(const osg::Image& source,
                                                                       const std::vector<double>& weights)
{
    // Any format FilterImage reads (luminance, LA, BGR, 16-bit, float, S3TC) as 8-bit RGB(A);
    // its error names the format of anything else.
    osg::ref_ptr<const osg::Image> converted;
    try
    {
        converted = FilterImage::toRGB8(source);
    }
    catch (const std::invalid_argument& e)
    {
        throw std::invalid_argument(std::string("TextureHistogram: ") + e.what());
    }
    const osg::Image& texture = *converted;
    const std::size_t n = std::size_t(texture.s()) * std::size_t(texture.t());
    if (weights.size() != n)
        throw std::invalid_argument("TextureHistogram: weights hold " + std::to_string(weights.size()) +
                                    " values for a texture of " + std::to_string(n) + " texels");
    std::map<unsigned, double> sums;
    for (int y = 0; y < texture.t(); ++y)
        for (int x = 0; x < texture.s(); ++x)
        {
            const double w = weights[std::size_t(y) * std::size_t(texture.s()) + std::size_t(x)];
            if (!std::isfinite(w) || w < 0)
                throw std::invalid_argument("TextureHistogram: weight of texel (" + std::to_string(x) + ", " +
                                            std::to_string(y) + ") is negative or not finite");
            if (w == 0) continue;
            const unsigned char* p = texture.data(x, y);
            const unsigned r = p[0], gg = p[1], b = p[2];
            sums[(r << 16) | (gg << 8) | b] += w;
        }
    std::vector<ColorEntry> out;
    out.reserve(sums.size());
    for (const auto& kv : sums)
        out.push_back({(unsigned char)(kv.first >> 16), (unsigned char)((kv.first >> 8) & 255),
                       (unsigned char)(kv.first & 255), kv.second});
    std::stable_sort(out.begin(), out.end(),
                     [](const ColorEntry& a, const ColorEntry& b) { return a.weight > b.weight; });
    return out;
}

namespace
{

/** Collects (geometry, effective unit-0 Texture2D) pairs along the traversal. */
class TexturedGeometryCollector : public osg::NodeVisitor
{
public:
    struct Entry
    {
        const osg::Geometry* geometry;
        const osg::Texture2D* texture;
    };
    std::vector<Entry> entries;

    TexturedGeometryCollector() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Node& node) override
    {
        const std::size_t depth = push(node.getStateSet());
        traverse(node);
        _stack.resize(depth);
    }
    void apply(osg::Geometry& geometry) override
    {
        const std::size_t depth = push(geometry.getStateSet());
        const Current& c = _stack.empty() ? Current() : _stack.back();
        const osg::Texture2D* t = dynamic_cast<const osg::Texture2D*>(c.texture);
        if (t && t->getImage(0) && geometry.getTexCoordArray(0) &&
            geometry.getTexCoordArray(0)->getNumElements())
            entries.push_back({&geometry, t});
        _stack.resize(depth);
    }

private:
    struct Current
    {
        const osg::StateAttribute* texture = nullptr;
        unsigned value = 0;
    };
    std::vector<Current> _stack;

    std::size_t push(const osg::StateSet* ss)
    {
        const std::size_t depth = _stack.size();
        Current c = _stack.empty() ? Current() : _stack.back();
        if (ss)
        {
            const osg::StateSet::RefAttributePair* p =
                ss->getTextureAttributePair(0, osg::StateAttribute::TEXTURE);
            if (p && p->first.valid())
            {
                const bool parentOverrides = c.texture && (c.value & osg::StateAttribute::OVERRIDE);
                if (!parentOverrides || (p->second & osg::StateAttribute::PROTECTED))
                    c = Current{p->first.get(), p->second};
            }
        }
        _stack.push_back(c);
        return depth;
    }
};

} // namespace

std::map<const osg::Image*, std::vector<double>> TextureHistogram::sceneWeights(osg::Node& scene,
                                                                                osg::State* gpuState)
{
    TexturedGeometryCollector collector;
    scene.accept(collector);
    std::map<const osg::Image*, std::vector<double>> out;
    for (const auto& e : collector.entries)
    {
        const osg::Image* image = e.texture->getImage(0);
        const int w = image->s(), h = image->t();
        if (w < 1 || h < 1 || !image->data()) continue; // unreadable, or emptied by ModelValidation
        const ImageBorder border = ImageBorder::of(*e.texture);
        std::vector<double>& acc = out[image];
        if (acc.empty()) acc.assign(std::size_t(w) * std::size_t(h), 0.0);
        if (gpuState)
        {
            const std::vector<float> wts = texelWeightsGpu(*gpuState, *e.geometry, w, h, border, 0);
            for (std::size_t k = 0; k < acc.size(); ++k)
                acc[k] += wts[k];
        }
        else
        {
            const std::vector<double> wts = texelWeights(*e.geometry, w, h, border, 0);
            for (std::size_t k = 0; k < acc.size(); ++k)
                acc[k] += wts[k];
        }
    }
    return out;
}

} // namespace osgLoA
