/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/GpuFilterEngine>

#include "../render/GLProgramBuild.h"
#include <osgLoA/render/ShaderLibrary>

#include <osg/GLExtensions>

#include <algorithm>
#include <cstring>
#include <set>

#ifndef GL_COMPUTE_SHADER
#define GL_COMPUTE_SHADER 0x91B9
#endif
#ifndef GL_SHADER_STORAGE_BUFFER
#define GL_SHADER_STORAGE_BUFFER 0x90D2
#endif
#ifndef GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
#define GL_SHADER_IMAGE_ACCESS_BARRIER_BIT 0x00000020
#endif
#ifndef GL_TEXTURE_FETCH_BARRIER_BIT
#define GL_TEXTURE_FETCH_BARRIER_BIT 0x00000008
#endif
#ifndef GL_SHADER_STORAGE_BARRIER_BIT
#define GL_SHADER_STORAGE_BARRIER_BIT 0x00002000
#endif
#ifndef GL_READ_ONLY
#define GL_READ_ONLY 0x88B8
#endif
#ifndef GL_READ_WRITE
#define GL_READ_WRITE 0x88BA
#endif
#ifndef GL_CURRENT_PROGRAM
#define GL_CURRENT_PROGRAM 0x8B8D
#endif
#ifndef GL_DYNAMIC_DRAW
#define GL_DYNAMIC_DRAW 0x88E8
#endif

namespace osgLoA
{

bool GpuFilterEngine::TileCache::isDone(std::size_t pass, std::size_t region, int tileIndex) const
{
    auto it = _done.find({pass, region});
    return it != _done.end() && std::size_t(tileIndex) < it->second.size() &&
           it->second[std::size_t(tileIndex)];
}

void GpuFilterEngine::TileCache::markDone(std::size_t pass, std::size_t region, int tileIndex)
{
    std::vector<bool>& v = _done[{pass, region}];
    if (v.size() <= std::size_t(tileIndex)) v.resize(std::size_t(tileIndex) + 1, false);
    v[std::size_t(tileIndex)] = true;
}

std::size_t GpuFilterEngine::TileCache::doneCount(std::size_t pass, std::size_t region) const
{
    auto it = _done.find({pass, region});
    return it == _done.end() ? 0 : std::size_t(std::count(it->second.begin(), it->second.end(), true));
}

namespace
{
using GetTextureSubImage = void(GL_APIENTRY*)(GLuint, GLint, GLint, GLint, GLint, GLsizei, GLsizei, GLsizei,
                                              GLenum, GLenum, GLsizei, void*);

/** Restores the texture binding and program OSG believes are current, and the unpack/pack
 *  row length, when a public engine call returns. */
class SavedGLState
{
public:
    explicit SavedGLState(osg::GLExtensions* ext) : _ext(ext)
    {
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &_texture);
        glGetIntegerv(GL_CURRENT_PROGRAM, &_program);
        glGetIntegerv(GL_UNPACK_ROW_LENGTH, &_unpackRow);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &_packRow);
        glGetIntegerv(GL_UNPACK_ALIGNMENT, &_unpackAlign);
        glGetIntegerv(GL_PACK_ALIGNMENT, &_packAlign);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
    }
    ~SavedGLState()
    {
        glBindTexture(GL_TEXTURE_2D, GLuint(_texture));
        _ext->glUseProgram(GLuint(_program));
        _ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, _unpackRow);
        glPixelStorei(GL_PACK_ROW_LENGTH, _packRow);
        glPixelStorei(GL_UNPACK_ALIGNMENT, _unpackAlign);
        glPixelStorei(GL_PACK_ALIGNMENT, _packAlign);
    }

private:
    osg::GLExtensions* _ext;
    GLint _texture = 0, _program = 0, _unpackRow = 0, _packRow = 0, _unpackAlign = 4, _packAlign = 4;
};

struct Atlas
{
    GLuint texture = 0;
    int width = 0, height = 0;
    bool owned = true;
};
} // namespace

