// `lccp record`: a device's depth stream into an .oni file with openni::Recorder.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <thread>
#include <vector>

#include <OpenNI.h>

#include "depth_stream.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"

namespace lccp {
namespace {

// The .oni layout as openni::Recorder writes it (OpenNI2, Source/Core/OniRecorder.cpp
// and OniDataRecords.cpp): a 24-byte file header, then records. A record is a 28-byte
// header (magic "NIR\0", type, node id, size of header and fields, payload size:
// little-endian uint32s; an undo position: uint64), its fields, its payload. One
// stream gives NodeAdded (name, node type, codec, number of frames, min and max
// timestamp, seek table position), properties, one NewData per frame (timestamp,
// frame number 1..N, the compressed depth) and, when the recorder is destroyed,
// NodeRemoved, SeekTable (an empty entry, then per frame: timestamp, configuration
// id, position of its NewData; 20 bytes each) and End.
namespace oni {

constexpr std::uint64_t kFileHeaderBytes = 24;
constexpr std::uint64_t kRecordHeaderBytes = 28;
constexpr std::uint64_t kSeekEntryBytes = 20;
constexpr std::uint32_t kNodeRemoved = 0x07;
constexpr std::uint32_t kNewData = 0x0a;
constexpr std::uint32_t kEnd = 0x0b;
constexpr std::uint32_t kNodeAdded = 0x0d;
constexpr std::uint32_t kSeekTable = 0x0e;

struct Record {
  std::uint64_t at = 0;          // offset of the record header
  std::uint64_t fields_end = 0;  // offset of the payload
  std::uint64_t end = 0;         // offset of the next record
  std::uint32_t type = 0;
};

std::uint32_t u32(const char* bytes) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

// The records of a file of `size` bytes up to End, or up to the first one that does
// not parse or is cut short (a recording still being written ends in a partial one).
std::vector<Record> scan_records(std::istream& in, std::uint64_t size) {
  std::vector<Record> records;
  std::array<char, kRecordHeaderBytes> header{};
  for (std::uint64_t at = kFileHeaderBytes; at + kRecordHeaderBytes <= size;) {
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(header.data(), header.size()) || std::memcmp(header.data(), "NIR\0", 4) != 0) break;
    const std::uint32_t fields = u32(&header[12]);
    const std::uint64_t end = at + std::uint64_t{fields} + u32(&header[16]);
    if (fields < kRecordHeaderBytes || end > size) break;
    records.push_back({at, at + fields, end, u32(&header[4])});
    if (records.back().type == kEnd) break;
    at = end;
  }
  return records;
}

std::vector<Record> scan_file(const std::filesystem::path& path) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (error || !in) return {};
  return scan_records(in, size);
}

std::uint64_t count(const std::vector<Record>& records, std::uint32_t type) {
  return static_cast<std::uint64_t>(
      std::count_if(records.begin(), records.end(), [&](const Record& r) { return r.type == type; }));
}

// Frames the recorder has written so far (it writes on its own thread).
std::uint64_t frames_written(const std::filesystem::path& path) { return count(scan_file(path), kNewData); }

const Record* find_one(const std::vector<Record>& records, std::uint32_t type) {
  return count(records, type) == 1
             ? &*std::find_if(records.begin(), records.end(), [&](const Record& r) { return r.type == type; })
             : nullptr;
}

template <class T>
void put(std::string& bytes, std::uint64_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof value);
}

// The finished recording of one stream cut to its first `frames` frames, as the
// recorder would have written it for that many: the NewData records after them are
// left out, the seek table shortened, NodeAdded given the new count, last timestamp
// and seek table position. Empty if the records are not laid out as expected.
std::string keep_first_frames(const std::string& bytes, const std::vector<Record>& records, std::uint64_t frames) {
  std::vector<const Record*> new_data;
  for (const Record& r : records) {
    if (r.type == kNewData) new_data.push_back(&r);
  }
  const Record* added = find_one(records, kNodeAdded);
  const Record* removed = find_one(records, kNodeRemoved);
  const Record* seek = find_one(records, kSeekTable);
  const Record& end = records.back();
  if (!added || !removed || !seek || end.type != kEnd || frames == 0 || new_data.size() <= frames ||
      seek->end - seek->fields_end != (new_data.size() + 1) * kSeekEntryBytes || removed->at < new_data.back()->end) {
    return {};
  }
  // NodeAdded fields: name (uint32 size, then the bytes), node type, codec, number of
  // frames (uint32), min and max timestamp, seek table position (uint64).
  const std::uint64_t name_at = added->at + kRecordHeaderBytes;
  const std::uint64_t frames_at = name_at + 4 + u32(bytes.data() + name_at) + 8;
  if (frames_at + 4 + 3 * 8 > added->fields_end) return {};

  std::string out = bytes.substr(0, new_data[frames - 1]->end);
  out.append(bytes, removed->at, removed->end - removed->at);
  const std::uint64_t seek_at = out.size();
  out.append(bytes, seek->at, seek->fields_end - seek->at);
  put(out, seek_at + 16, static_cast<std::uint32_t>((frames + 1) * kSeekEntryBytes));
  out.append(bytes, seek->fields_end, (frames + 1) * kSeekEntryBytes);
  out.append(bytes, end.at, end.end - end.at);

  std::uint64_t last_timestamp = 0;
  std::memcpy(&last_timestamp, bytes.data() + new_data[frames - 1]->at + kRecordHeaderBytes, sizeof last_timestamp);
  put(out, frames_at, static_cast<std::uint32_t>(frames));
  put(out, frames_at + 4 + 8, last_timestamp);
  put(out, frames_at + 4 + 16, seek_at);
  return out;
}

