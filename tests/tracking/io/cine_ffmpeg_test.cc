// The .cine writer and reader against a reader this project did not write: FFmpeg's Phantom
// Cine demuxer (libavformat/cinedec.c, Debian's `ffmpeg` package). The round trips in
// cine_test.cc pass whenever the writer and the reader share a misreading of the format (a
// field at the wrong offset, the row order, the bit order of packed pixels); a camera's file
// would then be read wrong. FFmpeg's demuxer was written from the same public description by
// someone else and has read real cameras' files for years: what it reads from our files must be
// what we wrote, header values and pixels alike.
//
// FFmpeg scales pixels of RealBPP < 16 bits up to 16 (the value shifted left, its top bits
// repeated below), so a pixel written as v must come back as v << (16 - bpp) | ...: compared
// here as (ffmpeg's value >> (16 - bpp)) == v, and the low bits as the replication.
// Without ffmpeg on the PATH the tests skip, except under CI (the environment variable CI set),
// where `./dimerlab.sh setup` installs it and a skip would hide a lost check.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "tests/common/test_tmpdir.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/cine_source.h"
#include "tracking/io/cine_writer.h"
#include "tracking/io/mosaic_grey.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

bool HaveFfmpeg() {
  return std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") ==
         0;
}

#define REQUIRE_FFMPEG()                                                              \
  do {                                                                                \
    if (!HaveFfmpeg()) {                                                              \
      if (std::getenv("CI")) FAIL() << "ffmpeg/ffprobe not on the PATH under CI";     \
      GTEST_SKIP() << "ffmpeg/ffprobe not on the PATH (Debian package ffmpeg)";       \
    }                                                                                 \
  } while (0)

