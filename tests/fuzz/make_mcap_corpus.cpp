// Writes the fuzzer's seed corpus: tiny valid recordings with each compression, one with
// metadata, and a crashed recorder's file without summary.
//   mcap_make_corpus OUT_DIR

#include <cstdio>
#include <filesystem>
#include <string>

#include "uavmot/mcap/writer.hpp"

int main(int argc, char** argv) {
  using namespace uavmot::mcap;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  std::filesystem::create_directories(out);
  const std::pair<const char*, Compression> kinds[] = {
      {"tiny_none.mcap", Compression::None}, {"tiny_lz4.mcap", Compression::Lz4}, {"tiny_zstd.mcap", Compression::Zstd}};
  for (const auto& [name, compression] : kinds) {
    WriterOptions options;
    options.compression = compression;
    options.chunk_size = 96;
    Writer writer(options);
    writer.open(out + "/" + name);
    const uint16_t schema = writer.add_schema("m::T", "omgidl", std::string("module m { struct T { long a; }; };"));
    const uint16_t a = writer.add_channel(schema, "a", "cdr", {{"topic", "a"}});
    const uint16_t b = writer.add_channel(0, "b", "cdr");
    if (compression == Compression::Zstd) writer.add_metadata({"recorder", {{"k", "v"}}});
    for (uint32_t i = 0; i < 8; ++i) {
      const uint8_t payload[8] = {0, 1, 0, 0, static_cast<uint8_t>(i), 0, 0, 0};
      writer.write(i % 2 ? b : a, i, 100 + 7 * i - (i % 3), 100 + 7 * i, payload, sizeof payload);
    }
    if (compression == Compression::Lz4) {
      // The crashed-recorder shape: chunks and definitions, no DataEnd, summary or footer.
      writer.flush();
      std::filesystem::copy_file(writer.temporary_path(), out + "/tiny_crashed_no_summary.partial",
                                 std::filesystem::copy_options::overwrite_existing);
    }
    writer.close();
  }
  return 0;
}
