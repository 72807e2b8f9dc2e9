// loa-palette: the colour segmentation of paper 003 ("GPU texture level of abstraction in 3D
// scenes", Figure 1) for every texture of a model: the texture-object histogram, the hierarchy of
// colour merges, and per requested level the segmented texture and the selected colours.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"
#include "../common/ProgressBar.h"

#include <osgLoA/filtering/FilterImage>
#include <osgLoA/palette/PaletteHierarchy>
#include <osgLoA/palette/TextureHistogram>
#include <osgLoA/palette/WeightedColor>
#include <osgLoA/render/HeadlessContext>
#include <osgLoA/util/AtomicDirectory>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>
#include <osgLoA/util/JsonString>
#include <osgLoA/util/StateSetVisitor>

#include <osg/Texture2D>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/Registry>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>
#include <unordered_map>

namespace
{
const char* kDescription =
    R"(Loads MODEL (any file osgDB reads: .osgb, .osgt, .obj, .cityjson, demo.loacity ...; several are
one scene) and, for every distinct image of a 2D texture on unit 0, computes the colour segmentation of paper 003
(Suarez, Belhadj & Boyer, "GPU texture level of abstraction in 3D scenes"):
  1. the texel weights: how much each texel is used by the geometry that shows the texture
     (per mesh, the sum over covering triangles of P_o x P_t, object- and texture-space area
     shares; osgLoA::TextureHistogram), summed over every geometry using the image;
  2. the weighted colour table: the texels of non-zero weight unified by exact RGB colour;
  3. the hierarchy of colour merges in CIELab (agglomerative clustering down to one colour);
  4. for each requested level k: the segmented texture, every texel replaced by the colour of
     its cluster at level k (texel colour -> table entry -> cluster -> the cluster's weighted
     mean colour). Colours that occur only on texels of weight 0 (parts of the texture no
     triangle covers) are in no cluster: they get the nearest level-k colour in CIELab (CIE76).
     Alpha is kept as it is.

Writes into the --out-dir DIR, as a whole (a new run replaces an earlier one's folder in one step;
an interrupted run leaves it as it was; an existing folder must be empty or such an output):
  NAME-K.png            the segmented texture at level K, the texture's size (RGB, or RGBA
                        when the texture has alpha)
  NAME-histogram.png    the colour table as vertical bars sorted by weight (height
                        proportional to weight), and below it one strip per level: that
                        level's colours with widths proportional to their weights, the level
                        number at the left (paper 003 Figure 1, "selected colors")
  palettes.json         per texture: its size, table size, and per level the colours (hex),
                        their weights and shares, and the quantization error (weighted mean
                        CIE76 Delta E of the table colours to their cluster colour)
NAME is the image's file name without directory and extension (else the image's or the
texture's name), reduced to letters, digits, '.', '-', '_' and made unique with _2, _3 ...

)";
const char* kFooter =
    R"(Progress goes to stderr: a bar (textures done/total, ETA) when stderr is a terminal, one line
per texture otherwise. Luminance, luminance-alpha, 16-bit, float and S3TC (DXT) images are
converted to 8-bit RGB(A) first. Unusable images (missing or corrupt files, 0x0 images, other
compressed or packed formats, tables above --max-colors, no texel of non-zero weight) are
reported by name and skipped.

exit status: 0 every texture done, 1 the model could not be read, it has no textured geometry,
or DIR could not be created or written, 2 bad arguments, 3 no usable EGL/OpenGL context
(--gpu), 4 some textures were skipped (the others are done).
)";

constexpr int kSkipped = 4;
constexpr unsigned kMaxLevel = 65536;

struct Options
{
    std::vector<std::string> models;
    std::string model, out, readerOptions;
    std::vector<unsigned> levels{4, 8, 16, 32};
    osgLoA::PaletteHierarchy::Linkage linkage = osgLoA::PaletteHierarchy::WARD;
    unsigned maxColors = 65536;
    bool gpu = false, quiet = false;
};

