// `lccp record`: a device's depth stream into an .oni file with openni::Recorder.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <thread>

#include <OpenNI.h>

#include "depth_stream.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

// Whether two depth images agree, but for the last two pixels, which the
// recorder's 16zT codec may alter (GUIDE 4).
bool same_depth(const DepthImage& a, const DepthImage& b) {
  if (a.depth_mm.size() != b.depth_mm.size() || a.depth_mm.size() < 2) return false;
  return std::equal(a.depth_mm.begin(), a.depth_mm.end() - 2, b.depth_mm.begin());
}

// openni::Recorder leaves the file padded with zeros to about twice its
// content. The .oni layout: a 24-byte header, then records "NIR\0", type,
// node id, header size, payload size (little-endian uint32s), ... up to an
// End record. Cuts the file after the End record; leaves it alone if the
// records do not parse.
void trim_recorder_padding(const std::filesystem::path& path) {
  constexpr std::size_t kFileHeaderBytes = 24;
  constexpr std::uint32_t kEndRecord = 0x0b;
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto u32 = [&](std::size_t at) {
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, sizeof value);
    return value;
  };
  std::size_t at = kFileHeaderBytes;
  while (at + 20 <= bytes.size() && bytes.compare(at, 4, std::string("NIR\0", 4)) == 0) {
    const std::uint64_t record_end = at + std::uint64_t{u32(at + 12)} + u32(at + 16);
    if (record_end > bytes.size() || record_end <= at) return;
    if (u32(at + 4) == kEndRecord) {
      std::filesystem::resize_file(path, record_end);
      return;
    }
    at = record_end;
  }
}

}  // namespace

RecordStats record_device(const LiveOptions& options, const std::filesystem::path& output, std::uint64_t frames,
                          const std::atomic<bool>& stop) {
  if (output.extension() != ".oni") throw Error("recording " + output.string() + " must have the .oni suffix");
  detail::DepthStream stream;
  stream.open_live(options);
  // Written beside the output, renamed when complete (the temporary keeps the .oni suffix).
  const std::filesystem::path partial =
      output.parent_path() / (".partial-" + std::to_string(::getpid()) + "-" + output.filename().string());
  std::uint64_t read = 0;
  DepthImage first_depth;
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
    // Counted by the sensor's frame index, so a frame we were too late to read
    // (the recorder still has it) counts too.
    std::optional<std::uint64_t> first_index;
    while (read < frames) {
      std::optional<Frame> frame = stream.wait_and_read(options.stall_timeout_ms, stop);
      if (!frame) break;
      if (!first_index) {
        first_index = frame->index;
        first_depth = std::move(*frame->depth);
      }
      read = frame->index - *first_index + 1;
    }
    // OpenNI2 hands a frame to the recorder just after waking readers: give
    // it the last frame before stopping (the next is a frame period away).
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    recorder.stop();
    recorder.destroy();
  }
  std::error_code ignored;
  if (read < frames && !stop.load()) {
    std::filesystem::remove(partial, ignored);
    const std::string after = " after " + std::to_string(read) + " of " + std::to_string(frames) + " frames";
    if (stream.lost()) throw Error("device " + stream.uri() + " disconnected" + after);
    throw Error("device " + stream.uri() + " stopped sending frames" + after);
  }
  trim_recorder_padding(partial);
  // The file must hold what we saw: every frame from the first one we read.
  RecordStats stats;
  stats.mode = stream.mode();
  bool starts_with_first_frame = false;
  {
    const auto replay = open_recording(partial);
    const std::optional<Frame> first_recorded = replay->next();
    stats.frames = replay->frame_count().value_or(0);
    starts_with_first_frame = first_recorded && same_depth(*first_recorded->depth, first_depth);
  }
  if (!starts_with_first_frame || stats.frames < read) {
    std::filesystem::remove(partial, ignored);
    throw Error("openni::Recorder missed frames of " + stream.uri() + " (" + std::to_string(stats.frames) + " of " +
                std::to_string(read) + " recorded); " + output.string() + " not written");
  }
  std::filesystem::rename(partial, output, ignored);
  if (ignored) {
    std::filesystem::remove(partial, ignored);
    throw Error("cannot write " + output.string());
  }
  return stats;
}

}  // namespace lccp
