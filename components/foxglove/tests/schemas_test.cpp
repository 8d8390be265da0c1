// The Foxglove schema texts are self-contained: every struct once, defined before it is used.

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/foxglove/schemas.hpp"

namespace uavmot::foxglove {
namespace {

const std::string kIdlDir = build_paths::source_dir() + "/idl";

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

TEST(Schemas, ImageAnnotationsIsFlattenedWithDefinitionsBeforeUse) {
  const std::string text = schema_text(kImageAnnotationsSchema, kIdlDir);
  EXPECT_EQ(text.find("#include"), std::string::npos);
  for (const char* s : {"struct Time ", "struct Color ", "struct Point2 ", "enum PointsAnnotationType ", "struct CircleAnnotation ",
                        "struct PointsAnnotation ", "struct TextAnnotation ", "struct ImageAnnotations "}) {
    EXPECT_EQ(count(text, s), 1u) << s;
  }
  EXPECT_LT(text.find("struct Time "), text.find("struct CircleAnnotation "));
  EXPECT_LT(text.find("enum PointsAnnotationType "), text.find("struct PointsAnnotation "));
  EXPECT_LT(text.find("struct TextAnnotation "), text.find("struct ImageAnnotations "));
}

TEST(Schemas, ImagesAndUnknownNames) {
  EXPECT_NE(schema_text(kCompressedImageSchema, kIdlDir).find("struct CompressedImage "), std::string::npos);
  EXPECT_NE(schema_text(kRawImageSchema, kIdlDir).find("struct RawImage "), std::string::npos);
  EXPECT_THROW(schema_text("foxglove::SceneUpdate", kIdlDir), InputError);
  EXPECT_THROW(schema_text(kRawImageSchema, "/nonexistent"), InputError);
}

}  // namespace
}  // namespace uavmot::foxglove