struct GpuFilterEngine::Impl
{
    osg::State* state = nullptr;
    osg::GLExtensions* ext = nullptr;
    GetTextureSubImage getTextureSubImage = nullptr;
    unsigned nextAtlas = 1;
    std::map<unsigned, Atlas> atlases;
    std::map<std::string, GLuint> programs;
    /** Scratch atlases for intermediate pass outputs, per (source atlas, pass index). */
    std::map<std::pair<unsigned, std::size_t>, unsigned> scratch;
    GLuint regionBuffer = 0, workBuffer = 0;
    std::size_t workCapacity = 0;

    Atlas& atlas(unsigned id)
    {
        auto it = atlases.find(id);
        if (it == atlases.end()) throw GpuFilterError("GpuFilterEngine: no atlas " + std::to_string(id));
        return it->second;
    }

    GLuint compile(const std::string& name, const std::string& source)
    {
        std::string log;
        const GLuint sh = detail::compileShaderStage(ext, GL_COMPUTE_SHADER, source, log);
        if (!sh)
            throw GpuFilterError("GpuFilterEngine: shader '" + name +
                                 "' (compute stage) failed to compile: " + log);
        return sh;
    }

    GLuint program(const GpuFilterPass& pass, bool interior)
    {
        std::string key = pass.shader + (interior ? "|interior" : "");
        for (const auto& kv : pass.defines)
            key += "|" + kv.first + "=" + kv.second;
        if (pass.dispatch != GpuFilterPass::TEXELS) key += "|lines=" + std::to_string(int(pass.dispatch));
        auto it = programs.find(key);
        if (it != programs.end()) return it->second;
        std::vector<std::pair<std::string, std::string>> defines = pass.defines;
        if (interior) defines.push_back({"LOA_INTERIOR", "1"});
        if (pass.dispatch != GpuFilterPass::TEXELS)
            defines.push_back({"LOA_LINES", pass.dispatch == GpuFilterPass::ROWS ? "1" : "2"});
        const std::string common = ShaderLibrary::getSource("loa_filter_common.comp.glsl").text;
        const std::string own = ShaderLibrary::getSource(pass.shader).text;
        GLuint a = compile("loa_filter_common.comp.glsl",
                           ShaderLibrary::withDefines(common, defines, "loa_filter_common.comp.glsl"));
        GLuint b = 0;
        try
        {
            b = compile(pass.shader, ShaderLibrary::withDefines(own, defines, pass.shader));
        }
        catch (...)
        {
            ext->glDeleteShader(a);
            throw;
        }
        std::string log;
        const GLuint p = detail::linkProgram(ext, {a, b}, log);
        if (!p)
            throw GpuFilterError("GpuFilterEngine: program of pass '" + pass.shader +
                                 "' failed to link: " + log);
        programs[key] = p;
        return p;
    }

    void bindBuffer(GLuint& buffer, GLuint index, const void* data, std::size_t bytes, std::size_t* capacity)
    {
        if (!buffer) ext->glGenBuffers(1, &buffer);
        ext->glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
        if (!capacity || bytes > *capacity)
        {
            const std::size_t size = std::max<std::size_t>(bytes, 16);
            ext->glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(size), data, GL_DYNAMIC_DRAW);
            if (capacity) *capacity = size;
        }
        else if (bytes)
            ext->glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes), data);
        ext->glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, buffer);
    }

    void setUniforms(GLuint prog, const GpuFilterPass& pass)
    {
        for (const GpuUniform& u : pass.uniforms)
        {
            const GLint loc = ext->glGetUniformLocation(prog, u.name.c_str());
            if (loc < 0) continue; // optimized away
            const GLsizei n = GLsizei(u.values.size());
            switch (u.type)
            {
            case GpuUniform::FLOAT:
            case GpuUniform::FLOAT_ARRAY:
                ext->glUniform1fv(loc, n, u.values.data());
                break;
            case GpuUniform::VEC2:
                ext->glUniform2fv(loc, n / 2, u.values.data());
                break;
            case GpuUniform::VEC3:
                ext->glUniform3fv(loc, n / 3, u.values.data());
                break;
            case GpuUniform::VEC4:
                ext->glUniform4fv(loc, n / 4, u.values.data());
                break;
            case GpuUniform::INT:
                ext->glUniform1i(loc, GLint(u.values.empty() ? 0 : u.values[0]));
                break;
            }
        }
    }
};

