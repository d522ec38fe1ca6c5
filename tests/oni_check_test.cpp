// The .oni structure check (src/capture/oni_check.*) and the frame checks of
// DepthStream::to_frame: the bundled recordings pass, our reader agrees with
// OpenNI2's player on every frame, and each crafted inconsistency is refused with
// one line naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "../src/capture/depth_stream.hpp"
#include "../src/capture/oni_16zt.hpp"
#include "../src/capture/oni_check.hpp"
#include "expect_error.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/error.hpp"
#include "oni_test_bytes.hpp"
#include "openni2_player.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

using namespace test;
using namespace std::string_literals;

std::span<const std::uint8_t> as_bytes(const std::string& bytes) {
  return {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()};
}

detail::OniRecordingFacts check(const std::string& bytes) { return detail::check_oni_recording(as_bytes(bytes), "x.oni"); }

class OniCheckTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    synthetic_ = new std::string(read_bytes(kRecordingsDir / "synthetic_tabletop.oni"));
    mosd_ = new std::string(read_bytes(kRecordingsDir / "mosd_scenes.oni"));
  }
  static void TearDownTestSuite() {
    delete synthetic_;
    delete mosd_;
  }
  // A copy of the smaller bundled recording (62 real Kinect frames, 4.5 MB).
  static std::string recording() { return *mosd_; }

  static void expect_refused(const std::string& bytes, std::initializer_list<std::string> parts) {
    std::vector<std::string> all(parts);
    all.push_back("x.oni: ");
    test::expect_lccp_error([&] { check(bytes); }, all);
  }

  static inline std::string* synthetic_ = nullptr;
  static inline std::string* mosd_ = nullptr;
};

// --- what must pass -----------------------------------------------------------------

TEST_F(OniCheckTest, BundledRecordingsPass) {
  const detail::OniRecordingFacts synthetic = check(*synthetic_);
  EXPECT_EQ(synthetic.frames, 60u);
  EXPECT_EQ(synthetic.width, 640);
  EXPECT_EQ(synthetic.height, 480);
  EXPECT_EQ(synthetic.pixel_format, 100);
  const detail::OniRecordingFacts mosd = detail::check_oni_file(kRecordingsDir / "mosd_scenes.oni");
  EXPECT_EQ(mosd.frames, 62u);
  EXPECT_EQ(mosd.width, 640);
}

TEST_F(OniCheckTest, BytesAfterTheEndRecordAreNeverRead) {
  EXPECT_EQ(check(recording() + std::string(1000, '\xab')).frames, 62u);
}

// Every frame of `path` from our reader equals OpenNI2's player's: pixels,
// timestamp, size and fields of view; returns our frames' depth.
std::vector<std::vector<std::uint16_t>> expect_openni2s_frames(const std::filesystem::path& path, std::size_t expected) {
  std::vector<std::vector<std::uint16_t>> depth;
  const auto ours = open_recording(path);
  EXPECT_EQ(ours->frame_count(), expected);
  OpenNI2Player theirs(path);
  EXPECT_EQ(theirs.frames(), static_cast<int>(expected));
  for (std::size_t i = 0; i < expected; ++i) {
    const std::optional<Frame> a = ours->next({});
    const std::optional<Frame> b = theirs.next();
    if (!(a && a->depth && b && b->depth)) {
      ADD_FAILURE() << "frame " << i << " missing";
      break;
    }
    EXPECT_EQ(a->index, i);
    EXPECT_EQ(a->timestamp_us, b->timestamp_us) << "frame " << i;
    EXPECT_EQ(a->depth->width, b->depth->width);
    EXPECT_EQ(a->depth->height, b->depth->height);
    EXPECT_EQ(a->depth->horizontal_fov_rad, b->depth->horizontal_fov_rad);
    EXPECT_EQ(a->depth->vertical_fov_rad, b->depth->vertical_fov_rad);
    EXPECT_EQ(a->depth->depth_mm, b->depth->depth_mm) << "frame " << i;
    depth.push_back(a->depth->depth_mm);
  }
  EXPECT_FALSE(ours->next({}).has_value());
  return depth;
}

