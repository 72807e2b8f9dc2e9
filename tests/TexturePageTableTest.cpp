// The page table of deferred texturing (osgLoA::TexturePageTable, paper 000 Fig. 5): texture
// identifiers, one atlas region per mip level with the texture's wrap modes, a shelf packer
// without overlaps, the atlas contents and the tables the shaders read.
#include <osgLoA/filtering/TexturePageTable>

#include <gtest/gtest.h>

using namespace osgLoA;

namespace
{
FilterImage ramp(int w, int h, float id)
{
    FilterImage img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, osg::Vec4f(float(x) / float(w), float(y) / float(h), id, 1.0f));
    return img;
}

osg::ref_ptr<osg::Texture2D> texture(int w, int h, osg::Texture::WrapMode s, osg::Texture::WrapMode t)
{
    osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(ramp(w, h, 0.5f).toImage().get());
    tex->setWrap(osg::Texture::WRAP_S, s);
    tex->setWrap(osg::Texture::WRAP_T, t);
    return tex;
}

bool overlap(const GpuFilterEngine::Region& a, const GpuFilterEngine::Region& b)
{
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
}
} // namespace

TEST(TexturePageTableTest, RegistersTexturesWithLevelsAndWrapModes)
{
    osg::ref_ptr<TexturePageTable> table = new TexturePageTable;
    osg::ref_ptr<osg::Texture2D> a = texture(64, 32, osg::Texture::REPEAT, osg::Texture::MIRROR);
    osg::ref_ptr<osg::Texture2D> b = texture(20, 12, osg::Texture::CLAMP_TO_EDGE, osg::Texture::REPEAT);
    EXPECT_EQ(table->registerTexture(*a), 0);
    EXPECT_EQ(table->registerTexture(*b), 1);
    EXPECT_EQ(table->registerTexture(*a), 0) << "the same texture on the same unit: the same TID";
    EXPECT_EQ(table->registerTexture(*a, 1), 2) << "another channel: its own TID";
    EXPECT_EQ(table->find(b.get()), 1);
    EXPECT_EQ(table->find(b.get(), 1), -1);
    ASSERT_EQ(table->size(), 3u);

    const TexturePageTable::Entry& ea = table->entries()[0];
    EXPECT_EQ(ea.width, 64);
    EXPECT_EQ(ea.height, 32);
    EXPECT_EQ(ea.levels, 7); // 64x32 32x16 16x8 8x4 4x2 2x1 1x1
    EXPECT_EQ(ea.border, ImageBorder(WrapMode::Repeat, WrapMode::Mirror));
    EXPECT_EQ(ea.firstRegion, 0);
    const TexturePageTable::Entry& eb = table->entries()[1];
    EXPECT_EQ(eb.levels, 5); // 20x12 10x6 5x3 2x1 1x1
    EXPECT_EQ(eb.border, ImageBorder(WrapMode::Clamp, WrapMode::Repeat));
    EXPECT_EQ(eb.firstRegion, 7);
    EXPECT_EQ(table->entries()[2].unit, 1u);
    EXPECT_EQ(table->entries()[2].firstRegion, 12);

    // Regions: consecutive levels, floor-halved sizes, the texture's wrap modes.
    ASSERT_EQ(table->regions().size(), 7u + 5u + 7u);
    const int bw[] = {20, 10, 5, 2, 1}, bh[] = {12, 6, 3, 1, 1};
    for (int l = 0; l < 5; ++l)
    {
        const GpuFilterEngine::Region& r = table->regions()[std::size_t(table->regionOf(1, l))];
        EXPECT_EQ(r.width, bw[l]);
        EXPECT_EQ(r.height, bh[l]);
        EXPECT_EQ(r.border, eb.border);
        EXPECT_EQ(table->levelOf(table->regionOf(1, l)), l);
        EXPECT_EQ(table->textureOf(table->regionOf(1, l)), 1);
    }
    // Tiles: 8x8, partial at the edges; the flat tile index of each region follows the previous.
    EXPECT_EQ(table->tileBase(0), 0u);
    EXPECT_EQ(table->tileBase(1), 8u * 4u); // 64x32: 8 x 4 tiles
    EXPECT_EQ(table->tileBase(7), 32u + 8u + 2u + 1u + 1u + 1u + 1u);
    EXPECT_EQ(table->tileBase(8), table->tileBase(7) + 3u * 2u); // 20x12: 3 x 2 tiles

    // Levels are FilterImage::mipPyramid.
    const std::vector<FilterImage> pyramid = FilterImage::fromImage(*b->getImage()).mipPyramid();
    EXPECT_EQ(FilterImage::maxAbsDifference(table->levelImage(1, 2), pyramid[2], true), 0.0f);

    osg::ref_ptr<osg::Texture2D> empty = new osg::Texture2D;
    empty->setName("render target");
    try
    {
        table->registerTexture(*empty);
        FAIL() << "no error";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("'render target' on unit 0 has no image"), std::string::npos)
            << e.what();
    }
}

