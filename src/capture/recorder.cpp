// `lccp record`: a device's depth stream into an .oni file with openni::Recorder.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <thread>
#include <vector>

#include <OpenNI.h>

#include "depth_stream.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"
#include "lccp/io/atomic_file.hpp"
#include "oni_format.hpp"

namespace lccp {
namespace {

// What openni::Recorder writes for one stream (OpenNI2, Source/Core/OniRecorder.cpp
// and OniDataRecords.cpp; the record layout is in oni_format.hpp): NodeAdded (name,
// node type, codec, number of frames, min and max timestamp, seek table position),
// properties, one NewData per frame (timestamp, frame number 1..N, the compressed
// depth) and, when the recorder is destroyed, NodeRemoved, SeekTable (an empty entry,
// then per frame: timestamp, configuration id, position of its NewData) and End.
namespace oni {

using namespace detail::oni;
using Bytes = std::vector<std::uint8_t>;

// The file's bytes as they are now (empty if it cannot be read).
Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (size < 0) return {};
  Bytes bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

std::uint64_t count(const std::vector<RecordHeader>& records, std::uint32_t type) {
  return static_cast<std::uint64_t>(
      std::count_if(records.begin(), records.end(), [&](const RecordHeader& r) { return r.type == type; }));
}

// Frames the recorder has written so far (it writes on its own thread): the records
// up to the first one it has not finished (walk_records).
std::uint64_t frames_written(const std::filesystem::path& path) {
  const Bytes bytes = read_file(path);
  return count(walk_records(bytes).records, kNewData);
}

const RecordHeader* find_one(const std::vector<RecordHeader>& records, std::uint32_t type) {
  return count(records, type) == 1
             ? &*std::find_if(records.begin(), records.end(), [&](const RecordHeader& r) { return r.type == type; })
             : nullptr;
}

template <class T>
void put(Bytes& bytes, std::uint64_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof value);
}

void append(Bytes& out, std::span<const std::uint8_t> bytes, std::uint64_t from, std::uint64_t to) {
  out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(from), bytes.begin() + static_cast<std::ptrdiff_t>(to));
}

// The finished recording of one stream cut to its first `frames` frames, as the
// recorder would have written it for that many: the NewData records after them are
// left out, the seek table shortened, NodeAdded given the new count, last timestamp
// and seek table position. Empty if the records are not laid out as expected.
Bytes keep_first_frames(std::span<const std::uint8_t> bytes, const std::vector<RecordHeader>& records,
                        std::uint64_t frames) {
  std::vector<const RecordHeader*> new_data;
  for (const RecordHeader& r : records) {
    if (r.type == kNewData) new_data.push_back(&r);
  }
  const RecordHeader* added = find_one(records, kNodeAdded);
  const RecordHeader* removed = find_one(records, kNodeRemoved);
  const RecordHeader* seek = find_one(records, kSeekTable);
  const RecordHeader& end = records.back();
  if (!added || !removed || !seek || end.type != kEnd || frames == 0 || new_data.size() <= frames ||
      seek->payload_size != (new_data.size() + 1) * kSeekEntryBytes || removed->offset < new_data.back()->end() ||
      added->fields.size() < 4) {
    return {};
  }
  // NodeAdded fields: the name (u32 size, then the bytes), then the fields at kNodeAdded*At.
  const std::uint64_t after_name = added->offset + kRecordHeaderBytes + 4 + read_u32(added->fields, 0);
  if (after_name + kNodeAddedBytesAfterName > added->fields_end()) return {};

  const RecordHeader& last = *new_data[frames - 1];
  Bytes out(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(last.end()));
  append(out, bytes, removed->offset, removed->end());
  const std::uint64_t seek_at = out.size();
  append(out, bytes, seek->offset, seek->fields_end());
  put(out, seek_at + kRecordPayloadSizeAt, static_cast<std::uint32_t>((frames + 1) * kSeekEntryBytes));
  append(out, bytes, seek->fields_end(), seek->fields_end() + (frames + 1) * kSeekEntryBytes);
  append(out, bytes, end.offset, end.end());

  const std::uint64_t last_timestamp = read_u64(bytes, last.offset + kRecordHeaderBytes);  // NewData's first field
  put(out, after_name + kNodeAddedFramesAt, static_cast<std::uint32_t>(frames));
  put(out, after_name + kNodeAddedMaxTimestampAt, last_timestamp);
  put(out, after_name + kNodeAddedSeekTableAt, seek_at);
  return out;
}

// Finishes the file openni::Recorder left: cuts its zero padding (it leaves the file
// padded to about twice its content) and any frames beyond `frames`. Returns the
// frames the file holds; a file whose records do not parse is left alone.
std::uint64_t finish_recording(const std::filesystem::path& path, std::uint64_t frames) {
  const Bytes bytes = read_file(path);
  const std::vector<RecordHeader> records = walk_records(bytes).records;
  const std::uint64_t written = count(records, kNewData);
  if (records.empty() || records.back().type != kEnd) return written;
  if (written <= frames) {
    std::filesystem::resize_file(path, records.back().end());
    return written;
  }
  const Bytes trimmed = keep_first_frames(bytes, records, frames);
  if (trimmed.empty()) return written;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(trimmed.data()), static_cast<std::streamsize>(trimmed.size()));
  out.close();
  if (!out) throw Error("cannot write " + path.string());
  return frames;
}

}  // namespace oni

// How long the recorder may lag behind the frames we have read before we give up.
constexpr auto kRecorderCatchUp = std::chrono::seconds(10);

// Reads frames until the recorder has written `frames` of them, a stop is requested, the
// device is lost or stalls, or the recorder lags kRecorderCatchUp behind. OpenNI2
// hands every frame to the recorder before readers can see it (VideoStream::
// stream_NewFrame), but the recorder writes on its own thread, and on a loaded
// machine we may read a frame late or not at all, so the file is what we count.
// Returns the frames read, counted by the sensor's frame index.
std::uint64_t read_until_written(detail::DepthStream& stream, const std::filesystem::path& partial,
                                 std::uint64_t frames, const LiveOptions& options, std::stop_token stop) {
  std::optional<std::uint64_t> first_index;
  std::optional<std::chrono::steady_clock::time_point> read_enough;
  std::uint64_t read = 0;
  const int stall_timeout_ms = options.stall_timeout_ms;
  const int first_frame_timeout_ms = std::max(stall_timeout_ms, options.first_frame_timeout_ms);
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
                          std::stop_token stop) {
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
    read = read_until_written(stream, partial, frames, options, stop);
    recorder.stop();
    recorder.destroy();  // writes the seek table and the End record
  }
  // Exactly `frames` frames: the recorder may have written more than asked for.
  const std::uint64_t written = oni::finish_recording(partial, frames);
  if (written != frames && (written > frames || !stop.stop_requested())) {
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
    replays = replay->next(std::stop_token{}).has_value();
  }
  if (!replays || stats.frames != written) {
    throw Error("the recording of " + stream.uri() + " does not replay its " + std::to_string(written) +
                " frames; " + output.string() + " not written");
  }
  pending.commit();
  return stats;
}

}  // namespace lccp