std::vector<unsigned> parseLevels(const std::string& text)
{
    std::set<unsigned> levels;
    std::size_t start = 0;
    while (true)
    {
        const std::size_t comma = text.find(',', start);
        const std::string item =
            text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const bool digits =
            !item.empty() && item.size() <= 6 && item.find_first_not_of("0123456789") == std::string::npos;
        if (!digits)
            throw loa::UsageError("--levels '" + text + "': '" + item +
                                  "' is not a level (a list like 4,8,16,32)");
        const unsigned long k = std::stoul(item);
        if (k < 1 || k > kMaxLevel)
            throw loa::UsageError("--levels '" + text + "': " + item + " is outside 1.." +
                                  std::to_string(kMaxLevel));
        levels.insert(unsigned(k));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return std::vector<unsigned>(levels.begin(), levels.end());
}

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl("loa-palette", "loa-palette MODEL... --out-dir DIR [options]", kDescription);
    CLI::App& app = cl.app();
    loa::addModels(app, o.models, "the models whose textures to segment (one scene)");
    loa::addReaderOptions(app, o.readerOptions);
    loa::addOutDir(
        app, o.out,
        "the output directory (required; created if missing, replaced as a whole; an existing one must "
        "be empty or an earlier loa-palette output)");
    app.add_option_function<std::string>(
           "--levels", [&o](const std::string& t) { o.levels = parseLevels(t); },
           "comma-separated levels, each 1..65536 (default 4,8,16,32); a level above a texture's number of "
           "colours n gives its n colours (noted; the file keeps the requested number)")
        ->type_name("LIST");
    app.add_option_function<std::string>(
           "--linkage",
           [&o](const std::string& v)
           {
               if (v == "ward")
                   o.linkage = osgLoA::PaletteHierarchy::WARD;
               else if (v == "centroid")
                   o.linkage = osgLoA::PaletteHierarchy::CENTROID;
               else
                   throw loa::UsageError("--linkage '" + v + "' is not ward or centroid");
           },
           "ward (default: merges the pair that least increases the weighted within-cluster variance) or "
           "centroid (the closest pair, paper 003)")
        ->type_name("NAME");
    app.add_flag("--gpu", o.gpu, "compute the texel weights on the GPU (headless EGL), as the paper does");
    loa::addCount(app, "--max-colors", o.maxColors, 1, 1u << 24,
                  "skip textures whose colour table holds more than N colours (default 65536; the hierarchy "
                  "takes O(n^2) time)");
    app.add_flag("--quiet", o.quiet, "print only errors, notes and skipped textures");
    cl.footer(kFooter);
    cl.parse(argc, argv);
    o.model = loa::modelLabel(o.models);
    if (o.model.empty()) throw loa::UsageError("no MODEL given (see --help)");
    if (o.out.empty()) throw loa::UsageError("--out-dir DIR is required (the output directory)");
    return o;
}

/** One distinct image and the unit-0 textures that show it. */
struct Unit
{
    std::string label; ///< for messages: the file name, else a name, else "texture #i"
    std::string name;  ///< for output files: sanitized and unique
    osg::ref_ptr<osg::Image> image;
    std::vector<osg::ref_ptr<osg::Texture2D>> textures;
    std::string problem; ///< non-empty: skipped
};

/** The file-name stem of a texture: the image's file name without directory and extension,
 *  else the image's or texture's name, else "texture"; characters other than [A-Za-z0-9._-]
 *  become '_'. */
std::string stemOf(const osg::Texture2D& texture)
{
    const osg::Image* image = texture.getImage();
    std::string s;
    if (image && !image->getFileName().empty())
        s = osgDB::getStrippedName(image->getFileName());
    else if (image && !image->getName().empty())
        s = image->getName();
    else
        s = texture.getName();
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_')) c = '_';
    while (!s.empty() && s[0] == '.')
        s.erase(0, 1);
    return s.empty() ? std::string("texture") : s;
}

bool supportedFormat(const osg::Image& image)
{
    const GLenum f = image.getPixelFormat();
    return (f == GL_RGB || f == GL_RGBA || f == GL_BGR || f == GL_BGRA) &&
           image.getDataType() == GL_UNSIGNED_BYTE && image.r() == 1;
}

