// OITAutoSelection: the order-independent transparency method chosen by measured cost, with
// hand-made frame times (no GL).
#include <osgLoA/compositing/OITAutoSelection>

#include <gtest/gtest.h>

#include <stdexcept>

using namespace osgLoA;
using OIT = OrderIndependentTransparency;

TEST(OITAutoSelectionTest, TriesEachCandidateAndKeepsTheCheapest)
{
    OITAutoSelection sel({OIT::STENCIL_ROUTED, OIT::LINKED_LIST}, 3, 4);
    EXPECT_EQ(sel.current(), OIT::STENCIL_ROUTED);
    EXPECT_FALSE(sel.hasChosen());
    EXPECT_EQ(sel.record(500.0, 640, 480), OIT::STENCIL_ROUTED); // first frame: dropped
    EXPECT_EQ(sel.record(10.0, 640, 480), OIT::STENCIL_ROUTED);
    EXPECT_EQ(sel.record(30.0, 640, 480), OIT::STENCIL_ROUTED);
    EXPECT_EQ(sel.record(11.0, 640, 480), OIT::LINKED_LIST);  // median 11: the next candidate
    EXPECT_EQ(sel.record(900.0, 640, 480), OIT::LINKED_LIST); // after the switch: dropped
    EXPECT_EQ(sel.record(20.0, 640, 480), OIT::LINKED_LIST);
    EXPECT_EQ(sel.record(5.0, 640, 480), OIT::LINKED_LIST);
    EXPECT_EQ(sel.record(21.0, 640, 480), OIT::STENCIL_ROUTED); // median 20 > 11
    EXPECT_TRUE(sel.hasChosen());
    ASSERT_EQ(sel.getMedians().size(), 2u);
    EXPECT_DOUBLE_EQ(sel.getMedians()[0], 11.0);
    EXPECT_DOUBLE_EQ(sel.getMedians()[1], 20.0);
    // Held for 4 frames, whatever they cost; then a new trial from the first candidate.
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(sel.record(1000.0, 640, 480), OIT::STENCIL_ROUTED);
    EXPECT_EQ(sel.record(1000.0, 640, 480), OIT::STENCIL_ROUTED);
    EXPECT_DOUBLE_EQ(sel.getMedians()[0], -1.0);
}

TEST(OITAutoSelectionTest, PicksTheLinkedListsWhenTheyAreCheaperAndRetriesOnAResize)
{
    OITAutoSelection sel({OIT::STENCIL_ROUTED, OIT::LINKED_LIST}, 2, 100);
    for (double ms : {0.0, 40.0, 42.0})
        sel.record(ms, 800, 600);
    EXPECT_EQ(sel.current(), OIT::LINKED_LIST);
    for (double ms : {0.0, 30.0})
        sel.record(ms, 800, 600);
    EXPECT_EQ(sel.record(32.0, 800, 600), OIT::LINKED_LIST); // upper medians: 32 < 42
    EXPECT_TRUE(sel.hasChosen());
    // A new size: a new trial, from the first candidate; the resized frame and the first frame
    // after the switch back are dropped.
    EXPECT_EQ(sel.record(7.0, 1920, 1080), OIT::STENCIL_ROUTED);
    EXPECT_EQ(sel.record(1e6, 1920, 1080), OIT::STENCIL_ROUTED); // dropped
    EXPECT_EQ(sel.record(50.0, 1920, 1080), OIT::STENCIL_ROUTED);
    EXPECT_EQ(sel.record(52.0, 1920, 1080), OIT::LINKED_LIST); // median of 50, 52: 52 (upper)
    EXPECT_DOUBLE_EQ(sel.getMedians()[0], 52.0);
}

TEST(OITAutoSelectionTest, RefusesWhatCannotBeMeasured)
{
    EXPECT_THROW(OITAutoSelection(std::vector<OIT::Method>{}), std::invalid_argument);
    EXPECT_THROW(OITAutoSelection({OIT::LINKED_LIST}, 0, 1), std::invalid_argument);
    OITAutoSelection sel;
    EXPECT_THROW(sel.record(-1.0, 10, 10), std::invalid_argument);
    // One candidate: always it.
    OITAutoSelection one({OIT::LINKED_LIST}, 1, 1);
    for (int i = 0; i < 5; ++i)
        EXPECT_EQ(one.record(1.0, 10, 10), OIT::LINKED_LIST);
}
