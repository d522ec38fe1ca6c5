// `lccp replay` on damaged .oni recordings, through the release binary: the
// crafted recordings that crashed it (and OpenNI2's file driver) before the
// structure check, and 200 deterministic mutations of a small recording. Each
// run must end by itself, without a signal, in exit 0 or in exit 1 with exactly
// one "lccp: error:" line.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "oni_test_bytes.hpp"
#include "test_files.hpp"

namespace lccp {
namespace {

using namespace test;
using Clock = std::chrono::steady_clock;

constexpr int kRunTimeoutSeconds = 40;   // a hang shows as a timeout (exit 124)
constexpr double kMaxRunSeconds = 30.0;  // what the issue allows a damaged file
constexpr int kMutations = 200;

// xorshift64: the same mutations on every run.
class Random {
 public:
  std::uint64_t next() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 7;
    state_ ^= state_ << 17;
    return state_;
  }
  std::uint64_t below(std::uint64_t n) { return n == 0 ? 0 : next() % n; }

 private:
  std::uint64_t state_ = 0x5eed0f0a11ull;
};

// A small recording of the virtual sensor (3 frames), made once with `lccp record`.
class OniMutationTest : public LccpBinaryTest {
 protected:
  OniMutationTest() : LccpBinaryTest("lccp_oni_mutation") {}

  static void SetUpTestSuite() {
    shared_ = new fs::path(test::scratch_root() / "lccp_oni_mutation");
    fs::create_directories(*shared_);
    const RunResult r = run_lccp(*shared_, {"record", "--uri", "virtual://synthetic", "-o", small().string(), "--frames",
                                            "3", "--log-level", "warn"});
    recorded_ = r.exit_code == 0 && fs::exists(small());
  }
  static void TearDownTestSuite() {
    delete shared_;
  }
  static fs::path small() { return *shared_ / "small.oni"; }

  void SetUp() override {
    LccpBinaryTest::SetUp();
    ASSERT_TRUE(recorded_) << "lccp record failed";
    original_ = read_bytes(small());
  }

  // Replays `bytes` as NAME.oni; large voxels keep the segmentation of accepted files quick.
  RunResult replay(const std::string& bytes, const std::string& name) {
    const fs::path file = work_ / (name + ".oni");
    write_bytes(file, bytes);
    const RunResult r = run({"replay", file.string(), "-o", (work_ / (name + "_out")).string(), "--quiet", "--log-level",
                             "error", "--set", "voxel_size_m=0.02", "--set", "seed_size_m=0.08"},
                            kRunTimeoutSeconds);
    std::error_code ignored;
    fs::remove(file, ignored);
    fs::remove_all(work_ / (name + "_out"), ignored);
    return r;
  }

  void expect_refused(const std::string& bytes, const std::string& name, std::initializer_list<std::string> phrases) {
    expect_error(replay(bytes, name), phrases);
  }

