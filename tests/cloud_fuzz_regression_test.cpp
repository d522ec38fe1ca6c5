// 100 deterministic mutations (bit flips, truncations, header edits, splices)
// of small clouds in every input format, each run through the release
// `lccp segment`: no signal, exit 0 or 1 within 30 s, and on exit 1 exactly
// one "lccp: error: " line and no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "cli_runner.hpp"
#include "test_files.hpp"
#include "lccp/io/cloud_io.hpp"

namespace lccp {
namespace {

using test::RunResult;
namespace fs = std::filesystem;

const fs::path kData = LCCP_TEST_DATA_DIR;

// std::mt19937's output sequence is fixed by the C++ standard, so the
// mutations are the same everywhere (distributions are not, so none is used).
class Dice {
 public:
  explicit Dice(std::uint32_t seed) : engine_(seed) {}
  std::size_t below(std::size_t n) { return n == 0 ? 0 : engine_() % n; }

 private:
  std::mt19937 engine_;
};

std::string as_text(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

// An organized w x h window of an organized cloud, labels kept.
LabelledCloud crop(const LabelledCloud& in, std::uint32_t x0, std::uint32_t y0, std::uint32_t w, std::uint32_t h) {
  LabelledCloud out;
  out.cloud.width = w;
  out.cloud.height = h;
  out.labels.emplace();
  for (std::uint32_t y = y0; y < y0 + h; ++y) {
    for (std::uint32_t x = x0; x < x0 + w; ++x) {
      const std::size_t i = std::size_t{y} * in.cloud.width + x;
      out.cloud.points.push_back(in.cloud.points[i]);
      out.cloud.colors.push_back(in.cloud.colors[i]);
      out.labels->push_back((*in.labels)[i]);
    }
  }
  return out;
}

// A small greedy LZF compressor (format as in PCL's io/src/lzf.cpp): literal
// runs of <= 32 bytes, back references of 3..264 bytes up to 8192 back.
std::string lzf_compress(const std::string& in) {
  std::string out, literal;
  std::unordered_map<std::uint32_t, std::size_t> last;  // 3 bytes -> their last position
  const auto flush = [&] {
    if (literal.empty()) return;
    out += static_cast<char>(literal.size() - 1);
    out += literal;
    literal.clear();
  };
  for (std::size_t i = 0; i < in.size();) {
    std::size_t length = 0, distance = 0;
    if (i + 3 <= in.size()) {
      const auto byte = [&](std::size_t k) { return std::uint32_t{static_cast<std::uint8_t>(in[k])}; };
      const std::uint32_t key = byte(i) | byte(i + 1) << 8 | byte(i + 2) << 16;
      if (const auto found = last.find(key); found != last.end() && i - found->second <= 8192) {
        distance = i - found->second;
        while (length < 264 && i + length < in.size() && in[i + length] == in[i + length - distance]) ++length;
      }
      last[key] = i;
    }
    if (length < 3) {
      literal += in[i++];
      if (literal.size() == 32) flush();
      continue;
    }
    flush();
    const std::size_t l = length - 2, o = distance - 1;
    out += static_cast<char>(std::min<std::size_t>(l, 7) << 5 | o >> 8);
    if (l >= 7) out += static_cast<char>(l - 7);
    out += static_cast<char>(o & 0xff);
    i += length;
  }
  flush();
  return out;
}

template <typename T>
std::string raw(T value, bool big_endian = false) {
  std::string bytes(reinterpret_cast<const char*>(&value), sizeof value);
  if (big_endian) std::reverse(bytes.begin(), bytes.end());
  return bytes;
}

std::string pcd_header(const LabelledCloud& in, const std::string& data) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z rgb label\nSIZE 4 4 4 4 4\n"
         "TYPE F F F U U\nCOUNT 1 1 1 1 1\nWIDTH " + std::to_string(in.cloud.width) + "\nHEIGHT " +
         std::to_string(in.cloud.height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(in.cloud.size()) +
         "\nDATA " + data + "\n";
}

std::string ascii_pcd(const LabelledCloud& in) {
  std::string text = pcd_header(in, "ascii");
  for (std::size_t i = 0; i < in.cloud.size(); ++i) {
    for (int k = 0; k < 3; ++k) text += std::to_string(in.cloud.points[i][k]) + " ";
    text += std::to_string(in.cloud.colors[i]) + " " + std::to_string((*in.labels)[i]) + "\n";
  }
  return text;
}

std::string compressed_pcd(const LabelledCloud& in) {
  std::string planes;
  for (int k = 0; k < 3; ++k)
    for (const Eigen::Vector3f& p : in.cloud.points) planes += raw(p[k]);
  for (const std::uint32_t c : in.cloud.colors) planes += raw(c);
  for (const std::uint32_t l : *in.labels) planes += raw(l);
  const std::string lzf = lzf_compress(planes);
  return pcd_header(in, "binary_compressed") + raw(static_cast<std::uint32_t>(lzf.size())) +
         raw(static_cast<std::uint32_t>(planes.size())) + lzf;
}

// PLY with a face element (triangles over the grid) before the vertices.
std::string make_ply(const LabelledCloud& in, const std::string& format) {
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  const auto put = [&](auto value) { return ascii ? std::to_string(+value) + " " : raw(value, big); };
  const std::size_t faces = 20;
  std::string text = "ply\nformat " + format + " 1.0\ncomment cloud_fuzz_regression_test\nelement face " +
                     std::to_string(faces) + "\nproperty list uchar int vertex_indices\nelement vertex " +
                     std::to_string(in.cloud.size()) + "\nproperty float x\nproperty float y\nproperty float z\n"
                     "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uint label\nend_header\n";
  for (std::size_t f = 0; f < faces; ++f) {
    const auto k = static_cast<std::int32_t>(f);
    text += put(std::uint8_t{3}) + put(k) + put(k + 1) + put(k + static_cast<std::int32_t>(in.cloud.width));
    if (ascii) text += "\n";
  }
  for (std::size_t i = 0; i < in.cloud.size(); ++i) {
    const std::uint32_t c = in.cloud.colors[i];
    for (int k = 0; k < 3; ++k) text += put(in.cloud.points[i][k]);
    text += put(std::uint8_t(c >> 16)) + put(std::uint8_t(c >> 8)) + put(std::uint8_t(c)) + put((*in.labels)[i]);
    if (ascii) text += "\n";
  }
  return text;
}

struct Base {
  std::string name;  // with the extension lccp dispatches on
  std::string bytes;
};

std::vector<Base> make_bases() {
  const LabelledCloud scene = crop(read_cloud(kData / "mosd_test2.pcd"), 300, 200, 40, 30);
  std::vector<Base> bases = {
      {"binary.pcd", as_text(encode_labelled_pcd(scene.cloud, *scene.labels))},
      {"ascii.pcd", ascii_pcd(scene)},
      {"compressed.pcd", compressed_pcd(scene)},
      {"ascii.ply", make_ply(scene, "ascii")},
      {"le.ply", make_ply(scene, "binary_little_endian")},
      {"be.ply", make_ply(scene, "binary_big_endian")},
  };
  for (const char* name : {"pcl_normals_compressed.pcd", "pcl_count5_binary.pcd", "pcl_normals_binary.ply"})
    bases.push_back({name, test::read_bytes(kData / "formats" / name)});
  return bases;
}

// The end of the header: after the DATA line or end_header.
std::size_t header_end(const std::string& bytes) {
  std::size_t at = bytes.find("end_header\n");
  if (at != std::string::npos) return at + 11;
  at = bytes.find("\nDATA ");
  return at == std::string::npos ? bytes.size() : std::min(bytes.find('\n', at + 1) + 1, bytes.size());
}

const std::vector<std::string> kNastyWords = {
    "0", "-1", "1", "3", "65536", "4294967295", "4294967296", "18446744073709551615", "99999999999999999999",
    "nan", "inf", "-0", "1e9", "200000000", "", "x", "_", "binary_compressed", "ascii", "list", "uchar", "vertex"};

// Replaces one word of one header line.
std::string edit_header_word(std::string bytes, Dice& dice, std::string& what) {
  const std::size_t end = header_end(bytes);
  std::size_t start = dice.below(end);
  start = bytes.rfind('\n', start) == std::string::npos ? 0 : bytes.rfind('\n', start) + 1;
  const std::size_t line_end = std::min(bytes.find('\n', start), bytes.size());
  std::vector<std::size_t> words;
  for (std::size_t k = start; k < line_end; ++k)
    if (bytes[k] != ' ' && (k == start || bytes[k - 1] == ' ')) words.push_back(k);
  if (words.empty()) return bytes;
  const std::size_t word = words[dice.below(words.size())];
  const std::size_t length = std::min(bytes.find(' ', word), line_end) - word;
  const std::string& nasty = kNastyWords[dice.below(kNastyWords.size())];
  what = "header word '" + bytes.substr(word, length) + "' -> '" + nasty + "'";
  return bytes.replace(word, length, nasty);
}

std::string splice(std::string bytes, Dice& dice, std::string& what) {
  const std::size_t end = header_end(bytes);
  switch (dice.below(3)) {
    case 0: {  // keywords inside the data section
      const std::size_t at = end + dice.below(bytes.size() - end + 1);
      what = "keywords inserted at " + std::to_string(at);
      return bytes.insert(at, "\nCOLUMNS a b c\nPOINTS 4000000000\nDATA ascii\nelement vertex 9\n");
    }
    case 1: {  // a header line duplicated
      const std::size_t at = bytes.find('\n', dice.below(end));
      if (at == std::string::npos || at >= end) return bytes;
      const std::size_t next = std::min(bytes.find('\n', at + 1), end - 1);
      what = "header line duplicated at " + std::to_string(at);
      return bytes.insert(at + 1, bytes.substr(at + 1, next - at));
    }
    default: {  // a size-like word in the first data bytes
      const std::size_t at = end + dice.below(std::min<std::size_t>(16, bytes.size() - end));
      const std::uint32_t values[] = {0, 1, 0x7FFFFFFF, 0xFFFFFFFF, 2400000000u};
      const std::uint32_t value = values[dice.below(5)];
      what = "uint32 " + std::to_string(value) + " written at " + std::to_string(at);
      const std::string word = raw(value);
      return bytes.replace(at, std::min<std::size_t>(4, bytes.size() - at), word);
    }
  }
}

std::string mutate(const std::string& base, std::size_t kind, Dice& dice, std::string& what) {
  std::string bytes = base;
  if (kind == 0) {
    const std::size_t flips = 1 + dice.below(4);
    const bool header = dice.below(2) == 0;
    what = std::to_string(flips) + " bit flips in the " + (header ? "header" : "file");
    for (std::size_t k = 0; k < flips; ++k) bytes[dice.below(header ? header_end(bytes) : bytes.size())] ^= static_cast<char>(1 << dice.below(8));
    return bytes;
  }
  if (kind == 1) {
    const std::size_t size = dice.below(bytes.size());
    what = "cut to " + std::to_string(size) + " bytes";
    return bytes.substr(0, size);
  }
  return kind == 2 ? edit_header_word(bytes, dice, what) : splice(bytes, dice, what);
}

class IoFuzzRegression : public test::LccpBinaryTest {
 protected:
  IoFuzzRegression() : LccpBinaryTest("lccp_fuzz_regression") {}
};

TEST_F(IoFuzzRegression, HundredMutatedCloudsNeverCrashTheBinary) {
  const std::vector<Base> bases = make_bases();
  for (const Base& base : bases) {  // every base is a valid cloud to begin with
    const std::vector<std::uint8_t> bytes(base.bytes.begin(), base.bytes.end());
    const bool ply = base.name.ends_with(".ply");
    EXPECT_NO_THROW(ply ? parse_ply(bytes, base.name) : parse_pcd(bytes, base.name)) << base.name;
  }
  Dice dice(20261201);
  int failures = 0, successes = 0;
  for (std::size_t i = 0; i < 100; ++i) {
    const Base& base = bases[i % bases.size()];
    std::string what;
    const std::string bytes = mutate(base.bytes, (i / bases.size()) % 4, dice, what);
    std::string stem = "m";  // built up: GCC 12 warns (-Wrestrict) on "m" + std::to_string(i)
    stem += std::to_string(i);
    const fs::path input = work_ / (stem + "_" + base.name);
    const fs::path output = work_ / (stem + "_out.pcd");
    test::write_bytes(input, bytes);
    SCOPED_TRACE("mutation " + std::to_string(i) + " of " + base.name + ": " + what);
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run({"segment", input.string(), "-o", output.string(), "--threads", "1"}, 30);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.signal, 0) << test::describe(r);
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << test::describe(r);
    EXPECT_LT(seconds, 30.0);
    if (r.exit_code == 1) {
      ++failures;
      EXPECT_EQ(r.err.rfind("lccp: error: ", 0), 0u) << test::describe(r);
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << test::describe(r);
      EXPECT_FALSE(fs::exists(output)) << test::describe(r);
    } else if (r.exit_code == 0) {
      ++successes;
      EXPECT_TRUE(fs::exists(output)) << test::describe(r);
    }
    fs::remove(input);
    fs::remove(output);
    EXPECT_TRUE(test::list_dir(work_).empty()) << "files left behind";
  }
  EXPECT_GT(failures, 20);  // the mutations do reach the readers' checks
  std::printf("[          ] %d mutations rejected with one line, %d segmented\n", failures, successes);
}

}  // namespace
}  // namespace lccp