TEST(TexturePageTableTest, PacksRegionsWithoutOverlapAndFillsTheAtlas)
{
    osg::ref_ptr<TexturePageTable> table = new TexturePageTable;
    table->registerImage(ramp(256, 256, 0.1f), ImageBorder(WrapMode::Repeat, WrapMode::Repeat));
    table->registerImage(ramp(128, 64, 0.2f), ImageBorder(WrapMode::Clamp, WrapMode::Clamp));
    table->registerImage(ramp(37, 91, 0.3f), ImageBorder(WrapMode::Mirror, WrapMode::Clamp));
    table->pack();
    ASSERT_TRUE(table->isPacked());
    const auto& regions = table->regions();
    for (std::size_t i = 0; i < regions.size(); ++i)
    {
        EXPECT_GE(regions[i].x, 0);
        EXPECT_GE(regions[i].y, 0);
        EXPECT_LE(regions[i].x + regions[i].width, table->atlasWidth());
        EXPECT_LE(regions[i].y + regions[i].height, table->atlasHeight());
        for (std::size_t j = i + 1; j < regions.size(); ++j)
            EXPECT_FALSE(overlap(regions[i], regions[j])) << i << " and " << j;
    }
    // 87381 + 10923 + 4455 texels in the regions; the shelves waste some.
    std::cout << "atlas " << table->atlasWidth() << "x" << table->atlasHeight() << ", "
              << table->packingEfficiency() * 100.0 << " % used, " << table->atlasBytes() << " bytes"
              << std::endl;
    EXPECT_GT(table->packingEfficiency(), 0.75);
    EXPECT_EQ(table->atlasBytes(),
              std::size_t(table->atlasWidth()) * std::size_t(table->atlasHeight()) * 16u);

    // The atlas holds every level at its region.
    const FilterImage atlas = table->atlasImage();
    for (std::size_t r = 0; r < regions.size(); ++r)
    {
        const FilterImage& level = table->levelImage(table->textureOf(int(r)), table->levelOf(int(r)));
        for (int y = 0; y < regions[r].height; y += std::max(1, regions[r].height / 5))
            for (int x = 0; x < regions[r].width; x += std::max(1, regions[r].width / 5))
                ASSERT_EQ(atlas.get(regions[r].x + x, regions[r].y + y), level.get(x, y))
                    << r << ": " << x << "," << y;
    }

    // The shader tables: 8 ints per texture and per region.
    const std::vector<int> pages = table->pageTableData();
    ASSERT_EQ(pages.size(), 3u * 8u);
    EXPECT_EQ(std::vector<int>(pages.begin() + 16, pages.end()),
              (std::vector<int>{37, 91, 7, 0, int(WrapMode::Mirror), int(WrapMode::Clamp), 9 + 8, 0}));
    const std::vector<int> rt = table->regionTableData();
    ASSERT_EQ(rt.size(), regions.size() * 8u);
    const std::size_t r = std::size_t(table->regionOf(2, 1)); // 18x45
    EXPECT_EQ(std::vector<int>(rt.begin() + long(r * 8), rt.begin() + long(r * 8 + 8)),
              (std::vector<int>{regions[r].x, regions[r].y, 18, 45, int(table->tileBase(int(r))), 3, 6, 1}));

    EXPECT_THROW(table->pack(200), std::invalid_argument);
    table->clear();
    table->pack();
    EXPECT_EQ(table->atlasWidth(), 1);
    EXPECT_EQ(table->tileCount(), 0u);
}