GpuFilterEngine::GpuFilterEngine(osg::State& state) : _impl(new Impl)
{
    _impl->state = &state;
    if (!state.get<osg::GLExtensions>()) state.initializeExtensionProcs();
    _impl->ext = state.get<osg::GLExtensions>();
    const unsigned id = state.getContextID();
    const char* needs[] = {"GL_ARB_compute_shader", "GL_ARB_shader_image_load_store",
                           "GL_ARB_shader_storage_buffer_object", "GL_ARB_texture_storage"};
    const float versions[] = {4.3f, 4.2f, 4.3f, 4.2f};
    for (int i = 0; i < 4; ++i)
        if (!osg::isGLExtensionOrVersionSupported(id, needs[i], versions[i]))
            throw GpuFilterError(
                std::string("GpuFilterEngine: the OpenGL context lacks ") + needs[i] + " (OpenGL " +
                std::to_string(versions[i]).substr(0, 3) +
                "); GPU filtering is not available, use the CPU filters (ImageFilter::apply)");
    if (osg::isGLExtensionOrVersionSupported(id, "GL_ARB_get_texture_sub_image", 4.5f))
        _impl->getTextureSubImage =
            reinterpret_cast<GetTextureSubImage>(osg::getGLExtensionFuncPtr("glGetTextureSubImage"));
}

GpuFilterEngine::~GpuFilterEngine() = default;

unsigned GpuFilterEngine::createAtlas(int width, int height)
{
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        throw GpuFilterError("GpuFilterEngine: atlas size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is outside 1.." + std::to_string(maxSize));
    SavedGLState saved(_impl->ext);
    Atlas a;
    a.width = width;
    a.height = height;
    glGenTextures(1, &a.texture);
    glBindTexture(GL_TEXTURE_2D, a.texture);
    _impl->ext->glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F_ARB, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const GLenum err = glGetError();
    if (err != GL_NO_ERROR)
    {
        glDeleteTextures(1, &a.texture);
        throw GpuFilterError("GpuFilterEngine: could not allocate a " + std::to_string(width) + "x" +
                             std::to_string(height) + " RGBA32F atlas (GL error " + std::to_string(err) +
                             ")");
    }
    const unsigned id = _impl->nextAtlas++;
    _impl->atlases[id] = a;
    return id;
}

unsigned GpuFilterEngine::adoptAtlas(unsigned textureName, int width, int height)
{
    if (textureName == 0 || width <= 0 || height <= 0)
        throw GpuFilterError("GpuFilterEngine: cannot adopt texture " + std::to_string(textureName) +
                             " of size " + std::to_string(width) + "x" + std::to_string(height));
    Atlas a;
    a.texture = textureName;
    a.width = width;
    a.height = height;
    a.owned = false;
    const unsigned id = _impl->nextAtlas++;
    _impl->atlases[id] = a;
    return id;
}

void GpuFilterEngine::destroyAtlas(unsigned atlas)
{
    auto it = _impl->atlases.find(atlas);
    if (it == _impl->atlases.end()) return;
    if (it->second.owned) glDeleteTextures(1, &it->second.texture);
    _impl->atlases.erase(it);
    for (auto s = _impl->scratch.begin(); s != _impl->scratch.end();)
    {
        if (s->first.first == atlas)
        {
            auto a = _impl->atlases.find(s->second);
            if (a != _impl->atlases.end())
            {
                glDeleteTextures(1, &a->second.texture);
                _impl->atlases.erase(a);
            }
            s = _impl->scratch.erase(s);
        }
        else
            ++s;
    }
}

