// core/strings.h: ASCII lower-casing, the lower-case file extension, and join.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/strings.h"

namespace prism {
namespace {

TEST(CoreStrings, ToLowerChangesOnlyAsciiCapitals) {
  EXPECT_EQ(to_lower("Hello WORLD"), "hello world");
  EXPECT_EQ(to_lower("AZ az"), "az az");
  // The bytes either side of A-Z ('@' = 0x40, '[' = 0x5B) and of a-z ('`', '{') stay.
  EXPECT_EQ(to_lower("@[`{"), "@[`{");
  EXPECT_EQ(to_lower("Max_Leaf-Size.2"), "max_leaf-size.2");
  EXPECT_EQ(to_lower(""), "");
}

TEST(CoreStrings, ToLowerLeavesNonAsciiBytesAlone) {
  // UTF-8 "ÄÖÜ É" and "ΣΑ": multi-byte sequences are not letters A-Z, and must not be changed.
  EXPECT_EQ(to_lower("\xC3\x84\xC3\x96\xC3\x9C \xC3\x89"), "\xC3\x84\xC3\x96\xC3\x9C \xC3\x89");
  EXPECT_EQ(to_lower("A\xCE\xA3\xCE\x91Z"), "a\xCE\xA3\xCE\x91z");
  // Latin-1 capitals (0xC0 'À') are negative as char: not A-Z either.
  EXPECT_EQ(to_lower("\xC0\xDE"), "\xC0\xDE");
  // An embedded NUL is kept, with what follows it.
  const std::string with_nul("A\0B", 3);
  EXPECT_EQ(to_lower(with_nul), std::string("a\0b", 3));
}

TEST(CoreStrings, LowerCaseExtensionKeepsTheDot) {
  EXPECT_EQ(lower_case_extension("Out.EXR"), ".exr");
  EXPECT_EQ(lower_case_extension("image.png"), ".png");
  EXPECT_EQ(lower_case_extension("renders/Final.Pfm"), ".pfm");
  // Only the last extension counts, and a dotted directory is not an extension.
  EXPECT_EQ(lower_case_extension("archive.tar.GZ"), ".gz");
  EXPECT_EQ(lower_case_extension("DIR.X/Name.PNG"), ".png");
}

TEST(CoreStrings, LowerCaseExtensionIsEmptyWithoutOne) {
  EXPECT_EQ(lower_case_extension("output"), "");
  EXPECT_EQ(lower_case_extension("scenes.d/output"), "");
  EXPECT_EQ(lower_case_extension(".hidden"), "");
  EXPECT_EQ(lower_case_extension(""), "");
}

TEST(CoreStrings, JoinPutsTheSeparatorBetweenItems) {
  const std::vector<std::string> three{"brute", "bvh", "embree"};
  EXPECT_EQ(join(three), "brute, bvh, embree");
  EXPECT_EQ(join(three, "|"), "brute|bvh|embree");
  EXPECT_EQ(join(three, ""), "brutebvhembree");
  const std::vector<std::string> one{"only"};
  EXPECT_EQ(join(one, ", ", "(none)"), "only");
  // Empty items are items: the separators are still there.
  const std::vector<std::string> blanks{"", "", ""};
  EXPECT_EQ(join(blanks, "/"), "//");
}

TEST(CoreStrings, JoinOfNothingIsIfEmpty) {
  const std::vector<std::string> none;
  EXPECT_EQ(join(none), "");
  EXPECT_EQ(join(none, ", ", "(none)"), "(none)");
  // A single empty item is not "none".
  const std::vector<std::string> one_blank{""};
  EXPECT_EQ(join(one_blank, ", ", "(none)"), "");
}

}  // namespace
}  // namespace prism
