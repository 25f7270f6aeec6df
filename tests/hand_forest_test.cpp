// The hand forest's model file (hand_forest.h): what is written is read back, a damaged file is refused by name,
// and the forest compiled into the program is a real one.
#include "capture/hand_forest.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace gb {
namespace {

// Two splits and three leaves: the pixels with background 10 cm to their right are mostly a right hand, those
// with background 10 cm to their left body, the others a left hand.
HandForest smallForest() {
  DecisionTree tree;
  tree.nodes.resize(5);
  tree.nodes[0] = {{{{100, 0}}, {{0, 0}}}, 0.5f, 1};
  tree.nodes[1] = {{{{-100, 0}}, {{0, 0}}}, 0.25f, 3};
  tree.nodes[2].next = -1;
  tree.nodes[3].next = -2;
  tree.nodes[4].next = -3;
  tree.leaves = {{0.2f, 0.0f, 0.8f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  HandForest forest;
  forest.trees = {tree};
  forest.surfaceToCentre = 0.047f;
  forest.trainedOn = "a test";
  return forest;
}

TEST(HandForest, AModelReadsBackAsWrittenWithinItsQuantisation) {
  const HandForest forest = smallForest();
  const std::vector<uint8_t> bytes = forest.serialize();
  const HandForest back = HandForest::deserialize(bytes.data(), bytes.size());
  EXPECT_EQ(back.trainedOn, forest.trainedOn);
  EXPECT_EQ(back.surfaceToCentre, forest.surfaceToCentre);
  ASSERT_EQ(back.trees.size(), 1u);
  for (size_t i = 0; i < forest.trees[0].nodes.size(); ++i) {
    EXPECT_EQ(back.trees[0].nodes[i].next, forest.trees[0].nodes[i].next);
    if (forest.trees[0].nodes[i].next >= 0) {
      EXPECT_EQ(back.trees[0].nodes[i].threshold, forest.trees[0].nodes[i].threshold);
    }
  }
  // Leaf probabilities are kept in 255ths: within half a step of 1/255.
  for (size_t l = 0; l < forest.trees[0].leaves.size(); ++l)
    for (int c = 0; c < kPixelClasses; ++c)
      EXPECT_NEAR(back.trees[0].leaves[l][c], forest.trees[0].leaves[l][c], 0.5 / 255 + 1e-6);
}

TEST(HandForest, ADamagedModelIsRefusedNotRead) {
  const std::vector<uint8_t> bytes = smallForest().serialize();
  const auto refused = [](std::vector<uint8_t> b) {
    try {
      HandForest::deserialize(b.data(), b.size());
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  EXPECT_NE(refused({bytes.begin(), bytes.begin() + 5}).find("truncated"), std::string::npos);
  std::vector<uint8_t> foreign = bytes;
  foreign[0] = 'X';
  EXPECT_NE(refused(foreign).find("not a giantbubble hand forest"), std::string::npos);
  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 4);
  EXPECT_NE(refused(cut).find("damaged"), std::string::npos);
  // A node pointing outside its tree would send classification out of bounds.
  HandForest looping = smallForest();
  looping.trees[0].nodes[1].next = 0;
  const std::vector<uint8_t> loop = looping.serialize();
  EXPECT_NE(refused(loop).find("points outside its tree"), std::string::npos);
}

TEST(HandForest, ThePixelsOfATreeFollowItsSplits) {
  const HandForest forest = smallForest();
  BodyDepth body;
  for (int u = 100; u < 200; ++u) body.depth[static_cast<size_t>(120 * BodyDepth::kWidth + u)] = 2.0f;
  // 0.1 m at 2 m is 15 grid pixels. The strip's right end has background to its right (10 m - 2 m >= 0.5: leaf
  // 0), its left end background to its left (0 < 0.5, then 8 >= 0.25: leaf 2), its middle neither (leaf 1).
  EXPECT_NEAR(forest.classify(body, 199, 120, 2.0f)[kRightHandPixel], 0.8f, 1e-6);
  EXPECT_EQ(forest.classify(body, 100, 120, 2.0f)[kBodyPixel], 1.0f);
  EXPECT_EQ(forest.classify(body, 150, 120, 2.0f)[kLeftHandPixel], 1.0f);
}

TEST(HandForest, TheBuiltInForestIsTrained) {
  const HandForest& forest = HandForest::builtin();
  EXPECT_GE(forest.trees.size(), 1u);
  for (const DecisionTree& tree : forest.trees) EXPECT_GT(tree.nodes.size(), 1000u);
  EXPECT_GT(forest.surfaceToCentre, 0.0f);
  EXPECT_NE(forest.trainedOn.find("recordings"), std::string::npos) << forest.trainedOn;
}

}  // namespace
}  // namespace gb