int GpuFilterEngine::atlasWidth(unsigned atlas) const
{
    return _impl->atlas(atlas).width;
}
int GpuFilterEngine::atlasHeight(unsigned atlas) const
{
    return _impl->atlas(atlas).height;
}
unsigned GpuFilterEngine::textureName(unsigned atlas) const
{
    return _impl->atlas(atlas).texture;
}

namespace
{
void checkRegion(const GpuFilterEngine::Region& r, int w, int h)
{
    if (r.width <= 0 || r.height <= 0 || r.x < 0 || r.y < 0 || r.x + r.width > w || r.y + r.height > h)
        throw GpuFilterError("GpuFilterEngine: region " + std::to_string(r.width) + "x" +
                             std::to_string(r.height) + " at (" + std::to_string(r.x) + ", " +
                             std::to_string(r.y) + ") is not inside the " + std::to_string(w) + "x" +
                             std::to_string(h) + " atlas");
}
} // namespace

void GpuFilterEngine::upload(unsigned atlas, const Region& region, const FilterImage& image)
{
    Atlas& a = _impl->atlas(atlas);
    checkRegion(region, a.width, a.height);
    if (image.width() != region.width || image.height() != region.height)
        throw GpuFilterError("GpuFilterEngine: image size does not match the region");
    SavedGLState saved(_impl->ext);
    glBindTexture(GL_TEXTURE_2D, a.texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, region.x, region.y, region.width, region.height, GL_RGBA, GL_FLOAT,
                    image.data().data());
}

FilterImage GpuFilterEngine::download(unsigned atlas, const Region& region)
{
    Atlas& a = _impl->atlas(atlas);
    checkRegion(region, a.width, a.height);
    SavedGLState saved(_impl->ext);
    FilterImage out(region.width, region.height);
    if (_impl->getTextureSubImage)
    {
        _impl->getTextureSubImage(a.texture, 0, region.x, region.y, 0, region.width, region.height, 1,
                                  GL_RGBA, GL_FLOAT, GLsizei(out.data().size() * sizeof(float)),
                                  out.data().data());
        return out;
    }
    std::vector<float> all(std::size_t(a.width) * std::size_t(a.height) * 4);
    glBindTexture(GL_TEXTURE_2D, a.texture);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, all.data());
    for (int y = 0; y < region.height; ++y)
        std::memcpy(out.texel(0, y),
                    &all[(std::size_t(region.y + y) * std::size_t(a.width) + std::size_t(region.x)) * 4],
                    std::size_t(region.width) * 4 * sizeof(float));
    return out;
}

namespace
{
/** Marks, in a region's tile mask, the tiles holding texels [x0, x1] x [y0, y1] wrapped into the
 *  region by its modes (clamp and mirror fold out-of-range texels back inside). */
void markTexelRect(std::vector<unsigned char>& mask, const GpuFilterEngine::Region& r, int x0, int x1, int y0,
                   int y1)
{
    const int tx = r.tilesX();
    std::vector<unsigned char> cols(std::size_t(tx), 0), rows(std::size_t(r.tilesY()), 0);
    const int T = GpuFilterEngine::TILE;
    if (x1 - x0 + 1 >= r.width)
        std::fill(cols.begin(), cols.end(), 1);
    else
        for (int x = x0; x <= x1; ++x)
            cols[std::size_t(wrapIndex(x, r.width, r.border.s) / T)] = 1;
    if (y1 - y0 + 1 >= r.height)
        std::fill(rows.begin(), rows.end(), 1);
    else
        for (int y = y0; y <= y1; ++y)
            rows[std::size_t(wrapIndex(y, r.height, r.border.t) / T)] = 1;
    for (int j = 0; j < r.tilesY(); ++j)
        if (rows[std::size_t(j)])
            for (int i = 0; i < tx; ++i)
                if (cols[std::size_t(i)]) mask[std::size_t(j * tx + i)] = 1;
}
} // namespace