// The recording with every 16zT frame stored uncompressed (codec NONE). The records
// after the first frame move, so every position that names a record (undo
// positions, the stream's seek table position, the seek table's entries) moves too.
std::string uncompressed_copy(const std::string& bytes) {
  const detail::OniRecordingFacts facts = check(bytes);
  std::vector<std::uint16_t> pixels(std::size_t(facts.width) * facts.height);
  std::map<std::uint64_t, std::uint64_t> moved{{0, 0}};
  std::string out = bytes.substr(0, kOniFileHeaderBytes);
  for (const OniRecord& r : oni_records(bytes)) {
    moved[r.offset] = out.size();
    std::string record = bytes.substr(r.offset, r.fields_size);
    if (r.type == kOniNewData) {
      EXPECT_EQ(detail::decode_16zt(as_bytes(bytes).subspan(r.offset + r.fields_size, r.payload_size), pixels), std::nullopt);
      put_u32(record, 16, static_cast<std::uint32_t>(2 * pixels.size()));
      record.append(reinterpret_cast<const char*>(pixels.data()), 2 * pixels.size());
    } else {
      record += bytes.substr(r.offset + r.fields_size, r.payload_size);
    }
    out += record;
  }
  for (const OniRecord& r : oni_records(out)) {
    put_u64(out, r.offset + 20, moved.at(get_u64(out, r.offset + 20)));
    if (r.type == kOniNodeAdded) {
      const std::size_t after_name = r.offset + 32 + get_u32(out, r.offset + 28);
      put_u32(out, after_name + 4, get_u32("NONE", 0));
      put_u64(out, after_name + 28, moved.at(get_u64(out, after_name + 28)));
    }
    for (std::size_t e = 0; r.type == kOniSeekTable && e < r.payload_size / 20; ++e) {
      const std::size_t position = r.offset + r.fields_size + 20 * e + 12;
      put_u64(out, position, moved.at(get_u64(out, position)));
    }
  }
  EXPECT_EQ(check(out).codec, get_u32("NONE", 0));
  return out;
}

// Both bundled recordings replay in full through open_recording, our reader,
// and every frame equals what OpenNI2's player hands out.
TEST_F(OniCheckTest, OurReaderGivesOpenNI2sFramesOnEveryFrameOfBothRecordings) {
  for (const char* name : {"mosd_scenes.oni", "synthetic_tabletop.oni"}) {
    SCOPED_TRACE(name);
    expect_openni2s_frames(kRecordingsDir / name, std::string(name) == "mosd_scenes.oni" ? 62u : 60u);
  }
}

// The same recording stored uncompressed replays with the same pixels, as from OpenNI2.
TEST_F(OniCheckTest, AnUncompressedRecordingGivesTheSameFramesAsOpenNI2s) {
  const std::filesystem::path dir = scratch_dir("oni_check");
  write_bytes(dir / "compressed.oni", recording());
  write_bytes(dir / "uncompressed.oni", uncompressed_copy(recording()));
  EXPECT_EQ(expect_openni2s_frames(dir / "uncompressed.oni", 62), expect_openni2s_frames(dir / "compressed.oni", 62));
}

// Depth in 100 um units comes out in whole millimetres, rounded, as from OpenNI2
// through DepthStream.
TEST_F(OniCheckTest, DepthIn100umUnitsIsRoundedToMillimetresAsFromOpenNI2) {
  const std::filesystem::path dir = scratch_dir("oni_check");
  std::string bytes = recording();
  write_bytes(dir / "mm.oni", bytes);
  put_u64(bytes, oni_property(bytes, "oniPixelFormat").property_data, 101);
  write_bytes(dir / "100um.oni", bytes);
  const auto millimetres = expect_openni2s_frames(dir / "mm.oni", 62);
  const auto rounded = expect_openni2s_frames(dir / "100um.oni", 62);
  ASSERT_EQ(rounded.size(), millimetres.size());
  for (std::size_t i = 0; i < rounded.size(); ++i) {
    for (std::size_t p = 0; p < rounded[i].size(); p += 997) {
      ASSERT_EQ(rounded[i][p], (millimetres[i][p] + 5) / 10) << "frame " << i << " pixel " << p;
    }
  }
}

// --- the crafted recordings that crashed `lccp replay` -------------------------------

TEST_F(OniCheckTest, RequiredFrameSizeOfOneIsRefused) {
  std::string bytes = recording();
  put_u64(bytes, oni_property(bytes, "oniRequiredFrameSize").property_data, 1);
  expect_refused(bytes, {"required frame size 1", "640x480"});
}

TEST_F(OniCheckTest, PixelFormat200IsRefused) {
  std::string bytes = recording();
  put_u64(bytes, oni_property(bytes, "oniPixelFormat").property_data, 200);
  expect_refused(bytes, {"pixel format 200", "not a depth format"});
}