// Finishes the file openni::Recorder left: cuts its zero padding (it leaves the file
// padded to about twice its content) and any frames beyond `frames`. Returns the
// frames the file holds; a file whose records do not parse is left alone.
std::uint64_t finish_recording(const std::filesystem::path& path, std::uint64_t frames) {
  const std::vector<Record> records = scan_file(path);
  const std::uint64_t written = count(records, kNewData);
  if (records.empty() || records.back().type != kEnd) return written;
  if (written <= frames) {
    std::filesystem::resize_file(path, records.back().end);
    return written;
  }
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  in.close();
  const std::string trimmed = keep_first_frames(bytes, records, frames);
  if (trimmed.empty()) return written;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(trimmed.data(), static_cast<std::streamsize>(trimmed.size()));
  out.close();
  if (!out) throw Error("cannot write " + path.string());
  return frames;
}

}  // namespace oni

// How long the recorder may lag behind the frames we have read before we give up.
constexpr auto kRecorderCatchUp = std::chrono::seconds(10);
// The wait for the first frame, if longer than the stall timeout: a device may take a
// while to deliver it (measured: over 2 s for the virtual sensor in a sanitizer build
// on a loaded machine, where the stall timeout alone made `record` fail at once).
constexpr int kFirstFrameTimeoutMs = 20000;

// Reads frames until the recorder has written `frames` of them, `stop` is set, the
// device is lost or stalls, or the recorder lags kRecorderCatchUp behind. OpenNI2
// hands every frame to the recorder before readers can see it (VideoStream::
// stream_NewFrame), but the recorder writes on its own thread, and on a loaded
// machine we may read a frame late or not at all, so the file is what we count.
// Returns the frames read, counted by the sensor's frame index.
std::uint64_t read_until_written(detail::DepthStream& stream, const std::filesystem::path& partial,
                                 std::uint64_t frames, int stall_timeout_ms, const std::atomic<bool>& stop) {
  std::optional<std::uint64_t> first_index;
  std::optional<std::chrono::steady_clock::time_point> read_enough;
  std::uint64_t read = 0;
  const int first_frame_timeout_ms = std::max(stall_timeout_ms, kFirstFrameTimeoutMs);
  while (std::optional<Frame> frame =
             stream.wait_and_read(first_index ? stall_timeout_ms : first_frame_timeout_ms, stop)) {
    if (!first_index) first_index = frame->index;
    read = frame->index - *first_index + 1;
    if (read < frames) continue;  // the file cannot hold enough yet: no need to look
    if (oni::frames_written(partial) >= frames) break;
    const auto now = std::chrono::steady_clock::now();
    if (!read_enough) read_enough = now;
    if (now - *read_enough > kRecorderCatchUp) break;
  }
  return read;
}

}  // namespace

RecordStats record_device(const LiveOptions& options, const std::filesystem::path& output, std::uint64_t frames,
                          const std::atomic<bool>& stop) {
  if (output.extension() != ".oni") throw Error("recording " + output.string() + " must have the .oni suffix");
  detail::DepthStream stream;
  stream.open_live(options);
  // Written under a hidden, unpredictable name beside the output (created exclusively,
  // keeping the .oni suffix), renamed over it when complete, removed otherwise.
  PendingFile pending = PendingFile::named(output);
  const std::filesystem::path& partial = pending.temporary_path();
  std::uint64_t read = 0;
  {
    openni::Recorder recorder;
    if (recorder.create(partial.c_str()) != openni::STATUS_OK) {
      throw Error("cannot create " + output.string() + ": " + openni_error());
    }
    recorder.attach(stream.stream(), /*allowLossyCompression=*/false);
    recorder.start();
    // The recorder starts on its own thread: a frame sent at once could miss it.
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stream.start();
    read = read_until_written(stream, partial, frames, options.stall_timeout_ms, stop);
    recorder.stop();
    recorder.destroy();  // writes the seek table and the End record
  }
  // Exactly `frames` frames: the recorder may have written more than asked for.
  const std::uint64_t written = oni::finish_recording(partial, frames);
  if (written != frames && (written > frames || !stop.load())) {
    const std::string after = " after " + std::to_string(written) + " of " + std::to_string(frames) + " frames";
    if (written < frames && stream.lost()) throw Error("device " + stream.uri() + " disconnected" + after);
    if (written < frames && read < frames) throw Error("device " + stream.uri() + " stopped sending frames" + after);
    throw Error("openni::Recorder wrote " + std::to_string(written) + " frames of " + stream.uri() + ", not " +
                std::to_string(frames) + "; " + output.string() + " not written");
  }
  // The file must replay: every frame written, the first one readable.
  RecordStats stats;
  stats.mode = stream.mode();
  bool replays = false;
  {
    const auto replay = open_recording(partial);
    stats.frames = replay->frame_count().value_or(0);
    replays = replay->next().has_value();
  }
  if (!replays || stats.frames != written) {
    throw Error("the recording of " + stream.uri() + " does not replay its " + std::to_string(written) +
                " frames; " + output.string() + " not written");
  }
  pending.commit();
  return stats;
}

}  // namespace lccp