GpuFilterEngine::RunStats GpuFilterEngine::run(const ImageFilter& filter, unsigned source,
                                               unsigned destination, const std::vector<Region>& regions,
                                               const std::vector<Tile>* tiles, TileCache* cache)
{
    try
    {
        filter.checkParameters();
    }
    catch (const std::invalid_argument& e)
    {
        throw GpuFilterError(std::string("GpuFilterEngine: ") + e.what());
    }
    const std::vector<GpuFilterPass> passes = filter.gpuPasses();
    if (passes.empty())
        throw GpuFilterError("GpuFilterEngine: filter '" + filter.filterName() +
                             "' has no GPU implementation (it runs on the CPU only)");
    if (source == destination)
        throw GpuFilterError("GpuFilterEngine: source and destination atlas must differ");
    Atlas& src = _impl->atlas(source);
    Atlas& dst = _impl->atlas(destination);
    if (src.width != dst.width || src.height != dst.height)
        throw GpuFilterError("GpuFilterEngine: source and destination atlases differ in size");
    for (const Region& r : regions)
        checkRegion(r, src.width, src.height);
    for (std::size_t k = 0; k < passes.size(); ++k)
    {
        if (passes[k].inputs.empty() || passes[k].inputs.size() > 4)
            throw GpuFilterError("GpuFilterEngine: pass " + std::to_string(k) + " of '" +
                                 filter.filterName() + "' has " + std::to_string(passes[k].inputs.size()) +
                                 " inputs (1..4)");
        for (int in : passes[k].inputs)
            if (in >= int(k) || in < -1)
                throw GpuFilterError("GpuFilterEngine: pass " + std::to_string(k) + " of '" +
                                     filter.filterName() + "' reads pass " + std::to_string(in));
    }

    // Output tiles per pass, as masks per region.
    const std::size_t P = passes.size();
    std::vector<std::vector<std::vector<unsigned char>>> masks(
        P, std::vector<std::vector<unsigned char>>(regions.size()));
    for (std::size_t k = 0; k < P; ++k)
        for (std::size_t r = 0; r < regions.size(); ++r)
            masks[k][r].assign(std::size_t(regions[r].tilesX() * regions[r].tilesY()), 0);
    const bool global = filter.dependencyRadius() < 0;
    if (!tiles)
    {
        for (std::size_t k = 0; k < P; ++k)
            for (auto& m : masks[k])
                std::fill(m.begin(), m.end(), 1);
    }
    else
    {
        // What each pass must provide: need[k] texels around the final output tiles.
        std::vector<int> need(P, 0);
        for (std::size_t k = P; k-- > 0;)
            for (int in : passes[k].inputs)
                if (in >= 0)
                    need[std::size_t(in)] =
                        std::max(need[std::size_t(in)], need[k] + std::max(0, passes[k].radius));
        for (const Tile& t : *tiles)
        {
            if (t.region >= regions.size()) throw GpuFilterError("GpuFilterEngine: tile of unknown region");
            const Region& r = regions[t.region];
            if (int(t.x) >= r.tilesX() || int(t.y) >= r.tilesY())
                throw GpuFilterError("GpuFilterEngine: tile outside its region");
            for (std::size_t k = 0; k < P; ++k)
            {
                std::vector<unsigned char>& m = masks[k][t.region];
                if (global)
                    std::fill(m.begin(), m.end(), 1);
                else
                {
                    const int x0 = int(t.x) * TILE, y0 = int(t.y) * TILE;
                    const int x1 = std::min(x0 + TILE, r.width) - 1, y1 = std::min(y0 + TILE, r.height) - 1;
                    markTexelRect(m, r, x0 - need[k], x1 + need[k], y0 - need[k], y1 + need[k]);
                }
            }
        }
    }

    SavedGLState saved(_impl->ext);
    osg::GLExtensions* ext = _impl->ext;
    // Region table.
    std::vector<GLint> table;
    table.reserve(regions.size() * 8);
    for (const Region& r : regions)
    {
        table.insert(table.end(), {r.x, r.y, r.width, r.height, GLint(r.border.s), GLint(r.border.t), 0, 0});
    }
    _impl->bindBuffer(_impl->regionBuffer, 0, table.data(), table.size() * sizeof(GLint), nullptr);

    // Scratch atlases for intermediate outputs. With a cache, each pass keeps its own (its
    // filtered tiles must survive until later runs). Without one, an atlas is reused once no
    // later pass reads what it holds (a pass's output never shares an atlas with its inputs):
    // a filter of 41 passes (shock, 5 iterations) needs a handful of atlases, not 40.
    std::vector<std::size_t> slots(P, 0);
    if (cache)
        for (std::size_t k = 0; k < P; ++k)
            slots[k] = k;
    else
    {
        std::vector<std::size_t> lastRead(P, 0);
        for (std::size_t j = 0; j < P; ++j)
            for (int in : passes[j].inputs)
                if (in >= 0) lastRead[std::size_t(in)] = std::max(lastRead[std::size_t(in)], j);
        std::vector<std::size_t> slotFreeAfter; // per slot: the last pass that reads it
        for (std::size_t k = 0; k + 1 < P; ++k)
        {
            std::size_t slot = slotFreeAfter.size();
            for (std::size_t s = 0; s < slotFreeAfter.size(); ++s)
                if (slotFreeAfter[s] < k)
                {
                    slot = s;
                    break;
                }
            if (slot == slotFreeAfter.size()) slotFreeAfter.push_back(0);
            slotFreeAfter[slot] = std::max(lastRead[k], k);
            slots[k] = slot;
        }
    }
    std::vector<unsigned> outputs(P);
    for (std::size_t k = 0; k + 1 < P; ++k)
    {
        // Keys: (source, pass) for cached runs, (source, kSharedSlots + slot) for the others.
        const std::size_t kSharedSlots = 1u << 20;
        auto key = std::make_pair(source, cache ? slots[k] : kSharedSlots + slots[k]);
        auto it = _impl->scratch.find(key);
        if (it == _impl->scratch.end())
            it = _impl->scratch.emplace(key, createAtlas(src.width, src.height)).first;
        outputs[k] = it->second;
    }
    outputs[P - 1] = destination;

    RunStats stats;
    std::vector<GLuint> work, interiorWork;
    for (std::size_t k = 0; k < P; ++k)
    {
        const GpuFilterPass& pass = passes[k];
        work.clear();
        interiorWork.clear();
        // A tile whose reads (radius + 1 for bilinear samples) stay inside its region runs the
        // variant without wrap arithmetic.
        const int margin = pass.radius + 1;
        std::size_t texels = 0;
        for (std::size_t r = 0; r < regions.size(); ++r)
        {
            const Region& reg = regions[r];
            std::vector<unsigned char>& m = masks[k][r];
            if (cache)
                for (std::size_t i = 0; i < m.size(); ++i)
                    if (m[i] && cache->isDone(k, r, int(i)))
                    {
                        m[i] = 0;
                        if (k + 1 == P) ++stats.cachedTiles;
                    }
            if (pass.dispatch == GpuFilterPass::TEXELS)
            {
                for (int j = 0; j < reg.tilesY(); ++j)
                    for (int i = 0; i < reg.tilesX(); ++i)
                        if (m[std::size_t(j * reg.tilesX() + i)])
                        {
                            const bool inside =
                                pass.radius >= 0 && i * TILE - margin >= 0 && j * TILE - margin >= 0 &&
                                (i + 1) * TILE + margin <= reg.width && (j + 1) * TILE + margin <= reg.height;
                            std::vector<GLuint>& list = inside ? interiorWork : work;
                            list.insert(list.end(), {GLuint(r), GLuint(i), GLuint(j), 0u});
                            texels += std::size_t(std::min(TILE, reg.width - i * TILE) *
                                                  std::min(TILE, reg.height - j * TILE));
                        }
            }
            else if (std::find(m.begin(), m.end(), 1) != m.end())
            {
                const int lines = pass.dispatch == GpuFilterPass::ROWS ? reg.height : reg.width;
                for (int b = 0; b * 64 < lines; ++b)
                    work.insert(work.end(), {GLuint(r), GLuint(b), 0u, 0u});
                texels += std::size_t(reg.width) * std::size_t(reg.height);
            }
        }
        const std::size_t items = (work.size() + interiorWork.size()) / 4;
        if (items == 0) continue;
        for (GLuint unit = 0; unit < 4; ++unit)
        {
            const int in = unit < pass.inputs.size() ? pass.inputs[unit] : pass.inputs[0];
            const unsigned a = in < 0 ? source : outputs[std::size_t(in)];
            ext->glBindImageTexture(unit, _impl->atlas(a).texture, 0, GL_FALSE, 0, GL_READ_ONLY,
                                    GL_RGBA32F_ARB);
        }
        ext->glBindImageTexture(4, _impl->atlas(outputs[k]).texture, 0, GL_FALSE, 0, GL_READ_WRITE,
                                GL_RGBA32F_ARB);
        for (int variant = 0; variant < 2; ++variant)
        {
            const std::vector<GLuint>& list = variant == 0 ? interiorWork : work;
            const std::size_t n = list.size() / 4;
            if (n == 0) continue;
            const GLuint prog = _impl->program(pass, variant == 0);
            ext->glUseProgram(prog);
            _impl->setUniforms(prog, pass);
            ext->glUniform1ui(ext->glGetUniformLocation(prog, "loa_workCount"), GLuint(n));
            ext->glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, _impl->regionBuffer);
            _impl->bindBuffer(_impl->workBuffer, 1, list.data(), list.size() * sizeof(GLuint),
                              &_impl->workCapacity);
            const GLuint gx = GLuint(std::min<std::size_t>(n, 65535));
            const GLuint gy = GLuint((n + gx - 1) / gx);
            ext->glDispatchCompute(gx, gy, 1);
            ext->glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                                 GL_SHADER_STORAGE_BARRIER_BIT);
            ++stats.passes;
        }
        stats.tiles += items;
        stats.texels += texels;
        if (k + 1 == P) stats.outputTexels = texels;
        if (cache)
            for (std::size_t r = 0; r < regions.size(); ++r)
                for (std::size_t i = 0; i < masks[k][r].size(); ++i)
                    if (masks[k][r][i]) cache->markDone(k, r, int(i));
    }
    return stats;
}