struct Rgb8
{
    unsigned char r = 0, g = 0, b = 0;
};

Rgb8 toBytes(const osg::Vec3f& rgb)
{
    auto byte = [](float v)
    { return (unsigned char)(std::lround(std::min(1.0f, std::max(0.0f, v)) * 255.0f)); };
    return Rgb8{byte(rgb.x()), byte(rgb.y()), byte(rgb.z())};
}

std::string hex(const Rgb8& c)
{
    char b[8];
    std::snprintf(b, sizeof b, "#%02x%02x%02x", c.r, c.g, c.b);
    return b;
}

/** The texture with every texel replaced by its level colour (see the help text). tableIndex
 *  maps 0xRRGGBB to the table entry, assign the entries to palette indices. */
osg::ref_ptr<osg::Image> segment(const osg::Image& src,
                                 const std::unordered_map<unsigned, unsigned>& tableIndex,
                                 const std::vector<unsigned>& assign, const std::vector<Rgb8>& colors,
                                 const std::vector<osg::Vec3d>& labs)
{
    const GLenum f = src.getPixelFormat();
    const bool bgr = f == GL_BGR || f == GL_BGRA, alpha = f == GL_RGBA || f == GL_BGRA;
    osg::ref_ptr<osg::Image> out = new osg::Image;
    out->allocateImage(src.s(), src.t(), 1, alpha ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE);
    out->setPacking(1);
    std::unordered_map<unsigned, unsigned> unused; // colours of weight-0 texels -> palette index
    for (int y = 0; y < src.t(); ++y)
        for (int x = 0; x < src.s(); ++x)
        {
            const unsigned char* p = src.data(x, y);
            const unsigned r = bgr ? p[2] : p[0], g = p[1], b = bgr ? p[0] : p[2];
            const unsigned key = (r << 16) | (g << 8) | b;
            unsigned j = 0;
            const auto it = tableIndex.find(key);
            if (it != tableIndex.end())
                j = assign[it->second];
            else
            {
                auto u = unused.find(key);
                if (u == unused.end())
                {
                    const osg::Vec3d lab(osgLoA::WeightedColor::toLab(osg::Vec3f(r, g, b) / 255.0f));
                    unsigned best = 0;
                    double bestDistance = 0;
                    for (unsigned c = 0; c < labs.size(); ++c)
                    {
                        const double d = osgLoA::WeightedColor::deltaE(lab, labs[c]);
                        if (c == 0 || d < bestDistance) best = c, bestDistance = d;
                    }
                    u = unused.emplace(key, best).first;
                }
                j = u->second;
            }
            unsigned char* q = out->data(x, y);
            q[0] = colors[j].r, q[1] = colors[j].g, q[2] = colors[j].b;
            if (alpha) q[3] = p[3];
        }
    return out;
}

/** Draws into an RGB8 image with y = 0 at the top. */
class Canvas
{
public:
    Canvas(int w, int h, Rgb8 background) : _image(new osg::Image)
    {
        _image->allocateImage(w, h, 1, GL_RGB, GL_UNSIGNED_BYTE);
        _image->setPacking(1);
        fill(0, 0, w, h, background);
    }
    void fill(int x0, int y0, int x1, int y1, Rgb8 c) // [x0, x1) x [y0, y1)
    {
        x0 = std::max(x0, 0), y0 = std::max(y0, 0);
        x1 = std::min(x1, _image->s()), y1 = std::min(y1, _image->t());
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
            {
                unsigned char* p = _image->data(x, _image->t() - 1 - y);
                p[0] = c.r, p[1] = c.g, p[2] = c.b;
            }
    }
    /** A decimal number in a 3x5 pixel font, each font pixel scale x scale, right-aligned at
     *  xRight. */
    void number(unsigned value, int xRight, int yTop, int scale, Rgb8 c)
    {
        static const char* const glyphs[10] = {
            "111101101101111", "010110010010111", "111001111100111", "111001111001111", "101101111001001",
            "111100111001111", "111100111101111", "111001001001001", "111101111101111", "111101111001111"};
        const std::string digits = std::to_string(value);
        int x = xRight - int(digits.size()) * 4 * scale + scale;
        for (char d : digits)
        {
            const char* g = glyphs[d - '0'];
            for (int row = 0; row < 5; ++row)
                for (int col = 0; col < 3; ++col)
                    if (g[row * 3 + col] == '1')
                        fill(x + col * scale, yTop + row * scale, x + (col + 1) * scale,
                             yTop + (row + 1) * scale, c);
            x += 4 * scale;
        }
    }
    osg::Image* image() { return _image.get(); }

private:
    osg::ref_ptr<osg::Image> _image;
};