std::string Capture(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

// ffprobe's key=value lines for the first video stream (tags as TAG:name).
std::map<std::string, std::string> Probe(const std::string& path) {
  const std::string text = Capture("ffprobe -v error -select_streams v:0 -show_streams "
                                   "-of default=noprint_wrappers=1 '" + path + "'");
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return kv;
}

// Every frame decoded by ffmpeg to raw pixels of `pix_fmt` (gray, gray16le, a Bayer format,
// bgr24, ...), concatenated; empty when ffmpeg fails.
std::string DecodeRaw(const std::string& path, const std::string& pix_fmt,
                      const std::string& raw_path) {
  const std::string cmd = "ffmpeg -nostdin -v error -y -i '" + path + "' -f rawvideo -pix_fmt " +
                          pix_fmt + " '" + raw_path + "'";
  if (std::system(cmd.c_str()) != 0) return {};
  std::ifstream in(raw_path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<cv::Mat> FramesWithRampAndExtremes(int n, int w, int h, int type, int max_value,
                                               uint64_t seed) {
  // Random pixels, plus the extremes 0 and max in the first row's first two pixels, and a
  // top-bottom ramp in the first column so that a flipped image cannot match by chance.
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < n; ++i) {
    cv::Mat m(h, w, type);
    rng.fill(m, cv::RNG::UNIFORM, 0, max_value + 1);
    for (int r = 0; r < h; ++r) {
      const double v = double(max_value) * r / (h - 1);
      if (type == CV_8U) m.at<uint8_t>(r, 0) = uint8_t(v);
      else m.at<uint16_t>(r, 0) = uint16_t(v);
    }
    if (type == CV_8U) { m.at<uint8_t>(0, 1) = 0; m.at<uint8_t>(0, 2) = uint8_t(max_value); }
    else { m.at<uint16_t>(0, 1) = 0; m.at<uint16_t>(0, 2) = uint16_t(max_value); }
    frames.push_back(m);
  }
  return frames;
}

struct Case {
  const char* name;
  CinePixels pixels;
  uint32_t real_bpp;
};

class CineAgainstFfmpeg : public ::testing::TestWithParam<Case> {};

TEST_P(CineAgainstFfmpeg, HeaderAndPixelsReadAsWritten) {
  REQUIRE_FFMPEG();
  const Case c = GetParam();
  TempDir dir;
  const std::string path = dir / "film.cine";
  const int w = 36, h = 20, n = 7;  // w*h a multiple of 4 (10-bit packing)
  const bool eight = c.pixels == CinePixels::k8Bit;
  const int max_value = (1 << c.real_bpp) - 1;
  const auto frames =
      FramesWithRampAndExtremes(n, w, h, eight ? CV_8U : CV_16U, max_value, 1234 + c.real_bpp);
  CineWriteOptions o;
  o.pixels = c.pixels;
  o.real_bpp = c.real_bpp;
  o.frame_rate = 2000;
  o.exposure_ns = 300000;
  WriteCine(path, frames, o);

  auto kv = Probe(path);
  ASSERT_FALSE(kv.empty()) << "ffprobe could not read " << path;
  EXPECT_EQ(kv["width"], std::to_string(w));
  EXPECT_EQ(kv["height"], std::to_string(h));
  EXPECT_EQ(kv["pix_fmt"], eight ? "gray" : "gray16le");
  EXPECT_EQ(kv["r_frame_rate"], "2000/1");
  EXPECT_EQ(kv["duration_ts"], std::to_string(n));
  EXPECT_EQ(kv["TAG:shutter_ns"], "300000");

  const std::string raw = DecodeRaw(path, eight ? "gray" : "gray16le", dir / "film.raw");
  const size_t bytes_per_frame = size_t(w) * h * (eight ? 1 : 2);
  ASSERT_EQ(raw.size(), bytes_per_frame * n) << "ffmpeg decoded a different number of frames";
  int mismatches = 0, low_bits_wrong = 0;
  for (int i = 0; i < n; ++i) {
    const uint8_t* f = reinterpret_cast<const uint8_t*>(raw.data()) + i * bytes_per_frame;
    for (int r = 0; r < h; ++r) {
      for (int col = 0; col < w; ++col) {
        const size_t k = size_t(r) * w + col;
        if (eight) {
          mismatches += f[k] != frames[i].at<uint8_t>(r, col);
          continue;
        }
        const unsigned v16 = unsigned(f[2 * k]) | unsigned(f[2 * k + 1]) << 8;
        const unsigned v = frames[i].at<uint16_t>(r, col);
        const int shift = 16 - int(c.real_bpp);
        mismatches += (v16 >> shift) != v;
        // The bits below: the value's top bits repeated (FFmpeg's scaling to full range).
        low_bits_wrong += shift > 0 && (v16 & ((1u << shift) - 1)) != (v >> (c.real_bpp - shift));
      }
    }
  }
  EXPECT_EQ(mismatches, 0) << "pixels ffmpeg reads differently from what was written";
  EXPECT_EQ(low_bits_wrong, 0);

  // And our reader agrees with the same file (it did in cine_test.cc; here on these frames).
  auto src = OpenFrameSource(path);
  ASSERT_EQ(src->size(), size_t(n));
  for (int i = 0; i < n; ++i) {
    const Frame fr = src->Read(size_t(i));
    ASSERT_TRUE(fr.error.empty()) << fr.error;
    EXPECT_EQ(cv::norm(fr.image, frames[i], cv::NORM_INF), 0) << "frame " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Pixels, CineAgainstFfmpeg,
                         ::testing::Values(Case{"gray8", CinePixels::k8Bit, 8},
                                           Case{"gray16", CinePixels::k16Bit, 16},
                                           Case{"gray12_in_16", CinePixels::k16Bit, 12},
                                           Case{"packed10", CinePixels::k10BitPacked, 10}),
                         [](const ::testing::TestParamInfo<Case>& tp) {
                           return std::string(tp.param.name);
                         });

// A colour camera's files: the raw Bayer mosaic (Compression 2) and interpolated colour (24 and
// 48 bits). FFmpeg must read back the pixels written, in the pixel format it names for them
// (a Bayer format for the mosaic, BGR for colour), decoded without conversion; and our grey
// frame must be the grey of what FFmpeg read (the mosaic filter of mosaic_grey.h, OpenCV's
// BGR2GRAY). Full-range values: FFmpeg's scaling of fewer bits is checked above.
struct ColourCase {
  const char* name;
  CinePixels pixels;
  int channels;
  const char* pix_fmt_prefix;  // what ffprobe must call the pixels
};

class CineColourAgainstFfmpeg : public ::testing::TestWithParam<ColourCase> {};

TEST_P(CineColourAgainstFfmpeg, PixelsReadAsWrittenAndGreyOfThem) {
  REQUIRE_FFMPEG();
  const ColourCase c = GetParam();
  TempDir dir;
  const std::string path = dir / "colour.cine";
  const int w = 18, h = 10, n = 3;
  const bool eight = c.pixels == CinePixels::k8Bit;
  const int depth = eight ? CV_8U : CV_16U;
  std::vector<cv::Mat> frames;
  for (const cv::Mat& g : FramesWithRampAndExtremes(n * c.channels, w, h, depth,
                                                    eight ? 255 : 65535, 77)) {
    frames.push_back(g);
  }
  if (c.channels == 3) {  // three planes merged into BGR frames
    std::vector<cv::Mat> merged;
    for (int i = 0; i < n; ++i) {
      cv::Mat bgr;
      cv::merge(std::vector<cv::Mat>{frames[3 * i], frames[3 * i + 1], frames[3 * i + 2]}, bgr);
      merged.push_back(bgr);
    }
    frames = merged;
  }
  CineWriteOptions o;
  o.pixels = c.pixels;
  o.channels = c.channels;
  o.cfa = 3;  // CFA_BAYER
  WriteCine(path, frames, o);

  auto kv = Probe(path);
  ASSERT_FALSE(kv.empty()) << "ffprobe could not read " << path;
  const std::string fmt = kv["pix_fmt"];
  EXPECT_EQ(fmt.rfind(c.pix_fmt_prefix, 0), 0u) << fmt;
  const std::string raw = DecodeRaw(path, fmt, dir / "colour.raw");
  const size_t frame_bytes = frames[0].total() * frames[0].elemSize();
  ASSERT_EQ(raw.size(), frame_bytes * n) << "ffmpeg decoded a different number of frames";

  auto src = OpenFrameSource(path);
  ASSERT_EQ(src->size(), size_t(n));
  for (int i = 0; i < n; ++i) {
    const cv::Mat ffmpeg(h, w, frames[i].type(), const_cast<char*>(raw.data()) + i * frame_bytes);
    EXPECT_EQ(cv::norm(ffmpeg, frames[i], cv::NORM_INF), 0)
        << "frame " << i << " as ffmpeg reads it";
    cv::Mat grey;
    if (c.channels == 3) {
      cv::cvtColor(ffmpeg, grey, cv::COLOR_BGR2GRAY);
    } else {
      // The reader balances every frame by its first frame's phases.
      const cv::Mat first(h, w, frames[0].type(), const_cast<char*>(raw.data()));
      grey = MosaicToGrey(ffmpeg, EstimateMosaicBalance(first, eight ? 255 : 65535));
    }
    const Frame fr = src->Read(size_t(i));
    ASSERT_TRUE(fr.error.empty()) << fr.error;
    EXPECT_EQ(cv::norm(fr.image, grey, cv::NORM_INF), 0) << "frame " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Colour, CineColourAgainstFfmpeg,
                         ::testing::Values(ColourCase{"bayer8", CinePixels::k8Bit, 1, "bayer_"},
                                           ColourCase{"bayer16", CinePixels::k16Bit, 1, "bayer_"},
                                           ColourCase{"bgr24", CinePixels::k8Bit, 3, "bgr24"},
                                           ColourCase{"bgr48", CinePixels::k16Bit, 3, "bgr48"}),
                         [](const ::testing::TestParamInfo<ColourCase>& tp) {
                           return std::string(tp.param.name);
                         });

}  // namespace
}  // namespace dimer::tracking
