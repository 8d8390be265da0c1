#include "uavmot/core/segmentation_method.hpp"

#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>
#include <utility>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {

TEST(SegmentationMethod, EveryMethodParsesFromItsName) {
  for (SegmentationMethod m : kSegmentationMethods) EXPECT_EQ(parse_segmentation_method(to_string(m)), m);
  EXPECT_EQ(segmentation_method_names().size(), kSegmentationMethods.size());
}

TEST(SegmentationMethod, ListPositionIsTheWireNumber) {
  for (size_t i = 0; i < kSegmentationMethods.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(kSegmentationMethods[i]), i);
    EXPECT_TRUE(is_segmentation_method(i));
  }
  EXPECT_FALSE(is_segmentation_method(kSegmentationMethods.size()));
  // The paper's methods keep their numbers (recordings and the downlink carry them).
  EXPECT_EQ(static_cast<int>(SegmentationMethod::Clustering), 0);
  EXPECT_EQ(static_cast<int>(SegmentationMethod::Fusion), 4);
}

// The list is generated from the IDL's enum (cmake/segmentation_methods_from_idl.cmake): read the
// enum here another way and compare, names upper-cased, in order.
TEST(SegmentationMethod, ListIsTheIdlEnum) {
  const std::string path = build_paths::source_dir() + "/idl/segmentation.idl";
  std::ifstream idl(path);
  ASSERT_TRUE(idl) << path;
  std::stringstream text;
  text << idl.rdbuf();
  std::string source = std::regex_replace(text.str(), std::regex(R"(//[^\n]*)"), "");
  source = std::regex_replace(source, std::regex(R"(/\*[\s\S]*?\*/)"), "");
  std::smatch block;
  ASSERT_TRUE(std::regex_search(source, block, std::regex(R"(enum\s+SegmentationMethod\s*\{([^}]*)\})")));
  std::vector<std::string> idl_names;
  const std::string body = block[1];
  const std::regex enumerator(R"([A-Za-z_0-9]+)");
  for (std::sregex_iterator it(body.begin(), body.end(), enumerator), end; it != end; ++it) {
    idl_names.push_back(it->str());
  }
  std::vector<std::string> names;
  for (std::string name : segmentation_method_names()) {
    for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    names.push_back(name);
  }
  EXPECT_EQ(names, idl_names);
}

// The paper's methods keep their names (configs) and numbers (recordings, the downlink).
TEST(SegmentationMethod, PaperMethodsKeepTheirNamesAndNumbers) {
  const std::vector<std::pair<SegmentationMethod, std::string>> paper = {
      {SegmentationMethod::Clustering, "clustering"}, {SegmentationMethod::Korn, "korn"},
      {SegmentationMethod::Morphological, "morphological"}, {SegmentationMethod::Lbp, "lbp"},
      {SegmentationMethod::Fusion, "fusion"}};
  ASSERT_GE(kSegmentationMethods.size(), paper.size());
  for (size_t i = 0; i < paper.size(); ++i) {
    EXPECT_EQ(kSegmentationMethods[i], paper[i].first) << i;
    EXPECT_EQ(to_string(paper[i].first), paper[i].second) << i;
  }
}

TEST(SegmentationMethod, UnknownNameNamesTheChoices) {
  try {
    parse_segmentation_method("sobol");
    FAIL() << "no throw";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("sobol"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(segmentation_method_choices()), std::string::npos);
  }
  EXPECT_EQ(segmentation_method_choices().rfind("clustering, korn", 0), 0u);
}

}  // namespace
}  // namespace uavmot
