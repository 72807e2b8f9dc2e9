// TransitionRenderer without GL: the memory report against paper 004 §4.3's formula.
#include <osgLoA/transitions/TransitionRenderer>

#include <gtest/gtest.h>

using namespace osgLoA;

TEST(TransitionRendererTest, MemoryAgainstThePaperFormula)
{
    // 1920 x 1080 = 2,073,600 pixels, N = 8, one routing pass.
    const TransitionRenderer::Memory m = TransitionRenderer::memory(1920, 1080, 8, 1, true, true);
    const double px = 2073600.0;
    EXPECT_DOUBLE_EQ(m.aBufferBytes, px * 8 * 8);     // RGBA8 + DEPTH24_STENCIL8 per sample
    EXPECT_DOUBLE_EQ(m.geometryBufferBytes, px * 20); // 4 RGBA8 targets + DEPTH32F
    EXPECT_DOUBLE_EQ(m.pingPongBytes, px * 16);       // 2 x (RGBA8 + DEPTH32F)
    // Sigma 8 (the default): 3 RG32F targets at a quarter of the resolution (480 x 270).
    EXPECT_DOUBLE_EQ(m.unsharpBytes, 3.0 * 480 * 270 * 8);
    EXPECT_DOUBLE_EQ(m.paperBytes, px * 23 * 4);               // W H (2N + 7) words
    EXPECT_NEAR(m.paperBytes / 1048576.0, 181.93359375, 1e-9); // the paper's MB (2^20 bytes)
    EXPECT_NEAR(m.totalBytes() / 1048576.0, 200.7, 0.05);
    // Passes multiply only the A-buffer; without ping-pong and unsharp masking they cost nothing.
    const TransitionRenderer::Memory m3 = TransitionRenderer::memory(1920, 1080, 8, 3, false, false);
    EXPECT_DOUBLE_EQ(m3.aBufferBytes, 3 * m.aBufferBytes);
    EXPECT_DOUBLE_EQ(m3.pingPongBytes, 0.0);
    EXPECT_DOUBLE_EQ(m3.unsharpBytes, 0.0);
    // A narrow Gaussian (sigma < 4 pixels) is not reduced: 3 full-size RG32F targets; the
    // reduction is capped at 8 (sigma 64 -> 240 x 135); odd sizes round up.
    EXPECT_DOUBLE_EQ(TransitionRenderer::memory(100, 50, 1, 1, false, true, 3.0f).unsharpBytes,
                     3.0 * 5000 * 8);
    EXPECT_DOUBLE_EQ(TransitionRenderer::memory(1920, 1080, 1, 1, false, true, 64.0f).unsharpBytes,
                     3.0 * 240 * 135 * 8);
    EXPECT_DOUBLE_EQ(TransitionRenderer::memory(101, 51, 1, 1, false, true, 8.0f).unsharpBytes,
                     3.0 * 26 * 13 * 8);
}
