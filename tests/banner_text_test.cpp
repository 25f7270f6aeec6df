// The live window's message banner drawn on the CPU (host/banner_text.h, host/bitmap_font.h): the words wrapped
// to the image's width, long messages cut, the glyphs scaled with the image, and text that is not printable
// ASCII drawn as '?'. Exact checks: the banner is integer arithmetic on whole pixels.
#include "host/banner_text.h"

#include <gtest/gtest.h>

#include "host/bitmap_font.h"

namespace gb {
namespace {

size_t inkPixels(const BannerImage& banner) {
  size_t ink = 0;
  for (size_t p = 0; p < banner.rgba.size(); p += 4) ink += banner.rgba[p] > 128 ? 1 : 0;  // the text is light
  return ink;
}

TEST(BannerText, WrapsAtSpacesWithinTheColumns) {
  const auto lines = wrapBannerLines("the simulation became unstable;  a new\nfilm is dipped", 20, 3);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "the simulation");
  EXPECT_EQ(lines[1], "became unstable; a");
  EXPECT_EQ(lines[2], "new film is dipped");
}

TEST(BannerText, SplitsAWordLongerThanALineAndCutsWhatDoesNotFit) {
  EXPECT_EQ(wrapBannerLines("abcdefghij", 4, 3), (std::vector<std::string>{"abcd", "efgh", "ij"}));
  // Too much for two lines: the second line ends in "..." within the columns.
  EXPECT_EQ(wrapBannerLines("one two three four five", 8, 2), (std::vector<std::string>{"one two", "three..."}));
  EXPECT_EQ(wrapBannerLines("abcdefghijkl", 4, 2), (std::vector<std::string>{"abcd", "e..."}));
  EXPECT_TRUE(wrapBannerLines("   \n ", 10, 3).empty());
  EXPECT_TRUE(wrapBannerLines("text", 0, 3).empty());
}

TEST(BannerText, BannerSpansTheImageWidthAndScalesWithItsHeight) {
  const BannerImage small = drawBanner("camera lost", 320, 240);
  ASSERT_EQ(small.width, 320);
  // One line at scale 1: 9 rows of glyph and 3 of padding above and below.
  EXPECT_EQ(small.height, kGlyphHeight + 2 * 3);
  EXPECT_EQ(small.rgba.size(), 4u * 320 * small.height);
  const BannerImage large = drawBanner("camera lost", 1280, 720);
  EXPECT_EQ(large.height, 4 * small.height);  // scale 4 at 720 rows
  EXPECT_EQ(inkPixels(large), 16 * inkPixels(small));
  EXPECT_GT(inkPixels(small), 40u);  // "camera lost": ten glyphs of several pixels each
}

TEST(BannerText, LongMessagesWrapIntoAtMostThreeLines) {
  const std::string longText(400, 'x');
  const BannerImage banner = drawBanner(longText, 160, 120);
  EXPECT_EQ(banner.height, static_cast<int>(kMaxBannerLines) * (kGlyphHeight + 2) - 2 + 2 * 3);
  EXPECT_EQ(drawBanner("", 320, 240).height, 0);
  EXPECT_EQ(drawBanner("   ", 320, 240).height, 0);
  EXPECT_EQ(drawBanner("a message", 8, 8).height, 0);  // not even one character fits
}

TEST(BannerText, UnprintableCharactersDrawAsQuestionMarks) {
  const BannerImage question = drawBanner("?", 64, 32);
  EXPECT_EQ(drawBanner("\x01", 64, 32).rgba, question.rgba);
  EXPECT_EQ(drawBanner("\xc3", 64, 32).rgba, question.rgba);  // a byte of a UTF-8 sequence
  EXPECT_FALSE(glyphInk('A', -1, 0));
  EXPECT_FALSE(glyphInk('A', kGlyphWidth, 0));
  EXPECT_TRUE(glyphInk('A', 0, 3));  // the crossbar of the A
}

}  // namespace
}  // namespace gb
