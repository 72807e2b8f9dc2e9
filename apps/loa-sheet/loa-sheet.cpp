// loa-sheet: tiles images of one size into a contact sheet (docs/images/scenarios-*.png).
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"

#include <osgLoA/util/ImageFile>

#include <osgDB/FileNameUtils>

#include <algorithm>
#include <cstring>
#include <iostream>

namespace
{
const char* kDescription =
    R"(Tiles the IMAGEs (PNG or any format OpenImageIO reads; all of one size) row by row, left to
right, into one contact sheet --out FILE.png, with white gaps between them; 8-bit RGB. The write
is atomic. scripts/contact-sheets uses it for one sheet of every library scenario per scene.
)";
const char* kFooter = R"(exit status: 0 written, 1 an image could not be read or the sheet not written, 2 bad
arguments (no image, images of different sizes).
)";

/** The image as 8-bit RGB rows (OSG's bottom-up order), composited over white where it has
 *  alpha. */
std::vector<unsigned char> rgb8(const osg::Image& image, const std::string& path)
{
    const int w = image.s(), h = image.t();
    std::vector<unsigned char> out(std::size_t(w) * h * 3);
    if (image.getDataType() != GL_UNSIGNED_BYTE)
        throw std::runtime_error("'" + path + "' is not 8 bits per channel");
    const GLenum format = image.getPixelFormat();
    const int channels = format == GL_RGBA              ? 4
                         : format == GL_RGB             ? 3
                         : format == GL_LUMINANCE_ALPHA ? 2
                         : format == GL_LUMINANCE       ? 1
                                                        : 0;
    if (channels == 0) throw std::runtime_error("'" + path + "' has a pixel format loa-sheet does not read");
    for (int y = 0; y < h; ++y)
    {
        const unsigned char* row = image.data(0, y);
        for (int x = 0; x < w; ++x)
        {
            const unsigned char* p = row + x * channels;
            const unsigned char r = p[0], g = channels >= 3 ? p[1] : p[0], b = channels >= 3 ? p[2] : p[0];
            const int a = channels == 4 ? p[3] : channels == 2 ? p[1] : 255;
            unsigned char* q = &out[(std::size_t(y) * w + x) * 3];
            q[0] = (unsigned char)((r * a + 255 * (255 - a) + 127) / 255);
            q[1] = (unsigned char)((g * a + 255 * (255 - a) + 127) / 255);
            q[2] = (unsigned char)((b * a + 255 * (255 - a) + 127) / 255);
        }
    }
    return out;
}
} // namespace

int main(int argc, char** argv)
{
    std::string output;
    std::vector<std::string> inputs;
    unsigned columns = 3, gap = 8;
    return loa::runTool(
        "loa-sheet",
        [&]
        {
            loa::CommandLine cl("loa-sheet", "loa-sheet IMAGE... --out FILE.png [--columns N] [--gap PIXELS]",
                                kDescription);
            CLI::App& app = cl.app();
            app.add_option("IMAGE", inputs, "the images, in reading order")->group(loa::kGroupModel);
            loa::addOutFile(app, output, "the contact sheet to write (.png; required)");
            loa::addCount(app, "--columns", columns, 1, 64, "images per row (default 3)");
            loa::addCount(app, "--gap", gap, 0, 1024, "white space between images in pixels (default 8)");
            cl.footer(kFooter);
            cl.parse(argc, argv);
            if (output.empty()) throw loa::UsageError("no --out FILE.png given (see --help)");
            if (osgDB::getLowerCaseFileExtension(output) != "png")
                throw loa::UsageError("--out '" + output + "' must name a .png file");
            if (inputs.empty()) throw loa::UsageError("no IMAGE given (see --help)");
        },
        [&]
        {
            std::vector<std::vector<unsigned char>> tiles;
            int w = 0, h = 0;
            for (const std::string& path : inputs)
            {
                osg::ref_ptr<osg::Image> image = osgLoA::ImageFile::read(path);
                if (tiles.empty())
                {
                    w = image->s();
                    h = image->t();
                }
                else if (image->s() != w || image->t() != h)
                    throw loa::UsageError("'" + path + "' is " + loa::imageSizeText(*image) + ", '" +
                                          inputs.front() + "' " + std::to_string(w) + "x" +
                                          std::to_string(h) + ": the images of a sheet must have one size");
                tiles.push_back(rgb8(*image, path));
            }
            const unsigned cols = std::min<unsigned>(columns, unsigned(tiles.size()));
            const unsigned rows = unsigned((tiles.size() + cols - 1) / cols);
            const int W = int(cols) * w + int(cols - 1) * int(gap),
                      H = int(rows) * h + int(rows - 1) * int(gap);
            osg::ref_ptr<osg::Image> sheet = new osg::Image;
            sheet->allocateImage(W, H, 1, GL_RGB, GL_UNSIGNED_BYTE);
            std::memset(sheet->data(), 255, sheet->getTotalSizeInBytes());
            for (std::size_t i = 0; i < tiles.size(); ++i)
            {
                const int col = int(i % cols), row = int(i / cols);
                const int x0 = col * (w + int(gap));
                const int y0 = H - (row + 1) * h - row * int(gap); // rows from the top; OSG is bottom-up
                for (int y = 0; y < h; ++y)
                    std::memcpy(sheet->data(x0, y0 + y), &tiles[i][std::size_t(y) * w * 3],
                                std::size_t(w) * 3);
            }
            osgLoA::ImageFile::write(output, *sheet);
            std::cout << "wrote " << output << " (" << W << "x" << H << ", " << tiles.size() << " images, "
                      << cols << " a row)\n";
            return loa::kOk;
        });
}