struct Level
{
    unsigned requested = 0, k = 0; ///< k = min(requested, n)
    osgLoA::PaletteHierarchy::Colors palette;
    double error = 0;
};

/** Paper 003 Figure 1's "selected colors in the histogram": the table as bars, sorted by weight
 *  (the table's order), then one strip per level. */
osg::ref_ptr<osg::Image> histogramChart(const std::vector<osgLoA::TextureHistogram::ColorEntry>& table,
                                        const std::vector<Level>& levels)
{
    const int margin = 8, labelWidth = 48, plotWidth = 960, barHeight = 200, stripHeight = 28, gap = 8;
    const int left = margin + labelWidth;
    const int width = left + plotWidth + margin;
    const int height = margin + barHeight + 1 + int(levels.size()) * (gap + stripHeight) + margin;
    const Rgb8 background{236, 236, 236}, ink{64, 64, 64};
    Canvas canvas(width, height, background);

    const std::size_t n = table.size();
    const double maxWeight = n ? table[0].weight : 1.0;
    const int base = margin + barHeight; // the baseline row
    auto barTop = [&](double w) { return base - std::max(1, int(std::lround(barHeight * w / maxWeight))); };
    if (n <= std::size_t(plotWidth))
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            const int x0 = left + int(i * plotWidth / n), x1 = left + int((i + 1) * plotWidth / n);
            const int gapRight = x1 - x0 >= 4 ? 1 : 0; // a background line between wide bars
            canvas.fill(x0, barTop(table[i].weight), x1 - gapRight, base,
                        Rgb8{table[i].r, table[i].g, table[i].b});
        }
    }
    else // more colours than columns: each column shows the heaviest of its entries
        for (int x = 0; x < plotWidth; ++x)
        {
            const auto& e = table[std::size_t(x) * n / std::size_t(plotWidth)];
            canvas.fill(left + x, barTop(e.weight), left + x + 1, base, Rgb8{e.r, e.g, e.b});
        }
    canvas.fill(left, base, left + plotWidth, base + 1, ink);

    int y = base + 1;
    for (const Level& level : levels)
    {
        y += gap;
        std::vector<std::size_t> order(level.palette.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b)
                         { return level.palette[a].weight > level.palette[b].weight; });
        double total = 0;
        for (const auto& c : level.palette)
            total += c.weight;
        canvas.fill(left - 1, y - 1, left + plotWidth + 1, y + stripHeight + 1, ink);
        double cumulative = 0;
        for (std::size_t i : order)
        {
            const int x0 = left + int(std::lround(plotWidth * cumulative / total));
            cumulative += level.palette[i].weight;
            const int x1 = left + int(std::lround(plotWidth * cumulative / total));
            canvas.fill(x0, y, x1, y + stripHeight, toBytes(level.palette[i].rgb));
        }
        canvas.number(level.requested, left - 8, y + (stripHeight - 15) / 2, 3, ink);
        y += stripHeight;
    }
    return canvas.image();
}

