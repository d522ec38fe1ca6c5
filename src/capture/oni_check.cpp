// Structural check of .oni recordings, made when a replay opens one (oni_check.hpp;
// the frames are then read by oni_reader.cpp). It accepts what OpenNI2's own player
// reads safely, so a recording we replay is one OpenNI2 would replay too.
//
// What that player (Source/Drivers/OniFile/PlayerNode.cpp) does not check: it reads
// a record's fields into a fixed buffer without comparing the fields size to it
// (ReadRecordFields), allocates "max node id + 1" entries from the header
// (OpenStream), dereferences property
// data without size checks (IntPropRecord::GetValue, the xnFOV property), decodes
// 16zT data with table indices and an end test it never bounds
// (XnStreamUncompressDepth16ZWithEmbTable loops "while (pInput != pInputEnd)"),
// and decodes with a null codec for a stream declared without one. Every one of
// those is a fact about the bytes, checked here in one linear pass (about a
// millisecond a frame), testable and fuzzable on its own.
// The facts below come from OpenNI2's public source: DataRecords.h/.cpp,
// PlayerNode.cpp, PlayerDevice.cpp, PlayerSource.cpp, PlayerStream.cpp,
// Formats/XnCodecIDs.h and XnStreamCompression.cpp in Source/Drivers/OniFile/,
// and Source/Core/OniRecorder.cpp, OniDataRecords.cpp (what the Recorder writes).
#include "oni_check.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "lccp/error.hpp"
#include "depth_units.hpp"
#include "mapped_file.hpp"
#include "oni_16zt.hpp"
#include "oni_format.hpp"

