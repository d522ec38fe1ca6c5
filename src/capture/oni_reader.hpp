#pragma once
// Reads the depth frames of an .oni recording ourselves, in order, on the
// caller's thread: the whole file is checked first (check_oni_file), then each
// frame's record is read from the file and decoded when it is asked for.
//
// Why not OpenNI2's file player: its thread walks its stream list without a
// lock while destroying a stream removes and deletes one from that list
// (PlayerDevice::MainLoop and PlayerDevice::destroyStream, Source/Drivers/OniFile/
// PlayerDevice.cpp in OpenNI2's public source), so closing a replay could
// SIGSEGV on a loaded machine, and no order of OpenNI2 calls avoids it. Our
// reader has no thread; its pixels, timestamps and fields of view equal the
// player's on every frame of the bundled recordings (tests/oni_check_test.cpp).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "lccp/frame.hpp"
#include "oni_check.hpp"  // OniRecordingFacts

namespace lccp::detail {

class OniReader {
 public:
  // Throws lccp::Error naming the file when it cannot be read or check_oni_file refuses it.
  explicit OniReader(const std::filesystem::path& path);

  std::uint64_t frame_count() const { return facts_.frames; }

  // Frame `number` (from 0): depth in millimetres, the recorded timestamp and the
  // stream's fields of view; Frame::index = number. Throws lccp::Error naming the
  // file and the frame when its bytes are no longer what was checked (the file
  // was cut or rewritten since).
  Frame read(std::uint64_t number);

 private:
  std::filesystem::path path_;
  OniRecordingFacts facts_;
  std::ifstream file_;
  std::vector<std::uint8_t> payload_;  // reused from frame to frame
};

}  // namespace lccp::detail