  std::string original_;
  static inline fs::path* shared_ = nullptr;
  static inline bool recorded_ = false;
};

TEST_F(OniMutationTest, TheSmallRecordingReplays) {
  const RunResult r = replay(original_, "small");
  expect_success(r);
}

// --- the crafted recordings that crashed `lccp replay` in DepthStream::to_frame ------

TEST_F(OniMutationTest, RequiredFrameSizeOfOne) {
  std::string bytes = original_;
  put_u64(bytes, oni_property(bytes, "oniRequiredFrameSize").property_data, 1);
  expect_refused(bytes, "size1", {"size1.oni", "required frame size 1"});
}

TEST_F(OniMutationTest, PixelFormat200) {
  std::string bytes = original_;
  put_u64(bytes, oni_property(bytes, "oniPixelFormat").property_data, 200);
  expect_refused(bytes, "format200", {"format200.oni", "pixel format 200"});
}

TEST_F(OniMutationTest, Mode65535x65535) {
  std::string bytes = original_;
  const std::size_t mode = oni_property(bytes, "xnMapOutputMode").property_data;
  put_u32(bytes, mode, 65535);
  put_u32(bytes, mode + 4, 65535);
  expect_refused(bytes, "huge", {"huge.oni", "65535x65535"});
}

// --- recordings that corrupt OpenNI2's own file driver (libOniFile) ------------------

TEST_F(OniMutationTest, FieldsSizeBeyondThePlayersRecordBuffer) {
  std::string bytes = original_;  // PlayerNode::ReadRecordFields reads this many bytes into a fixed buffer
  put_u32(bytes, oni_property(bytes, "xnFOV").offset + 12, 0x00FFFFFF);
  expect_refused(bytes, "fields", {"fields.oni", "fields size 16777215"});
}

TEST_F(OniMutationTest, MaxNodeIdOfTwoToThe32) {
  std::string bytes = original_;  // PlayerNode::OpenStream allocates max node id + 1 (here 0) entries
  put_u32(bytes, 20, 0xFFFFFFFF);
  expect_refused(bytes, "nodes", {"nodes.oni", "node ids up to 4294967295"});
}

TEST_F(OniMutationTest, DepthTableIndexPastTheTable) {
  std::string bytes = original_;  // XnStreamUncompressDepth16ZWithEmbTable never bounds the index
  const OniRecord frame = oni_records_of(bytes, kOniNewData).at(1);
  const std::size_t payload = frame.offset + frame.fields_size;
  const std::uint32_t table_size = get_u32(bytes, payload) & 0xFFFF;
  bytes[payload + 2 + 2 * table_size] = '\xFF';
  bytes[payload + 2 + 2 * table_size + 1] = '\xFF';
  expect_refused(bytes, "index", {"index.oni", "frame 1", "past its table"});
}

TEST_F(OniMutationTest, DepthDataEndingInsideAStep) {
  std::string bytes = original_;  // the player's decoder loops "while (pInput != pInputEnd)" past the end
  append_to_payload(bytes, oni_records_of(bytes, kOniNewData).at(2), "\xFF");  // a long step, then nothing
  expect_refused(bytes, "step", {"step.oni", "frame 2", "ends inside a step"});
}

TEST_F(OniMutationTest, PropertyNameWithBytesAbove127) {
  std::string bytes = original_;  // xnOSStrCRC32 (XnLib) indexes its table with a signed char
  put_u32(bytes, oni_property(bytes, "xnPixelFormat").offset + 32 + 7, 0xFFFFFFFF);
  expect_refused(bytes, "name", {"name.oni", "property name holds a byte outside printable ASCII"});
}

TEST_F(OniMutationTest, SeekTableOfAnotherSize) {
  std::string bytes = original_;  // HandleDataIndexRecord: entries = payload / 20 against the frame count
  const OniRecord added = oni_records_of(bytes, kOniNodeAdded).at(0);
  put_u64(bytes, added.offset + added.fields_size - 8, oni_records_of(bytes, kOniNewData).at(0).offset);
  expect_refused(bytes, "seek", {"seek.oni", "seek table"});
}

// --- 200 deterministic mutations ------------------------------------------------------

struct Mutant {
  std::string bytes;
  std::string what;
};

// One of: a cut at a random offset; a bit flip anywhere; a bit flip in a record
// header or its fields (the structure); a header field or property value set to
// an edge value.
Mutant mutate(const std::string& original, const std::vector<OniRecord>& records, int kind, Random& random) {
  Mutant m{original, ""};
  const OniRecord& r = records[random.below(records.size())];
  if (kind == 0) {
    const std::size_t cut = random.below(original.size());
    m.bytes.resize(cut);
    m.what = "cut at " + std::to_string(cut);
  } else if (kind == 1 || kind == 2) {
    const std::size_t at = kind == 1 ? random.below(original.size()) : r.offset + random.below(r.fields_size);
    const int bit = static_cast<int>(random.below(8));
    m.bytes[at] = static_cast<char>(m.bytes[at] ^ (1 << bit));
    m.what = "bit " + std::to_string(bit) + " of byte " + std::to_string(at);
  } else {
    const std::uint64_t edges[] = {0, 1, 2, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF, 65535, 65536, original.size(), random.next()};
    const std::uint64_t value = edges[random.below(std::size(edges))];
    const std::size_t fields[] = {4, 8, 12, 16, 20};  // type, node, fields size, payload size, undo position
    std::size_t at = r.offset + fields[random.below(std::size(fields))];
    if (r.property_data != 0 && random.below(2) == 0) at = r.property_data;
    if (random.below(8) == 0) at = 12 + 8 * random.below(2);  // the file header's max timestamp or max node id
    if (at + 8 <= m.bytes.size() && random.below(2) == 0) {
      put_u64(m.bytes, at, value);
    } else {
      put_u32(m.bytes, at, static_cast<std::uint32_t>(value));
    }
    m.what = "value " + std::to_string(value) + " at byte " + std::to_string(at);
  }
  return m;
}

TEST_F(OniMutationTest, TwoHundredMutationsNeverCrashOrHang) {
  const std::vector<OniRecord> records = oni_records(original_);
  ASSERT_GT(records.size(), 20u);
  Random random;
  int refused = 0, refused_by_check = 0, replayed = 0, failed = 0;
  double slowest = 0;
  std::string slowest_what;
  for (int i = 0; i < kMutations; ++i) {
    const Mutant m = mutate(original_, records, i % 4, random);
    SCOPED_TRACE("mutation " + std::to_string(i) + ": " + m.what);
    const auto start = Clock::now();
    const RunResult r = replay(m.bytes, "mutant" + std::to_string(i));
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (seconds > slowest) {
      slowest = seconds;
      slowest_what = m.what;
    }
    EXPECT_EQ(r.signal, 0) << describe(r);
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << describe(r);
    EXPECT_LT(seconds, kMaxRunSeconds) << describe(r);
    if (r.exit_code == 1) {
      ++refused;
      refused_by_check += r.err.find("not a readable .oni recording: ") != std::string::npos;
      EXPECT_EQ(r.err.rfind("lccp: error: ", 0), 0u) << describe(r);
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(r);
      // A file the check passed but OpenNI2 stalls on costs the whole stall timeout (5 s).
      EXPECT_EQ(r.err.find("ended after"), std::string::npos) << describe(r);
    } else if (r.exit_code == 0) {
      ++replayed;
    } else {
      ++failed;
    }
  }
  std::cout << "[ figures  ] " << kMutations << " mutated recordings: " << refused << " refused (exit 1; " << refused_by_check << " by the structure check), " << replayed
            << " replayed (exit 0), " << failed << " otherwise; slowest " << slowest << " s (" << slowest_what << ")\n";
  RecordProperty("refused", refused);
  RecordProperty("replayed", replayed);
  RecordProperty("slowest_ms", static_cast<int>(slowest * 1000));
}

}  // namespace
}  // namespace lccp