TEST_F(OniCheckTest, Mode65535x65535IsRefused) {
  std::string bytes = recording();
  const std::size_t mode = oni_property(bytes, "xnMapOutputMode").property_data;
  put_u32(bytes, mode, 65535);
  put_u32(bytes, mode + 4, 65535);
  expect_refused(bytes, {"depth mode 65535x65535", "4096"});
}

TEST_F(OniCheckTest, ModeLargerThanOpenNI2sPlayerBufferIsRefused) {
  std::string bytes = recording();
  const std::size_t mode = oni_property(bytes, "xnMapOutputMode").property_data;
  put_u32(bytes, mode, 2048);
  put_u32(bytes, mode + 4, 2048);
  expect_refused(bytes, {"2048x2048", "player frame buffer"});
}

// --- file and record headers ---------------------------------------------------------

TEST_F(OniCheckTest, FileHeaderIsChecked) {
  expect_refused("", {"24-byte"});
  expect_refused("NI10", {"24-byte"});
  std::string bytes = recording();
  bytes[2] = '2';
  expect_refused(bytes, {"magic NI10"});
  bytes = recording();
  bytes[6] = 0;  // version 1.0.0.0: the 32-bit record layout
  expect_refused(bytes, {"version 1.0.0.0"});
  bytes = recording();
  put_u32(bytes, 20, 0xFFFFFFFF);  // max node id: the player allocates this + 1 entries
  expect_refused(bytes, {"node ids up to 4294967295"});
}

TEST_F(OniCheckTest, RecordSizesAreCheckedAgainstTheFileAndThePlayersBuffer) {
  const std::string original = recording();
  const OniRecord first_property = oni_property(original, "oniRequiredFrameSize");
  std::string bytes = original;
  put_u32(bytes, first_property.offset + 12, 0x7FFFFFFF);  // fields size: read into a fixed buffer by the player
  expect_refused(bytes, {"record at byte " + std::to_string(first_property.offset), "fields size 2147483647"});
  bytes = original;
  put_u32(bytes, first_property.offset + 12, 12);  // shorter than the header itself
  expect_refused(bytes, {"fields size 12"});
  const OniRecord frame = oni_records_of(original, kOniNewData)[3];
  bytes = original;
  put_u32(bytes, frame.offset + 16, 0xFFFFFF00);  // payload size past the end of the file
  expect_refused(bytes, {"runs past the end of the file"});
  bytes = original;
  put_u32(bytes, frame.offset, 0);  // no magic
  expect_refused(bytes, {"no record magic"});
}

TEST_F(OniCheckTest, UnknownAndLegacyRecordsAreRefused) {
  const std::string original = recording();
  const OniRecord ready = oni_records_of(original, kOniNodeStateReady).at(0);
  std::string bytes = original;
  put_u32(bytes, ready.offset + 4, 0x42);
  expect_refused(bytes, {"unknown record type 66"});
  bytes = original;
  put_u32(bytes, oni_records_of(original, kOniNodeAdded).at(0).offset + 4, 0x0C);
  expect_refused(bytes, {"legacy NodeAdded"});
}

TEST_F(OniCheckTest, TruncatedRecordingsAreRefusedWherever) {
  const std::string original = recording();
  std::vector<std::size_t> cuts;
  for (const OniRecord& r : oni_records(original)) {
    if (cuts.size() < 30) cuts.insert(cuts.end(), {r.offset, r.offset + 5, r.offset + 27, r.offset + r.fields_size - 1});
  }
  for (std::size_t i = 1; i < 20; ++i) cuts.push_back(original.size() * i / 20);
  cuts.push_back(original.size() - 1);
  for (const std::size_t cut : cuts) {
    SCOPED_TRACE("cut at " + std::to_string(cut));
    expect_refused(original.substr(0, cut), {});
  }
}

// --- the stream's declaration --------------------------------------------------------

TEST_F(OniCheckTest, AStreamOtherThanDepthIsRefused) {
  std::string bytes = recording();
  const OniRecord added = oni_records_of(bytes, kOniNodeAdded).at(0);
  put_u32(bytes, added.offset + 28 + 4 + 6, 5);  // after the name "Depth\0": node type 5, IR
  expect_refused(bytes, {"no depth stream"});
}

TEST_F(OniCheckTest, DepthCodecMustBe16zTOrNone) {
  std::string bytes = recording();
  const OniRecord added = oni_records_of(bytes, kOniNodeAdded).at(0);
  put_u32(bytes, added.offset + 28 + 4 + 6 + 4, 0);  // codec NULL: the player would decode with no codec
  expect_refused(bytes, {"codec"});
}

