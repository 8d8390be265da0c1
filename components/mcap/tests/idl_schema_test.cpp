// flatten_idl: schemas carry self-contained IDL text.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/idl_schema.hpp"

namespace uavmot::mcap {
namespace {

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

TEST(FlattenIdl, InlinesIncludesOnceAndKeepsTheRest) {
  const std::string tracks = flatten_idl(build_paths::source_dir() + "/idl/tracks.idl");
  EXPECT_EQ(tracks.find("#include"), std::string::npos);
  EXPECT_EQ(count(tracks, "struct OrientedBox"), 1u);
  EXPECT_EQ(count(tracks, "struct TrackList"), 1u);
  EXPECT_LT(tracks.find("struct OrientedBox"), tracks.find("struct Track "));  // definitions before use
}

TEST(FlattenIdl, DiamondIncludesAppearOnce) {
  const auto dir = test::temp_dir("idl");
  std::ofstream(dir / "base.idl") << "struct Base { long a; };\n";
  std::ofstream(dir / "left.idl") << "#include \"base.idl\"\nstruct Left { Base b; };\n";
  std::ofstream(dir / "right.idl") << "#include \"base.idl\"\nstruct Right { Base b; };\n";
  std::ofstream(dir / "top.idl") << "#include \"left.idl\"\n#include \"right.idl\"\nstruct Top { Left l; Right r; };\n";
  const std::string top = flatten_idl((dir / "top.idl").string());
  EXPECT_EQ(count(top, "struct Base"), 1u);
  EXPECT_EQ(count(top, "struct Top"), 1u);
  std::ofstream(dir / "broken.idl") << "#include \"nowhere.idl\"\n";
  try {
    flatten_idl((dir / "broken.idl").string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.idl:1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(flatten_idl((dir / "absent.idl").string()), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace uavmot::mcap
