// Serializer wrapper for osgLoA::TexturePalette (.osgt/.osgb/.osgx): Hierarchy (the
// PaletteHierarchy object), Levels (K), and, only for a palette without a hierarchy (loaded
// from the disk cache), "PaletteImage K { one row of K 0xRRGGBBAA values per line }" (K up to
// 1024 on read). The lookup texture is derived, not written.
#include <osgLoA/palette/TexturePalette>

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>
#include <osgDB/Serializer>

#include <stdexcept>
#include <string>

namespace
{
typedef osgLoA::TexturePalette Palette;
constexpr unsigned kMaxSide = 1024;

bool checkLevels(const Palette& p)
{
    return p.getLevels() != 0;
}

bool readLevels(osgDB::InputStream& is, Palette& p)
{
    unsigned int k = 0;
    is >> k;
    if (is.getException()) return false;
    try
    {
        p.setLevels(k);
    }
    catch (const std::invalid_argument& e)
    {
        is.throwException(std::string("TexturePalette: ") + e.what());
        return false;
    }
    return true;
}

bool writeLevels(osgDB::OutputStream& os, const Palette& p)
{
    os << p.getLevels() << std::endl;
    return true;
}

bool checkPaletteImage(const Palette& p)
{
    return !p.getHierarchy() && p.getStoredImage();
}

bool readPaletteImage(osgDB::InputStream& is, Palette& p)
{
    const unsigned K = is.readSize();
    if (is.getException()) return false;
    if (K < 1 || K > kMaxSide)
    {
        is.throwException("TexturePalette: PaletteImage side " + std::to_string(K) + " is not in [1, " +
                          std::to_string(kMaxSide) + "]");
        return false;
    }
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(int(K), int(K), 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    image->setInternalTextureFormat(GL_RGBA8);
    is >> is.BEGIN_BRACKET;
    for (unsigned y = 0; y < K && !is.getException(); ++y)
        for (unsigned x = 0; x < K && !is.getException(); ++x)
        {
            unsigned int v = 0;
            is >> v;
            unsigned char* q = image->data(int(x), int(y));
            q[0] = (v >> 24) & 255;
            q[1] = (v >> 16) & 255;
            q[2] = (v >> 8) & 255;
            q[3] = v & 255;
        }
    if (is.getException())
    {
        if (!is.isBinary()) is.advanceToCurrentEndBracket();
        return false;
    }
    is >> is.END_BRACKET;
    p.setStoredImage(image.get());
    return true;
}

bool writePaletteImage(osgDB::OutputStream& os, const Palette& p)
{
    const osg::Image& image = *p.getStoredImage();
    const unsigned K = unsigned(image.s());
    os.writeSize(K);
    os << os.BEGIN_BRACKET << std::endl;
    for (unsigned y = 0; y < K; ++y)
    {
        for (unsigned x = 0; x < K; ++x)
        {
            const unsigned char* c = image.data(int(x), int(y));
            os << ((unsigned int)(c[0]) << 24 | (unsigned int)(c[1]) << 16 | (unsigned int)(c[2]) << 8 |
                   (unsigned int)(c[3]));
        }
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}
} // namespace

REGISTER_OBJECT_WRAPPER(osgLoA_TexturePalette, new osgLoA::TexturePalette, osgLoA::TexturePalette,
                        "osg::Object osgLoA::TexturePalette")
{
    ADD_OBJECT_SERIALIZER(Hierarchy, osgLoA::PaletteHierarchy, NULL);
    ADD_USER_SERIALIZER(Levels);
    ADD_USER_SERIALIZER(PaletteImage);
}