TEST_F(OniCheckTest, DeclaredFrameCountMustMatch) {
  std::string bytes = recording();
  const OniRecord added = oni_records_of(bytes, kOniNodeAdded).at(0);
  put_u32(bytes, added.offset + 28 + 4 + 6 + 8, 0xFFFFFFFF);  // as an unfinished Recorder file says
  expect_refused(bytes, {"declares 4294967295 frames but holds 62"});
}

TEST_F(OniCheckTest, PropertyFieldsAreChecked) {
  const std::string original = recording();
  const OniRecord format = oni_property(original, "oniPixelFormat");
  std::string bytes = original;
  bytes[format.offset + 32 + format.property.size()] = 'X';  // the name's NUL
  expect_refused(bytes, {"property name is not one NUL-terminated string"});
  bytes = original;
  bytes[format.offset + 32 + 3] = '\xFF';  // XnLib's name hash indexes its table with a negative char
  expect_refused(bytes, {"property name holds a byte outside printable ASCII"});
  bytes = original;
  put_u32(bytes, format.property_data - 4, 0);  // data size 0, the value still there
  expect_refused(bytes, {"property 'oniPixelFormat' with bytes after its data"});
  bytes = original;
  bytes.erase(format.property_data + 4, 4);  // an int property of 4 bytes: the player reads 8
  put_u32(bytes, format.property_data - 4, 4);
  put_u32(bytes, format.offset + 12, format.fields_size - 4);
  expect_refused(bytes, {"number property 'oniPixelFormat' of 4 bytes"});
  const OniRecord fov = oni_property(original, "xnFOV");
  bytes = original;
  put_u64(bytes, fov.property_data, 0x7FF8000000000000ull);  // NaN
  expect_refused(bytes, {"horizontal field of view"});
  bytes = original;
  put_u32(bytes, oni_property(original, "xnCropping").property_data, 1);
  expect_refused(bytes, {"cropped depth"});
  bytes = original;
  bytes[oni_property(original, "xnCropping").offset + 32 + 2] = 'S';  // "xnSropping": an unknown property
  expect_refused(bytes, {"no xnCropping property", "drop every frame"});
}

// --- frames and the seek table -------------------------------------------------------

TEST_F(OniCheckTest, FrameNumbersTimestampsAndUndoPositionsAreChecked) {
  const std::string original = recording();
  const std::vector<OniRecord> frames = oni_records_of(original, kOniNewData);
  std::string bytes = original;
  put_u32(bytes, frames[5].offset + 28 + 8, 9);  // frame number
  expect_refused(bytes, {"frame 5", "frame number 9, expected 6"});
  bytes = original;
  put_u64(bytes, frames[5].offset + 28, 1);  // timestamp
  expect_refused(bytes, {"frame 5", "timestamp goes backwards"});
  bytes = original;
  put_u64(bytes, frames[5].offset + 20, 12345);  // undo position
  expect_refused(bytes, {"frame 5", "undo position 12345"});
}

TEST_F(OniCheckTest, SeekTableMustPointAtEveryFrame) {
  const std::string original = recording();
  const OniRecord table = oni_records_of(original, kOniSeekTable).at(0);
  std::string bytes = original;
  put_u64(bytes, table.offset + 28 + 3 * 20 + 12, 1234);  // entry 3's position
  expect_refused(bytes, {"seek table", "entry 3"});
  bytes = original;
  const OniRecord added = oni_records_of(original, kOniNodeAdded).at(0);
  put_u64(bytes, added.offset + added.fields_size - 8, 999);  // the stream's seek table position
  expect_refused(bytes, {"seek table at byte 999"});
}

TEST_F(OniCheckTest, Damaged16zTDataIsRefused) {
  const std::string original = recording();
  const OniRecord frame = oni_records_of(original, kOniNewData)[7];
  const std::size_t payload = frame.offset + frame.fields_size;
  const std::uint32_t table_size = get_u32(original, payload) & 0xFFFF;
  std::string bytes = original;
  bytes[payload + 2 + 2 * table_size] = static_cast<char>(table_size & 0xFF);  // first index: past the table
  bytes[payload + 2 + 2 * table_size + 1] = static_cast<char>(table_size >> 8);
  expect_refused(bytes, {"frame 7", "past its table"});
  bytes = original;
  append_to_payload(bytes, frame, "\xFF");  // a long step announced by the last byte
  expect_refused(bytes, {"frame 7", "ends inside a step"});
}

// --- the 16zT decoder on hand-made streams --------------------------------------------

