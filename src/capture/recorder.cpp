// `lccp record`: a device's depth stream into an .oni file with openni::Recorder.
#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <optional>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <OpenNI.h>

#include "depth_stream.hpp"
#include "lccp/capture/openni_sources.hpp"
#include "lccp/capture/openni_session.hpp"
#include "lccp/error.hpp"

namespace lccp {
namespace {

// The frames an .oni file holds (0 if it cannot be opened).
std::uint64_t frames_in_recording(const std::filesystem::path& path) {
  openni::Device device;
  if (device.open(path.c_str()) != openni::STATUS_OK) return 0;
  openni::VideoStream stream;
  std::uint64_t frames = 0;
  if (stream.create(device, openni::SENSOR_DEPTH) == openni::STATUS_OK) {
    frames = static_cast<std::uint64_t>(std::max(0, device.getPlaybackControl()->getNumberOfFrames(stream)));
    stream.destroy();
  }
  device.close();
  return frames;
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
  {
    openni::Recorder recorder;
    if (recorder.create(partial.c_str()) != openni::STATUS_OK) {
      throw Error("cannot create " + output.string() + ": " + openni_error());
    }
    recorder.attach(stream.stream(), /*allowLossyCompression=*/false);
    recorder.start();
    stream.start();
    // Counted by the sensor's frame index, so a frame we were too late to read
    // (the recorder still has it) counts too.
    std::optional<std::uint64_t> first_index;
    while (read < frames) {
      const std::optional<Frame> frame = stream.wait_and_read(options.stall_timeout_ms, stop);
      if (!frame) break;
      if (!first_index) first_index = frame->index;
      read = frame->index - *first_index + 1;
    }
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
  RecordStats stats;
  stats.mode = stream.mode();
  trim_recorder_padding(partial);
  stats.frames = frames_in_recording(partial);
  std::filesystem::rename(partial, output, ignored);
  if (ignored) {
    std::filesystem::remove(partial, ignored);
    throw Error("cannot write " + output.string());
  }
  return stats;
}

}  // namespace lccp
