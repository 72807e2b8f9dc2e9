// Included (#pragma include "loa_deferred_atlas.glsl") by osgLoA::DeferredTexturing's prefetch and
// shading stages: the layout of its page and atlas-region buffers (osgLoA::DeferredTexturing
// fills them; each stage binds them at its own binding points) and texture-coordinate wrapping.
struct LoaPage
{
    ivec4 size;       // level-0 width, height, levels, texture unit
    ivec4 addressing; // wrap s, wrap t (0 repeat, 1 clamp, 2 mirror), first region, -
};
struct LoaAtlasRegion
{
    ivec4 rect;       // x, y, width, height in the atlas
    ivec4 tiles;      // first tile, tiles x, tiles y, level
};

// osgLoA::wrapIndex without branches or integer division (both are slow on SIMD CPU
// rasterizers such as llvmpipe): repeat is i mod n, mirror folds i mod 2n, clamp clamps. The float
// quotients are exact enough for |i| < 2^24 (the one-off correction covers rounding).
int loa_deferredWrap(int i, int n, int mode)
{
    int rep = i - n * int(floor(float(i) / float(n)));
    rep += rep < 0 ? n : (rep >= n ? -n : 0);
    int period = 2 * n;
    int m = i - period * int(floor(float(i) / float(period)));
    m += m < 0 ? period : (m >= period ? -period : 0);
    int mir = m < n ? m : period - 1 - m;
    return mode == 0 ? rep : (mode == 2 ? mir : clamp(i, 0, n - 1));
}