std::string stream16zt(std::vector<std::uint16_t> table, std::uint16_t first, const std::string& steps) {
  std::string bytes;
  const auto put16 = [&](std::uint16_t v) { bytes += {static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)}; };
  put16(static_cast<std::uint16_t>(table.size()));
  for (const std::uint16_t v : table) put16(v);
  put16(first);
  return bytes + steps;
}

std::optional<std::string> decode(const std::string& bytes, std::vector<std::uint16_t>& out) {
  return detail::decode_16zt(as_bytes(bytes), out);
}

TEST(Decode16zT, EveryKindOfStep) {
  // index 0 -> 10; 0x65: -(6-6) -> 10, -(5-6) -> 20; 0xE1: 20 twice; FF 00 02: index 2 -> 30;
  // 0x7D: -(7-6) -> 20, D ends the byte; FF C1: -(0xC1-192) -> 10
  const std::string bytes = stream16zt({10, 20, 30}, 0, "\x65\xE1\xFF\x00\x02\x7D\xFF\xC1"s);
  std::vector<std::uint16_t> out(8);
  ASSERT_EQ(decode(bytes, out), std::nullopt);
  EXPECT_EQ(out, (std::vector<std::uint16_t>{10, 10, 20, 20, 20, 30, 20, 10}));
}

TEST(Decode16zT, EveryOverrunIsReported) {
  std::vector<std::uint16_t> out(4);
  EXPECT_EQ(decode("", out), "16zT data shorter than its table size");
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "").substr(0, 5), out), std::nullopt);     // table cut short
  EXPECT_NE(decode(stream16zt({1, 2}, 2, "\xE1\x66"s), out)->find("past its table"), std::string::npos);
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "\x6F"s), out)->find("ends inside a step"), std::string::npos);
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "\xFF\x01"s), out)->find("ends inside a step"), std::string::npos);
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "\x66\x66\x66"s), out)->find("more than 4 pixels"), std::string::npos);
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "\xE1"s), out)->find("3 of 4 pixels"), std::string::npos);
  EXPECT_NE(decode(stream16zt({1, 2}, 0, "\x76"s), out)->find("past its table"), std::string::npos);  // 0 - 1 = 65535
  EXPECT_NE(decode(stream16zt({}, 0, ""), out)->find("past its table"), std::string::npos);
}

// --- DepthStream::to_frame's checks ------------------------------------------------------

detail::DepthFrameLayout vga() {
  detail::DepthFrameLayout f;
  f.pixel_format = 100;
  f.width = f.mode_width = 640;
  f.height = f.mode_height = 480;
  f.stride_bytes = 1280;
  f.data_bytes = 640 * 480 * 2;
  f.has_data = true;
  return f;
}

TEST(DepthFrameChecks, AFrameThatFitsItsDataPasses) {
  EXPECT_EQ(detail::depth_frame_problem(vga()), std::nullopt);
  detail::DepthFrameLayout f = vga();
  f.pixel_format = 101;
  f.stride_bytes = 1300;
  f.data_bytes = 1300 * 479 + 1280;
  EXPECT_EQ(detail::depth_frame_problem(f), std::nullopt);
}

TEST(DepthFrameChecks, EachCrashingDeclarationIsRefused) {
  detail::DepthFrameLayout f = vga();
  f.data_bytes = 1;  // the file's required frame size of 1
  EXPECT_NE(detail::depth_frame_problem(f)->find("holds 1 bytes"), std::string::npos);
  f = vga();
  f.pixel_format = 200;
  EXPECT_NE(detail::depth_frame_problem(f)->find("pixel format 200"), std::string::npos);
  f = vga();
  f.width = f.height = f.mode_width = f.mode_height = 65535;
  EXPECT_NE(detail::depth_frame_problem(f)->find("65535x65535 outside"), std::string::npos);
  f = vga();
  f.width = 320;
  EXPECT_NE(detail::depth_frame_problem(f)->find("differs from the stream's mode 640x480"), std::string::npos);
  f = vga();
  f.stride_bytes = 0;  // what OpenNI2's player sets for an unknown pixel format
  EXPECT_NE(detail::depth_frame_problem(f)->find("row stride 0"), std::string::npos);
  f = vga();
  f.has_data = false;
  EXPECT_NE(detail::depth_frame_problem(f)->find("holds 0 bytes"), std::string::npos);
  f = vga();
  f.width = f.mode_width = -640;
  EXPECT_NE(detail::depth_frame_problem(f), std::nullopt);
}

}  // namespace
}  // namespace lccp