FilterImage GpuFilterEngine::filter(const ImageFilter& f, const FilterImage& image, const ImageBorder& border)
{
    if (image.empty()) throw GpuFilterError("GpuFilterEngine: empty image");
    const unsigned src = createAtlas(image.width(), image.height());
    unsigned dst = 0;
    try
    {
        dst = createAtlas(image.width(), image.height());
        Region r;
        r.width = image.width();
        r.height = image.height();
        r.border = border;
        upload(src, r, image);
        run(f, src, dst, {r});
        FilterImage out = download(dst, r);
        destroyAtlas(src);
        destroyAtlas(dst);
        return out;
    }
    catch (...)
    {
        destroyAtlas(src);
        if (dst) destroyAtlas(dst);
        throw;
    }
}

void GpuFilterEngine::releaseGLObjects()
{
    for (auto& a : _impl->atlases)
        if (a.second.owned) glDeleteTextures(1, &a.second.texture);
    _impl->atlases.clear();
    _impl->scratch.clear();
    for (auto& p : _impl->programs)
        _impl->ext->glDeleteProgram(p.second);
    _impl->programs.clear();
    if (_impl->regionBuffer) _impl->ext->glDeleteBuffers(1, &_impl->regionBuffer);
    if (_impl->workBuffer) _impl->ext->glDeleteBuffers(1, &_impl->workBuffer);
    _impl->regionBuffer = _impl->workBuffer = 0;
    _impl->workCapacity = 0;
}

} // namespace osgLoA
