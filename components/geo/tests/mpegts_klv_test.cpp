#include "uavmot/geo/mpegts_klv.hpp"

#include <random>

#include <gtest/gtest.h>

#include "test_data.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/geo/misb0601.hpp"

namespace uavmot::geo {
namespace {

using V = std::vector<std::uint8_t>;

TEST(MpegTsKlv, AphillClip) {
  const MpegTsKlv ts = read_mpegts_klv(test::aphill_ts_path());
  // ffprobe: video PID 0x100 (H.264), data PID 0x101 (KLVA); the KLV packets' PTS start at 126000
  // and step 3003; `ffmpeg -map 0:d -c copy -f data` writes 26592 bytes = 48 x 554.
  ASSERT_EQ(ts.klv.size(), 48u);
  EXPECT_EQ(ts.metadata_pids, std::vector<std::uint16_t>{0x101});
  EXPECT_EQ(ts.video_pid, 0x100);
  std::size_t total = 0;
  for (std::size_t i = 0; i < ts.klv.size(); ++i) {
    EXPECT_EQ(ts.klv[i].pts, 126000 + 3003 * static_cast<std::int64_t>(i)) << i;
    EXPECT_EQ(ts.klv[i].pid, 0x101);
    total += ts.klv[i].bytes.size();
  }
  EXPECT_EQ(total, 26592u);
  // The video is field-coded: 96 PES (one a field), first PTS 129003 (ffprobe's start_pts).
  EXPECT_EQ(ts.video_pes_pts.size(), 96u);
  EXPECT_EQ(ts.first_video_pts, 129003);
  EXPECT_EQ(ts.counts.resync_bytes, 0u);
  EXPECT_EQ(ts.counts.bad_packets, 0u);
  EXPECT_EQ(ts.counts.bad_pes, 0u);
  EXPECT_EQ(ts.counts.truncated_pes, 0u);
  EXPECT_EQ(ts.counts.truncated_klv, 0u);
  EXPECT_EQ(ts.counts.non_klv_bytes, 0u);
}

TEST(MpegTsKlv, GarbageIsAnInputError) {
  EXPECT_THROW(parse_mpegts_klv(V{}), InputError);
  std::mt19937 rng(7);
  V garbage(100000);
  for (auto& b : garbage) b = static_cast<std::uint8_t>(rng() % 0x47);  // never a sync byte
  try {
    parse_mpegts_klv(garbage, "garbage.ts");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("garbage.ts: not an MPEG transport stream"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_mpegts_klv("/nonexistent/clip.ts"), InputError);
}

TEST(MpegTsKlv, TruncatedClipKeepsOnlyWholeUnits) {
  const V clip = test::read_bytes(test::aphill_ts_path());
  ASSERT_GT(clip.size(), 100000u);
  for (const std::size_t cut : {std::size_t{188}, std::size_t{5000}, std::size_t{123457}, clip.size() / 2, clip.size() - 1}) {
    const MpegTsKlv ts = parse_mpegts_klv(std::span<const std::uint8_t>(clip.data(), cut));
    EXPECT_LE(ts.klv.size(), 48u);
    for (const KlvPacket& p : ts.klv) EXPECT_EQ(p.bytes.size(), 554u) << "cut " << cut;
  }
}

TEST(MpegTsKlv, CorruptedClipIsSkippedNotCrashed) {
  const V clip = test::read_bytes(test::aphill_ts_path());
  std::mt19937 rng(2024);
  for (int round = 0; round < 20; ++round) {
    V damaged = clip;
    for (int i = 0; i < 300; ++i) damaged[rng() % damaged.size()] = static_cast<std::uint8_t>(rng());
    // Also drop a run of bytes: every later packet is out of sync until the reader finds it again.
    const std::size_t from = rng() % (damaged.size() - 1000);
    damaged.erase(damaged.begin() + static_cast<std::ptrdiff_t>(from), damaged.begin() + static_cast<std::ptrdiff_t>(from + 1 + rng() % 900));
    const MpegTsKlv ts = parse_mpegts_klv(damaged);
    EXPECT_GT(ts.counts.resync_bytes, 0u);
    for (const KlvPacket& p : ts.klv) {
      try {
        (void)decode_uas_metadata(p.bytes);
      } catch (const InputError&) {
        // a damaged unit: reported, never undefined behaviour
      }
    }
  }
}

// A small transport stream built by hand: PAT, a PMT declaring stream_type 0x15 (metadata in
// PES), and one metadata PES (stream_id 0xFC) whose payload is a 5-byte metadata AU cell header
// and the hand-made ST 0601 packet, split over several TS packets.
class TsBuilder {
 public:
  void packet(std::uint16_t pid, bool unit_start, V payload) {
    V p = {0x47, static_cast<std::uint8_t>((unit_start ? 0x40 : 0) | (pid >> 8)), static_cast<std::uint8_t>(pid & 0xFF),
           static_cast<std::uint8_t>(0x10 | (cc_[pid]++ & 0x0F))};
    if (payload.size() < 184) {  // stuff with an adaptation field
      p[3] |= 0x20;
      const std::size_t stuffing = 184 - payload.size() - 1;
      p.push_back(static_cast<std::uint8_t>(stuffing));
      if (stuffing > 0) {
        p.push_back(0x00);
        p.insert(p.end(), stuffing - 1, 0xFF);
      }
    }
    p.insert(p.end(), payload.begin(), payload.end());
    bytes.insert(bytes.end(), p.begin(), p.end());
  }
  void section(std::uint16_t pid, V table) {  // CRC left zero: the reader does not check it
    table.insert(table.end(), {0, 0, 0, 0});
    table[1] = static_cast<std::uint8_t>(0xB0 | ((table.size() - 3) >> 8));
    table[2] = static_cast<std::uint8_t>((table.size() - 3) & 0xFF);
    table.insert(table.begin(), 0x00);  // pointer_field
    packet(pid, true, table);
  }
  void pes(std::uint16_t pid, const V& pes) {
    for (std::size_t i = 0; i < pes.size(); i += 184) {
      packet(pid, i == 0, V(pes.begin() + static_cast<std::ptrdiff_t>(i), pes.begin() + static_cast<std::ptrdiff_t>(std::min(pes.size(), i + 184))));
    }
  }
  V bytes;

 private:
  std::uint8_t cc_[8192] = {};
};

V metadata_pes(const V& klv, std::uint64_t pts) {
  V payload = {0x00, 0x00, 0x80, 0x00, static_cast<std::uint8_t>(klv.size())};  // AU cell header
  payload.insert(payload.end(), klv.begin(), klv.end());
  V pes = {0x00, 0x00, 0x01, 0xFC};
  const std::size_t length = 3 + 5 + payload.size();
  pes.push_back(static_cast<std::uint8_t>(length >> 8));
  pes.push_back(static_cast<std::uint8_t>(length & 0xFF));
  pes.insert(pes.end(), {0x84, 0x80, 0x05});  // PTS only
  pes.push_back(static_cast<std::uint8_t>(0x21 | ((pts >> 29) & 0x0E)));
  pes.push_back(static_cast<std::uint8_t>(pts >> 22));
  pes.push_back(static_cast<std::uint8_t>(0x01 | ((pts >> 14) & 0xFE)));
  pes.push_back(static_cast<std::uint8_t>(pts >> 7));
  pes.push_back(static_cast<std::uint8_t>(0x01 | ((pts << 1) & 0xFE)));
  pes.insert(pes.end(), payload.begin(), payload.end());
  return pes;
}

TEST(MpegTsKlv, SynchronousMetadataStreamType0x15) {
  const V klv = test::from_hex(test::kHandMade0601Hex);
  TsBuilder ts;
  ts.section(0x0000, {0x00, 0, 0, 0x00, 0x01, 0xC1, 0x00, 0x00, 0x00, 0x01, 0xF0, 0x00});  // program 1 -> PMT PID 0x1000
  ts.section(0x1000, {0x02, 0, 0, 0x00, 0x01, 0xC1, 0x00, 0x00, 0xE1, 0x01, 0xF0, 0x00,   // PCR PID 0x101, no program info
                      0x15, 0xE1, 0x01, 0xF0, 0x00});                                    // stream_type 0x15 on PID 0x101
  ts.pes(0x0101, metadata_pes(klv, (std::uint64_t{1} << 33) - 1000));  // just before the PTS wraps
  ts.pes(0x0101, metadata_pes(klv, 2003));                             // and just after
  const MpegTsKlv out = parse_mpegts_klv(ts.bytes);
  ASSERT_EQ(out.klv.size(), 2u);
  EXPECT_EQ(out.klv[0].bytes, klv);
  EXPECT_EQ(out.klv[0].pts, (std::int64_t{1} << 33) - 1000);
  EXPECT_EQ(out.klv[1].pts, (std::int64_t{1} << 33) + 2003);  // unwrapped: 3003 ticks later
  EXPECT_EQ(out.counts.non_klv_bytes, 10u);  // the two AU cell headers
  EXPECT_EQ(decode_st0601(out.klv[1].bytes).checksum_ok, true);
  EXPECT_FALSE(out.first_video_pts.has_value());
}

TEST(MpegTsKlv, StreamWithoutPmtIsClassifiedByStreamId) {
  const V klv = test::from_hex(test::kHandMade0601Hex);
  TsBuilder ts;
  ts.pes(0x0200, metadata_pes(klv, 90000));
  const MpegTsKlv out = parse_mpegts_klv(ts.bytes);
  ASSERT_EQ(out.klv.size(), 1u);
  EXPECT_EQ(out.klv[0].pts, 90000);
}

TEST(MpegTsKlv, CutPesCountsAndKeepsWholeUnits) {
  const V klv = test::from_hex(test::kHandMade0601Hex);
  TsBuilder ts;
  V pes = metadata_pes(klv, 90000);
  pes.erase(pes.end() - 20, pes.end());  // lose the end: PES_packet_length now promises more than there is
  ts.pes(0x0200, pes);
  const MpegTsKlv out = parse_mpegts_klv(ts.bytes);
  EXPECT_TRUE(out.klv.empty());
  EXPECT_EQ(out.counts.truncated_pes, 1u);
  EXPECT_EQ(out.counts.truncated_klv, 1u);
}

}  // namespace
}  // namespace uavmot::geo