namespace lccp::detail {
namespace {

using namespace oni;  // the record layout and its walk (oni_format.hpp)

// The player's record buffer: NewDataRecordHeader::MAX_SIZE (28 + 81 + 8 + 4) + DATA_MAX_SIZE.
constexpr std::uint64_t kPlayerRecordMaxBytes = 121 + kOniPlayerDataMaxBytes;
// Our own limits, far above what OpenNI2's Recorder writes (one node, id 1; fields of
// a few hundred bytes; names under 40 characters).
constexpr std::uint32_t kMaxNodeId = 255;
constexpr std::uint32_t kMaxFieldsBytes = 64 * 1024;
constexpr std::uint32_t kMaxNodeNameBytes = 80;       // XN_MAX_NAME_LENGTH: the player copies into char[80]
constexpr std::uint32_t kMaxPropertyNameBytes = 256;  // ONI_MAX_STR, the Recorder's limit

constexpr std::uint32_t kNodeTypeDepth = 2;  // XN_NODE_TYPE_DEPTH

// An inconsistency; turned into one lccp::Error line naming the file.
struct Corrupt {
  std::string text;
};
[[noreturn]] void corrupt(std::string text) { throw Corrupt{std::move(text)}; }

std::string str(std::uint64_t value) { return std::to_string(value); }

// Little-endian reads inside one span; reading past its end is an inconsistency.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::span<const std::uint8_t> take(std::uint64_t count) {
    if (count > bytes_.size() - at_) corrupt("its fields end early");
    const auto part = bytes_.subspan(at_, count);
    at_ += count;
    return part;
  }
  std::uint32_t u32() { return read_u32(take(4), 0); }
  std::uint64_t u64() { return read_u64(take(8), 0); }
  double f64() {
    const std::uint64_t bits = u64();
    double value = 0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

// A string field: u32 size (terminating NUL included), then the bytes
// (Record::ReadString). Must hold exactly one NUL, at its end, and printable ASCII
// before it: the player keys hashes by these names, and XnLib's xnOSStrCRC32
// indexes its table with a signed char (a byte >= 0x80 reads before the table).
std::string read_string(Cursor& fields, std::uint32_t max_bytes, const char* what) {
  const std::uint32_t size = fields.u32();
  if (size == 0 || size > max_bytes) corrupt(std::string(what) + " of " + str(size) + " bytes");
  const auto bytes = fields.take(size);
  const auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
  if (nul != bytes.end() - 1) corrupt(std::string(what) + " is not one NUL-terminated string");
  if (std::any_of(bytes.begin(), nul, [](std::uint8_t c) { return c < 0x20 || c > 0x7e; })) {
    corrupt(std::string(what) + " holds a byte outside printable ASCII");
  }
  return std::string(bytes.begin(), nul);
}

// The depth stream's declared state, in file order (PlayerDevice::OnNode*PropChanged).
struct DepthNode {
  std::uint32_t id = 0;
  std::uint64_t added_at = 0;
  std::uint32_t codec = 0;
  std::uint32_t declared_frames = 0;
  std::uint64_t max_timestamp = 0;
  std::uint64_t seek_table_position = 0;
  bool ready = false;
  bool data_begun = false;
  bool removed = false;
  std::uint32_t width = 0, height = 0;
  int pixel_format = kDepth1mm;  // the player's default for a depth source
  std::optional<std::uint64_t> required_frame_size;
  bool has_max_depth = false;
  bool has_cropping = false;
  double horizontal_fov = 0, vertical_fov = 0;
  std::vector<OniFrameRecord> frames;
  std::optional<RecordHeader> seek_table;
};



// Walks the records in file order, as OpenNI2's player meets them, and checks each.
class OniChecker {
 public:
  explicit OniChecker(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  OniRecordingFacts run() {
    check_file_header();
    const RecordWalk walk = walk_records(bytes_);
    for (const RecordHeader& record : walk.records) {
      at_record(record.offset, [&] {
        check_record_header(record);
        handle(record);
      });
      record_offsets_.push_back(record.offset);
    }
    if (walk.stop == WalkStop::end_of_bytes) {
      corrupt("ends at byte " + str(walk.failed.offset) + " without an End record (truncated?)");
    }
    if (walk.stop != WalkStop::end_record) at_record(walk.failed.offset, [&] { unreadable_record(walk); });
    return finish();
  }

 private:
  void check_file_header() {
    if (bytes_.size() < kFileHeaderBytes) corrupt("shorter than the 24-byte .oni file header");
    if (std::memcmp(bytes_.data(), "NI10", 4) != 0) corrupt("no .oni file header (magic NI10)");
    Cursor header(bytes_.subspan(4, kFileHeaderBytes - 4));
    const auto version = header.take(8);
    // {1, 0, 1, 0}: the only version OpenNI2's Recorder writes (OniRecorder.cpp), with
    // 64-bit positions; older ones use another record header (PlayerNode::OpenStream).
    const std::uint8_t current[8] = {1, 0, 1, 0, 0, 0, 0, 0};
    if (!std::equal(version.begin(), version.end(), current)) {
      const std::uint64_t maintenance = version[2] | version[3] << 8;
      const std::uint64_t build = version[4] | version[5] << 8 | version[6] << 16 | std::uint64_t{version[7]} << 24;
      corrupt("unsupported .oni format version " + str(version[0]) + "." + str(version[1]) + "." + str(maintenance) +
              "." + str(build) + " (only 1.0.1.0, written by OpenNI2, is read)");
    }
    global_max_timestamp_ = header.u64();
    max_node_id_ = header.u32();
    if (max_node_id_ > kMaxNodeId) corrupt("header declares node ids up to " + str(max_node_id_));
  }

  // Runs `check` on the record at `offset`, naming that offset in what it finds.
  template <class Check>
  static void at_record(std::uint64_t offset, Check check) {
    try {
      check();
    } catch (Corrupt& c) {
      c.text = "record at byte " + str(offset) + ": " + c.text;
      throw;
    }
  }

  // The record where the walk stopped before an End record.
  static void unreadable_record(const RecordWalk& walk) {
    if (walk.stop == WalkStop::truncated_header) corrupt("truncated record header (truncated file?)");
    if (walk.stop == WalkStop::no_magic) corrupt("no record magic NIR");
    check_fields_size(walk.failed);
    const std::uint64_t size = std::uint64_t{walk.failed.fields_size} + walk.failed.payload_size;
    corrupt("record of " + str(size) + " bytes runs past the end of the file (truncated?)");
  }

  static void check_fields_size(const RecordHeader& r) {
    if (r.fields_size < kRecordHeaderBytes || r.fields_size > kMaxFieldsBytes) {
      corrupt("fields size " + str(r.fields_size) + " outside " + str(kRecordHeaderBytes) + ".." + str(kMaxFieldsBytes));
    }
  }

  // What the player's buffers and record handlers take of a record that fits the file.
  static void check_record_header(const RecordHeader& r) {
    check_fields_size(r);
    if (r.type != kNewData && r.type != kSeekTable && r.payload_size != 0) {
      corrupt("record type " + str(r.type) + " with a payload");
    }
    const std::uint64_t size = std::uint64_t{r.fields_size} + r.payload_size;
    if (size > kPlayerRecordMaxBytes) corrupt("record of " + str(size) + " bytes exceeds OpenNI2's player buffer");
  }

  void handle(const RecordHeader& r) {
    switch (r.type) {
      case kNodeAdded: node_added(r); return;
      case kIntProperty:
      case kRealProperty:
      case kStringProperty:
      case kGeneralProperty: property(r); return;
      case kNodeStateReady: state_ready(r); return;
      case kNodeDataBegin: data_begin(r); return;
      case kNewData: new_data(r); return;
      case kNodeRemoved: node_removed(r); return;
      case kSeekTable: seek_table(r); return;
      case kEnd: check_no_fields(r); return;
      case kNodeAddedV1004:
      case kNodeAddedV1005: corrupt("legacy NodeAdded record (OpenNI 1 format) not supported");
      default: corrupt("unknown record type " + str(r.type));
    }
  }

  void check_no_fields(const RecordHeader& r) {
    if (!r.fields.empty()) corrupt("record type " + str(r.type) + " with " + str(r.fields.size()) + " bytes of fields");
  }

  void check_undo(const RecordHeader& r, std::uint64_t expected) {
    if (r.undo != expected) corrupt("undo position " + str(r.undo) + ", expected " + str(expected));
  }

  // Any undo position is 0 or an earlier record (PlayerNode::UndoRecord seeks there).
  void check_undo_earlier(const RecordHeader& r) {
    if (r.undo != 0 && !std::binary_search(record_offsets_.begin(), record_offsets_.end(), r.undo)) {
      corrupt("undo position " + str(r.undo) + " is not an earlier record");
    }
  }

  // The depth node a record names; it must have been added and not removed.
  DepthNode& live_node(const RecordHeader& r) {
    if (!node_ || node_->id != r.node) corrupt("record for node " + str(r.node) + ", which was never added");
    if (node_->removed) corrupt("record for node " + str(r.node) + " after it was removed");
    return *node_;
  }

  void node_added(const RecordHeader& r) {
    Cursor fields(r.fields);
    const std::string name = read_string(fields, kMaxNodeNameBytes, "node name");
    const std::uint32_t type = fields.u32();
    DepthNode node;
    node.id = r.node;
    node.added_at = r.offset;
    node.codec = fields.u32();
    node.declared_frames = fields.u32();
    const std::uint64_t min_timestamp = fields.u64();
    node.max_timestamp = fields.u64();
    node.seek_table_position = fields.u64();
    if (!fields.done()) corrupt("NodeAdded record with " + str(r.fields.size()) + " bytes of fields");
    if (type != kNodeTypeDepth) {
      corrupt("node '" + name + "' is of type " + str(type) + ", not depth: no depth stream (only depth-only recordings are read)");
    }
    if (node_) corrupt("a second stream (only recordings of one depth stream are read)");
    if (r.node == 0 || r.node > max_node_id_) corrupt("node id " + str(r.node) + " outside 1.." + str(max_node_id_));
    if (node.codec != kCodec16zT && node.codec != kCodecNone) corrupt("depth codec is neither 16zT nor NONE");
    if (min_timestamp > node.max_timestamp) corrupt("minimum timestamp after the maximum");
    check_undo(r, 0);
    node_ = node;
  }

  void property(const RecordHeader& r) {
    DepthNode& node = live_node(r);
    check_undo_earlier(r);
    Cursor fields(r.fields);
    const std::string name = read_string(fields, kMaxPropertyNameBytes, "property name");
    const std::uint32_t size = fields.u32();
    Cursor data(fields.take(size));
    if (!fields.done()) corrupt("property '" + name + "' with bytes after its data");
    if ((r.type == kIntProperty || r.type == kRealProperty) && size != 8) {
      corrupt("number property '" + name + "' of " + str(size) + " bytes");  // IntPropRecord::GetValue reads 8
    }
    if (r.type == kStringProperty) {  // PlayerDevice passes it to strlen
      const auto text = data.take(size);
      if (size == 0 || std::find(text.begin(), text.end(), std::uint8_t{0}) != text.end() - 1) {
        corrupt("string property '" + name + "' is not one NUL-terminated string");
      }
      return;
    }
    apply_property(node, r.type, name, data, size);
  }

  // The properties PlayerDevice turns into the stream's video mode, frame size and
  // field of view (OnNodeIntPropChanged, OnNodeGeneralPropChanged, PlayerNode's
  // xnRealWorldTranslationData); any other name is stored as an opaque value.
  void apply_property(DepthNode& node, std::uint32_t type, const std::string& name, Cursor& data, std::uint32_t size) {
    const bool general = type == kGeneralProperty;
    const bool shapes_frames = name == "xnMapOutputMode" || name == "oniPixelFormat" || name == "xnPixelFormat" ||
                               name == "oniRequiredFrameSize" || name == "RequiredDataSize" || name == "xnCropping";
    // The Recorder writes these when the stream is attached, before NodeDataBegin; the
    // player's stream takes its frame buffer size when it starts, at NodeDataBegin.
    if (shapes_frames && node.data_begun) corrupt("property '" + name + "' set after NodeDataBegin");
    if (name == "xnRealWorldTranslationData") corrupt("legacy property xnRealWorldTranslationData not supported");
    if (general && name == "xnMapOutputMode") {
      expect_size(name, size, 12);
      node.width = data.u32();
      node.height = data.u32();
      data.u32();  // frames per second
      check_mode(node);
    } else if (general && name == "xnFOV") {
      expect_size(name, size, 16);
      node.horizontal_fov = check_fov(data.f64(), "horizontal");
      node.vertical_fov = check_fov(data.f64(), "vertical");
    } else if (general && name == "xnCropping") {
      expect_size(name, size, 12);
      if (data.u32() != 0) corrupt("cropped depth (xnCropping enabled) not supported");
      node.has_cropping = true;
    } else if (type == kIntProperty && name == "oniPixelFormat") {
      const std::uint64_t format = data.u64();
      if (format != kDepth1mm && format != kDepth100um) corrupt("pixel format " + str(format) + " is not a depth format");
      node.pixel_format = static_cast<int>(format);
    } else if (type == kIntProperty && name == "xnPixelFormat") {
      node.pixel_format = kDepth1mm;  // what PlayerDevice sets for a depth source, whatever the value
    } else if (type == kIntProperty && (name == "oniRequiredFrameSize" || name == "RequiredDataSize")) {
      node.required_frame_size = data.u64();
    } else if (type == kIntProperty && name == "xnDeviceMaxDepth") {
      node.has_max_depth = true;  // PlayerCodecFactory needs it to create the 16zT codec
    }
  }

  static void expect_size(const std::string& name, std::uint32_t size, std::uint32_t expected) {
    if (size != expected) corrupt("property '" + name + "' of " + str(size) + " bytes, expected " + str(expected));
  }

  static double check_fov(double radians, const char* which) {
    if (!(radians > 0.0 && radians < std::numbers::pi)) corrupt(std::string(which) + " field of view outside (0, pi)");
    return radians;
  }

  static void check_mode(const DepthNode& node) {
    if (node.width == 0 || node.height == 0 || node.width > kMaxDepthSide || node.height > kMaxDepthSide) {
      corrupt("depth mode " + str(node.width) + "x" + str(node.height) + " outside 1.." + str(kMaxDepthSide) + " a side");
    }
    if (2ull * node.width * node.height > kOniPlayerDataMaxBytes) {
      corrupt("depth mode " + str(node.width) + "x" + str(node.height) + " exceeds OpenNI2's player frame buffer");
    }
  }

  void state_ready(const RecordHeader& r) {
    DepthNode& node = live_node(r);
    check_no_fields(r);
    check_undo(r, 0);
    if (node.ready) corrupt("a second NodeStateReady record");
    if (node.codec == kCodec16zT && !node.has_max_depth) corrupt("16zT depth without xnDeviceMaxDepth");
    node.ready = true;  // the player creates the node's codec here
  }

  void data_begin(const RecordHeader& r) {
    DepthNode& node = live_node(r);
    Cursor fields(r.fields);
    fields.u32();  // frame count and max timestamp: the Recorder writes placeholders
    fields.u64();
    if (!fields.done()) corrupt("NodeDataBegin record with " + str(r.fields.size()) + " bytes of fields");
    check_undo(r, 0);
    if (!node.ready || node.data_begun) corrupt("NodeDataBegin record out of order");
    check_frame_shape(node);
    node.data_begun = true;
  }

  void new_data(const RecordHeader& r) {
    DepthNode& node = live_node(r);
    const std::uint64_t frame = node.frames.size();
    try {
      Cursor fields(r.fields);
      const std::uint64_t timestamp = fields.u64();
      const std::uint32_t number = fields.u32();
      if (!fields.done()) corrupt("NewData record with " + str(r.fields.size()) + " bytes of fields");
      if (!node.data_begun) corrupt("depth data before its NodeDataBegin record");
      check_undo(r, node.frames.empty() ? 0 : node.frames.back().record_offset);
      if (number != frame + 1) corrupt("frame number " + str(number) + ", expected " + str(frame + 1));
      if (frame >= node.declared_frames) corrupt("more frames than the " + str(node.declared_frames) + " declared");
      if (timestamp > node.max_timestamp || timestamp > global_max_timestamp_) corrupt("timestamp past the declared maximum");
      if (!node.frames.empty() && timestamp < node.frames.back().timestamp_us) corrupt("timestamp goes backwards");
      check_payload(node, r.payload);
      node.frames.push_back({r.offset, r.fields_end(), r.payload_size, timestamp});
    } catch (Corrupt& c) {
      c.text = "frame " + str(frame) + ": " + c.text;
      throw;
    }
  }

  // What PlayerStream will hand out, fixed from NodeDataBegin on: width x height 2-byte
  // pixels in a buffer of the required frame size (PlayerStream::OnNewDataCallback).
  static void check_frame_shape(const DepthNode& node) {
    if (node.width == 0) corrupt("no depth mode (xnMapOutputMode) before NodeDataBegin");
    // PlayerStream::OnNewDataCallback drops every frame of a stream without a cropping property.
    if (!node.has_cropping) corrupt("no xnCropping property before NodeDataBegin (OpenNI2 would drop every frame)");
    const std::uint64_t bytes = 2ull * node.width * node.height;
    if (node.required_frame_size &&
        (*node.required_frame_size < bytes || *node.required_frame_size > kOniPlayerDataMaxBytes)) {
      corrupt("required frame size " + str(*node.required_frame_size) + " does not fit the " + str(node.width) + "x" +
              str(node.height) + " depth mode (" + str(bytes) + " bytes)");
    }
  }

  void check_payload(const DepthNode& node, std::span<const std::uint8_t> payload) {
    const std::size_t pixels = std::size_t{node.width} * node.height;
    if (node.codec == kCodecNone) {
      if (payload.size() != 2 * pixels) {
        corrupt("uncompressed frame of " + str(payload.size()) + " bytes, expected " + str(2 * pixels));
      }
      return;
    }
    pixels_.resize(pixels);
    if (const auto problem = decode_16zt(payload, pixels_)) corrupt(*problem);
  }

  void node_removed(const RecordHeader& r) {
    DepthNode& node = live_node(r);
    check_no_fields(r);
    check_undo(r, node.added_at);
    node.removed = true;
  }

  void seek_table(const RecordHeader& r) {
    if (!node_ || node_->id != r.node) corrupt("seek table of node " + str(r.node) + ", which was never added");
    check_no_fields(r);
    check_undo(r, 0);
    if (node_->seek_table) corrupt("a second seek table");
    node_->seek_table = r;
  }

  // After the End record: the counts and the seek table agree with the frames.
  OniRecordingFacts finish() {
    if (!node_) corrupt("no depth stream");
    const DepthNode& node = *node_;
    const std::uint64_t frames = node.frames.size();
    if (frames == 0) corrupt("holds no depth frames");
    if (frames != node.declared_frames) {
      corrupt("declares " + str(node.declared_frames) + " frames but holds " + str(frames) + " (unfinished recording?)");
    }
    if (node.seek_table_position != 0) check_seek_table(node);
    OniRecordingFacts facts;
    facts.frames = static_cast<std::uint32_t>(frames);
    facts.width = static_cast<int>(node.width);
    facts.height = static_cast<int>(node.height);
    facts.pixel_format = node.pixel_format;
    facts.codec = node.codec;
    facts.horizontal_fov_rad = static_cast<float>(node.horizontal_fov);
    facts.vertical_fov_rad = static_cast<float>(node.vertical_fov);
    facts.frame_records = node.frames;
    return facts;
  }

  // The table the player loads when the stream is added (HandleNodeAddedRecord,
  // HandleDataIndexRecord): frames + 1 entries, entry i pointing at frame i's record.
  static void check_seek_table(const DepthNode& node) {
    const std::string where = "seek table at byte " + str(node.seek_table_position) + ": ";
    if (!node.seek_table || node.seek_table->offset != node.seek_table_position) {
      corrupt(where + "the stream's seek table position is not its SeekTable record");
    }
    const auto payload = node.seek_table->payload;
    const std::size_t frames = node.frames.size();
    if (payload.size() != (frames + 1) * kSeekEntryBytes) {
      corrupt(where + str(payload.size()) + " bytes for " + str(frames) + " frames");
    }
    for (std::size_t i = 1; i <= frames; ++i) {
      Cursor entry(payload.subspan(i * kSeekEntryBytes, kSeekEntryBytes));
      const std::uint64_t timestamp = entry.u64();
      entry.u32();  // configuration id
      const std::uint64_t position = entry.u64();
      if (timestamp != node.frames[i - 1].timestamp_us || position != node.frames[i - 1].record_offset) {
        corrupt(where + "entry " + str(i) + " does not match frame " + str(i - 1));
      }
    }
  }

  std::span<const std::uint8_t> bytes_;
  std::uint64_t global_max_timestamp_ = 0;
  std::uint32_t max_node_id_ = 0;
  std::optional<DepthNode> node_;
  std::vector<std::uint64_t> record_offsets_;
  std::vector<std::uint16_t> pixels_;
};

}  // namespace

OniRecordingFacts check_oni_recording(std::span<const std::uint8_t> bytes, std::string_view name) {
  try {
    return OniChecker(bytes).run();
  } catch (const Corrupt& c) {
    throw Error(std::string(name) + ": not a readable .oni recording: " + c.text);
  }
}

OniRecordingFacts check_oni_file(const std::filesystem::path& path) {
  const MappedFile file(path);
  return check_oni_recording(file.bytes(), path.string());
}

}  // namespace lccp::detail
