#pragma once
// OpenNI2's own file player on an .oni recording, in manual playback (each frame
// on request, none dropped): the reference our reader (src/capture/oni_reader.*)
// is held to in tests/oni_check_test.cpp and timed against in perf/bench_oni_read.cpp.
#include <filesystem>
#include <optional>

#include <OpenNI.h>

#include "../src/capture/depth_stream.hpp"
#include "lccp/error.hpp"
#include "lccp/frame.hpp"

namespace lccp::test {

class OpenNI2Player {
 public:
  explicit OpenNI2Player(const std::filesystem::path& path) {
    stream_.open_device(path.string(), "OpenNI2 cannot open " + path.string());
    openni::PlaybackControl* playback = stream_.device().getPlaybackControl();
    if (playback == nullptr) throw Error("OpenNI2 does not play " + path.string());
    playback->setRepeatEnabled(false);
    playback->setSpeed(-1.0f);
    stream_.open_depth_stream();
    frames_ = playback->getNumberOfFrames(stream_.stream());
    stream_.start();
  }
  int frames() const { return frames_; }
  // The next frame, or nullopt if none comes within 30 s.
  std::optional<Frame> next() { return stream_.wait_and_read(30000, {}); }

 private:
  detail::DepthStream stream_;
  int frames_ = 0;
};

}  // namespace lccp::test