std::string number(double v, const char* format = "%.9g")
{
    char b[40];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

int run(const Options& o)
{
    // The output directory first: a run that cannot write should fail before the work. It is
    // written as a whole: the files go into a staging folder that replaces --out-dir at the end,
    // so an interrupted run leaves the old outputs, never new images beside an old palettes.json.
    osgLoA::AtomicDirectory outDir(o.out, "palettes.json");
    const std::string& staging = outDir.staging();

    // An image file that cannot be read leaves an empty image carrying its name (reported below).
    osg::ref_ptr<osg::Node> scene = loa::loadModels(o.models, o.readerOptions, true);

    // Every distinct image of a 2D texture on unit 0, in traversal order.
    std::vector<Unit> units;
    std::map<const osg::Image*, std::size_t> unitOf;
    std::set<const osg::Texture*> seen;
    std::size_t otherTextures = 0, textureCount = 0;
    osgLoA::StateSetVisitor visitor(
        [&](osg::StateSet& ss)
        {
            osg::Texture* t =
                dynamic_cast<osg::Texture*>(ss.getTextureAttribute(0, osg::StateAttribute::TEXTURE));
            if (!t || !seen.insert(t).second) return;
            osg::Texture2D* t2 = dynamic_cast<osg::Texture2D*>(t);
            if (!t2)
            {
                ++otherTextures;
                return;
            }
            ++textureCount;
            osg::Image* image = t2->getImage();
            auto it = image ? unitOf.find(image) : unitOf.end();
            if (it != unitOf.end())
            {
                units[it->second].textures.push_back(t2);
                return;
            }
            Unit u;
            u.label = loa::textureLabel(*t2, units.size());
            u.name = stemOf(*t2);
            u.image = image;
            u.textures.push_back(t2);
            if (!image)
                u.problem = "has no image (its file could not be read?)";
            else if (image->s() <= 0 || image->t() <= 0 || !image->data())
                u.problem = "is empty (" + std::to_string(image->s()) + "x" + std::to_string(image->t()) +
                            "): its file is missing, corrupt or unreadable";
            else if (!supportedFormat(*image))
            {
                // Luminance, LA, 16-bit, float and S3TC images are converted to 8-bit RGB(A)
                // (the colours a shader samples); anything else is skipped by name.
                try
                {
                    osg::ref_ptr<const osg::Image> rgb = osgLoA::FilterImage::toRGB8(*image);
                    u.image = const_cast<osg::Image*>(rgb.get());
                }
                catch (const std::invalid_argument& e)
                {
                    char b[64];
                    std::snprintf(b, sizeof b, "0x%x/0x%x", unsigned(image->getPixelFormat()),
                                  unsigned(image->getDataType()));
                    u.problem = std::string("has pixel format ") + b + ", which the palette cannot read (" +
                                e.what() + ")";
                }
            }
            if (image) unitOf.emplace(image, units.size());
            units.push_back(u);
        });
    scene->accept(visitor);
    if (units.empty())
        throw std::runtime_error(
            "'" + o.model + "' has no textured geometry (no 2D texture on unit 0)" +
            (otherTextures ? " (" + std::to_string(otherTextures) + " other textures)" : ""));

    // Unique output names, in traversal order.
    std::set<std::string> names;
    for (Unit& u : units)
    {
        std::string name = u.name;
        for (int i = 2; !names.insert(name).second; ++i)
            name = u.name + "_" + std::to_string(i);
        u.name = name;
    }

    // Images that cannot be weighted are detached while the weights are computed (the
    // histogram skips textures without image), then put back.
    auto detach = [](Unit& u)
    {
        for (auto& t : u.textures)
            t->setImage(nullptr);
    };
    auto attach = [](Unit& u)
    {
        for (auto& t : u.textures)
            t->setImage(u.image.get());
    };
    for (Unit& u : units)
        if (!u.problem.empty()) detach(u);

    osg::ref_ptr<osgLoA::HeadlessContext> context;
    if (o.gpu)
    {
        context = new osgLoA::HeadlessContext;
        if (!context->realize() || !context->makeCurrent())
            throw osgLoA::HeadlessContextError("cannot make the headless EGL context current");
    }
    osg::State* state = context.valid() ? context->getState() : nullptr;
    if (!o.quiet)
        std::cerr << "loa-palette: " << o.model << ": " << textureCount << " 2D textures on unit 0, "
                  << units.size() << " distinct images"
                  << (otherTextures ? ", " + std::to_string(otherTextures) + " other textures ignored" : "")
                  << "; texel weights on the " << (state ? "GPU" : "CPU") << ", "
                  << osgLoA::PaletteHierarchy::toString(o.linkage) << " linkage\n";

    std::map<const osg::Image*, std::vector<double>> weights;
    try
    {
        weights = osgLoA::TextureHistogram::sceneWeights(*scene, state);
    }
    catch (const std::invalid_argument&)
    {
        // One image's geometry is refused (a texture coordinate range past the limit, a
        // malformed geometry): weight the images one at a time to find which.
        std::vector<Unit*> good;
        for (Unit& u : units)
            if (u.problem.empty()) good.push_back(&u), detach(u);
        for (Unit* u : good)
        {
            attach(*u);
            try
            {
                auto one = osgLoA::TextureHistogram::sceneWeights(*scene, state);
                auto it = one.find(u->image.get());
                if (it != one.end()) weights[u->image.get()] = std::move(it->second);
            }
            catch (const std::invalid_argument& e)
            {
                u->problem = std::string("its texel weights cannot be computed: ") + e.what();
            }
            detach(*u);
        }
    }
    for (Unit& u : units)
        if (u.image.valid()) attach(u);
    if (context.valid()) context->releaseContext();

    std::size_t used = 0;
    for (const Unit& u : units)
        if (!u.problem.empty() || weights.count(u.image.get())) ++used;
    if (used == 0)
        throw std::runtime_error("'" + o.model + "' has no textured geometry (none of its " +
                                 std::to_string(units.size()) +
                                 " textures is shown by a geometry with texture coordinates on unit 0)");

    loa::ProgressBar progress("loa-palette", used, "textures", o.quiet);
    std::size_t done = 0, skipped = 0;
    std::ostringstream json;
    json << "{\n  \"model\": \"" << osgLoA::jsonEscape(o.model) << "\",\n  \"linkage\": \""
         << osgLoA::PaletteHierarchy::toString(o.linkage) << "\",\n  \"weights\": \""
         << (state ? "gpu" : "cpu") << "\",\n  \"levels\": [";
    for (std::size_t i = 0; i < o.levels.size(); ++i)
        json << (i ? ", " : "") << o.levels[i];
    json << "],\n  \"textures\": [";
    std::ostringstream skippedJson;
    auto skip = [&](const Unit& u, const std::string& why)
    {
        ++skipped;
        progress.message("skipped " + u.label + ": " + why);
        progress.done("skipped " + u.label);
        skippedJson << (skipped > 1 ? ",\n" : "\n") << "    {\"name\": \"" << osgLoA::jsonEscape(u.label)
                    << "\", \"reason\": \"" << osgLoA::jsonEscape(why) << "\"}";
    };

    for (const Unit& u : units)
    {
        if (!u.problem.empty())
        {
            skip(u, u.problem);
            continue;
        }
        const auto wit = weights.find(u.image.get());
        if (wit == weights.end())
        {
            progress.message("note: " + u.label +
                             " is shown by no geometry with texture coordinates: ignored");
            continue;
        }
        progress.start(u.label);
        const auto t0 = std::chrono::steady_clock::now();
        const osg::Image& image = *u.image;
        const auto table = osgLoA::TextureHistogram::colorTable(image, wit->second);
        if (table.empty())
        {
            skip(u,
                 "no texel has a non-zero weight (the geometry's texture coordinates cover no texel centre)");
            continue;
        }
        if (table.size() > o.maxColors)
        {
            skip(u, "its colour table holds " + std::to_string(table.size()) +
                        " colours, above --max-colors " + std::to_string(o.maxColors));
            continue;
        }
        osgLoA::PaletteHierarchy::Colors colors;
        colors.reserve(table.size());
        std::unordered_map<unsigned, unsigned> tableIndex;
        double totalWeight = 0;
        for (std::size_t i = 0; i < table.size(); ++i)
        {
            const auto& e = table[i];
            colors.emplace_back(osg::Vec3f(e.r, e.g, e.b) / 255.0f, e.weight);
            tableIndex[(unsigned(e.r) << 16) | (unsigned(e.g) << 8) | e.b] = unsigned(i);
            totalWeight += e.weight;
        }
        osg::ref_ptr<osgLoA::PaletteHierarchy> hierarchy = osgLoA::PaletteHierarchy::build(colors, o.linkage);
        const unsigned n = hierarchy->numColors();

        std::vector<Level> levels;
        std::string clamped;
        for (unsigned requested : o.levels)
        {
            Level level;
            level.requested = requested;
            level.k = std::min(requested, n);
            if (requested > n) clamped += (clamped.empty() ? "" : ", ") + std::to_string(requested);
            level.palette = hierarchy->palette(level.k);
            level.error = hierarchy->error(level.k);
            std::vector<Rgb8> bytes;
            for (const auto& c : level.palette)
                bytes.push_back(toBytes(c.rgb));
            osg::ref_ptr<osg::Image> segmented = segment(image, tableIndex, hierarchy->assignment(level.k),
                                                         bytes, hierarchy->paletteLab(level.k));
            osgLoA::ImageFile::write(staging + "/" + u.name + "-" + std::to_string(requested) + ".png",
                                     *segmented);
            levels.push_back(level);
        }
        if (!clamped.empty())
            progress.message("note: " + u.label + " has " + std::to_string(n) + " colours: level" +
                             (clamped.find(',') != std::string::npos ? "s " : " ") + clamped + " give" +
                             (clamped.find(',') != std::string::npos ? "" : "s") + " all " +
                             std::to_string(n));
        osgLoA::ImageFile::write(staging + "/" + u.name + "-histogram.png", *histogramChart(table, levels));

        json << (done ? ",\n" : "\n") << "    {\n      \"name\": \"" << osgLoA::jsonEscape(u.name)
             << "\",\n      \"source\": \"" << osgLoA::jsonEscape(u.label)
             << "\",\n      \"width\": " << image.s() << ",\n      \"height\": " << image.t()
             << ",\n      \"tableSize\": " << n << ",\n      \"totalWeight\": " << number(totalWeight)
             << ",\n      \"histogram\": \"" << osgLoA::jsonEscape(u.name)
             << "-histogram.png\",\n      \"levels\": [";
        for (std::size_t i = 0; i < levels.size(); ++i)
        {
            const Level& level = levels[i];
            json << (i ? ",\n" : "\n") << "        {\"level\": " << level.requested
                 << ", \"colors\": " << level.k << ", \"file\": \"" << osgLoA::jsonEscape(u.name) << "-"
                 << level.requested << ".png\", \"error\": " << number(level.error, "%.6g")
                 << ",\n         \"palette\": [";
            for (std::size_t c = 0; c < level.palette.size(); ++c)
                json << (c ? ", " : "") << "{\"color\": \"" << hex(toBytes(level.palette[c].rgb))
                     << "\", \"weight\": " << number(level.palette[c].weight)
                     << ", \"share\": " << number(level.palette[c].weight / totalWeight, "%.6g") << "}";
            json << "]}";
        }
        json << "\n      ]\n    }";
        ++done;
        char line[200];
        std::snprintf(line, sizeof line, "%s %dx%d: %u colours -> %s-*.png (%.2f s)", u.label.c_str(),
                      image.s(), image.t(), n, u.name.c_str(),
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        progress.done(line);
    }
    progress.finish();
    json << (done ? "\n  ],\n" : "],\n") << "  \"skipped\": [" << skippedJson.str()
         << (skipped ? "\n  ]\n}\n" : "]\n}\n");
    osgLoA::AtomicFile::writeText(staging + "/palettes.json", json.str());
    outDir.commit();

    std::string levelList;
    for (unsigned k : o.levels)
        levelList += (levelList.empty() ? "" : ",") + std::to_string(k);
    if (!o.quiet)
        std::cerr << "loa-palette: " << done << " textures segmented at levels " << levelList << ", "
                  << skipped << " skipped in " << loa::durationText(progress.elapsed()) << "; wrote " << o.out
                  << "/palettes.json\n";
    return skipped ? kSkipped : loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    Options o;
    return loa::runTool(
        "loa-palette", [&] { o = parse(argc, argv); }, [&] { return run(o); });
}
