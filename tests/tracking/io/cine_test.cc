// The .cine reader against the writer (round trips for every pixel format, header values read
// back exactly) and against broken files: truncated, corrupt headers, random bytes. Every
// failure must be a clean InputError or a per-frame reason, never a crash or a read outside the
// file (run this test in the sanitizer build).
#include "tracking/io/frame_source.h"
#include "tracking/io/cine_source.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"
#include "tracking/io/cine_layout.h"
#include "tracking/io/cine_writer.h"
#include "tracking/io/mosaic_grey.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

std::vector<cv::Mat> RandomFrames(int n, int w, int h, int type, int max_value, uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < n; ++i) {
    cv::Mat m(h, w, type);
    rng.fill(m, cv::RNG::UNIFORM, 0, max_value + 1);
    frames.push_back(m);
  }
  return frames;
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

CineWriteOptions Recording(CinePixels p) {
  CineWriteOptions o;
  o.pixels = p;
  o.frame_rate = 12345;
  o.exposure_ns = 41234;
  o.trigger_seconds = 1700000123u;
  o.trigger_fraction = 0x89ABCDEFu;
  o.first_image_no = -5;
  return o;
}

void ExpectRoundTrip(const std::string& path, const std::vector<cv::Mat>& frames,
                     const CineWriteOptions& o, int real_bpp) {
  WriteCine(path, frames, o);
  auto src = OpenFrameSource(path);
  ASSERT_EQ(src->size(), frames.size());
  EXPECT_TRUE(src->random_access());
  for (size_t i = 0; i < frames.size(); ++i) {
    const Frame f = src->Read(i);
    ASSERT_TRUE(f.error.empty()) << f.error;
    EXPECT_EQ(f.index, i);
    EXPECT_EQ(f.name, std::filesystem::path(path).filename().string() + "#" + std::to_string(i));
    EXPECT_TRUE(Same(f.image, frames[i])) << "frame " << i;
  }
  const RecordingInfo r = src->recording();
  EXPECT_TRUE(r.known);
  EXPECT_EQ(r.fps, 12345.0);
  EXPECT_EQ(r.exposure_ns, 41234);
  EXPECT_EQ(r.trigger_seconds, 1700000123);
  EXPECT_EQ(r.trigger_fraction, int64_t(0x89ABCDEFu));
  EXPECT_EQ(r.first_image_no, -5);
  EXPECT_EQ(r.real_bpp, real_bpp);
}

TEST(Cine, RoundTrip8BitOddWidth) {
  TempDir dir;
  ExpectRoundTrip(dir / "a.cine", RandomFrames(3, 37, 11, CV_8UC1, 255, 1),
                  Recording(CinePixels::k8Bit), 8);
}

TEST(Cine, RoundTrip16BitTwelveBitCamera) {
  TempDir dir;
  CineWriteOptions o = Recording(CinePixels::k16Bit);
  o.real_bpp = 12;
  ExpectRoundTrip(dir / "b.cine", RandomFrames(3, 33, 9, CV_16UC1, 4095, 2), o, 12);
}

TEST(Cine, RoundTrip16BitFullRange) {
  TempDir dir;
  ExpectRoundTrip(dir / "c.cine", RandomFrames(2, 16, 5, CV_16UC1, 65535, 3),
                  Recording(CinePixels::k16Bit), 16);
}

TEST(Cine, RoundTrip10BitPackedIncludingExtremes) {
  TempDir dir;
  auto frames = RandomFrames(3, 40, 7, CV_16UC1, 1023, 4);
  frames[0].at<uint16_t>(0, 0) = 1023;
  frames[0].at<uint16_t>(0, 1) = 0;
  frames[0].at<uint16_t>(6, 39) = 1023;
  ExpectRoundTrip(dir / "d.cine", frames, Recording(CinePixels::k10BitPacked), 10);
}

TEST(Cine, RoundTripTopDownRowsAndLongAnnotations) {
  TempDir dir;
  CineWriteOptions o = Recording(CinePixels::k8Bit);
  o.top_down = true;
  o.annotation_size = 48;
  ExpectRoundTrip(dir / "e.cine", RandomFrames(2, 20, 6, CV_8UC1, 255, 5), o, 8);
}

TEST(Cine, UppercaseExtensionOpens) {
  TempDir dir;
  ExpectRoundTrip(dir / "F.CINE", RandomFrames(1, 8, 4, CV_8UC1, 255, 6),
                  Recording(CinePixels::k8Bit), 8);
}

// A colour camera's raw mosaic (Compression 2, a CFA code): the pixels are read as grey ones
// are and made grey by the layout-free filter; the header says what they were.
TEST(Cine, RawColourMosaicIsReadGrey) {
  TempDir dir;
  struct Case {
    CinePixels pixels;
    int type, max_value, real_bpp;
  };
  for (const Case c : {Case{CinePixels::k8Bit, CV_8UC1, 255, 8},
                       Case{CinePixels::k16Bit, CV_16UC1, 4095, 12},
                       Case{CinePixels::k10BitPacked, CV_16UC1, 1023, 10}}) {
    CineWriteOptions o = Recording(c.pixels);
    o.cfa = 3;
    if (c.pixels == CinePixels::k16Bit) o.real_bpp = 12;
    const auto frames = RandomFrames(2, 40, 24, c.type, c.max_value, 21 + c.real_bpp);
    const std::string path = dir / ("raw" + std::to_string(c.real_bpp) + ".cine");
    WriteCine(path, frames, o);
    auto src = OpenFrameSource(path);
    ASSERT_EQ(src->size(), frames.size());
    // The balance is the first frame's, for every frame.
    const MosaicBalance balance = EstimateMosaicBalance(frames[0], c.max_value);
    EXPECT_TRUE(balance.found());
    for (size_t i = 0; i < frames.size(); ++i) {
      const Frame f = src->Read(i);
      ASSERT_TRUE(f.error.empty()) << f.error;
      EXPECT_TRUE(Same(f.image, MosaicToGrey(frames[i], balance))) << path << " frame " << i;
    }
    EXPECT_NE(src->recording().mosaic_balance.find("cells)"), std::string::npos);
    EXPECT_EQ(src->recording().colour, "mosaic");
    EXPECT_EQ(src->recording().cfa, 3);
    EXPECT_EQ(src->recording().real_bpp, c.real_bpp);
  }
}

// Interpolated colour (24 or 48 bits a pixel, BGR): grey as OpenCV makes colour image files
// grey; odd widths (rows not a multiple of 4 bytes), both row orders.
TEST(Cine, InterpolatedColourIsReadGrey) {
  TempDir dir;
  for (const bool sixteen : {false, true}) {
    for (const bool top_down : {false, true}) {
      CineWriteOptions o = Recording(sixteen ? CinePixels::k16Bit : CinePixels::k8Bit);
      o.channels = 3;
      o.cfa = 3;
      o.top_down = top_down;
      const auto frames = RandomFrames(2, 13, 7, sixteen ? CV_16UC3 : CV_8UC3,
                                       sixteen ? 65535 : 255, 30 + sixteen + 2 * top_down);
      const std::string path = dir / ("bgr" + std::to_string(sixteen) +
                                      std::to_string(top_down) + ".cine");
      WriteCine(path, frames, o);
      auto src = OpenFrameSource(path);
      ASSERT_EQ(src->size(), frames.size());
      for (size_t i = 0; i < frames.size(); ++i) {
        const Frame f = src->Read(i);
        ASSERT_TRUE(f.error.empty()) << f.error;
        cv::Mat grey;
        cv::cvtColor(frames[i], grey, cv::COLOR_BGR2GRAY);
        EXPECT_TRUE(Same(f.image, grey)) << path << " frame " << i;
      }
      EXPECT_EQ(src->recording().colour, "bgr");
      EXPECT_EQ(src->recording().real_bpp, sixteen ? 16 : 8);
    }
  }
}

// The packing order of the public description, worked by hand: the 40 bits of 4 pixels are
// one big-endian bit stream.
TEST(Cine, Pack10BitOrder) {
  const uint16_t px[4] = {0x3FF, 0x000, 0x155, 0x2AA};
  uint8_t bytes[5];
  Pack10(px, 4, bytes);
  EXPECT_EQ(bytes[0], 0xFF);
  EXPECT_EQ(bytes[1], 0xC0);
  EXPECT_EQ(bytes[2], 0x05);
  EXPECT_EQ(bytes[3], 0x56);
  EXPECT_EQ(bytes[4], 0xAA);
  uint16_t back[4];
  Unpack10(bytes, 4, back);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(back[k], px[k]);
}

std::vector<uint8_t> Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void Put(const std::string& path, const std::vector<uint8_t>& b) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
}
uint64_t Le(const std::vector<uint8_t>& b, size_t at, int n) {
  uint64_t v = 0;
  for (int k = 0; k < n; ++k) v |= uint64_t(b[at + k]) << (8 * k);
  return v;
}
void SetLe(std::vector<uint8_t>* b, size_t at, uint64_t v, int n) {
  for (int k = 0; k < n; ++k) (*b)[at + k] = uint8_t(v >> (8 * k));
}

// Checked against the file's bytes, not through the reader: biHeight > 0 stores the bottom row
// first; the annotation block's last word is ImageSize.
TEST(Cine, FileStoresBottomRowFirst) {
  TempDir dir;
  cv::Mat m(6, 8, CV_8UC1);
  for (int r = 0; r < 6; ++r) m.row(r).setTo(10 + r);
  WriteCine(dir / "g.cine", {m}, Recording(CinePixels::k8Bit));
  const auto b = Bytes(dir / "g.cine");
  const size_t table = Le(b, cine::kHOffImageOffsets, 4);
  const size_t image = Le(b, table, 8);
  const size_t annotation = Le(b, image, 4);
  EXPECT_EQ(Le(b, image + annotation - 4, 4), 48u);  // ImageSize
  EXPECT_EQ(b[image + annotation], 15);              // row 5 first
  EXPECT_EQ(b[image + annotation + 47], 10);         // row 0 last
  EXPECT_GT(int32_t(Le(b, cine::kHOffImageHeader, 4) + 0), 0);
  EXPECT_EQ(int32_t(Le(b, Le(b, cine::kHOffImageHeader, 4) + cine::kBHeight, 4)), 6);
}

TEST(Cine, TruncatedImageIsReportedPerFrame) {
  TempDir dir;
  const auto frames = RandomFrames(4, 16, 8, CV_8UC1, 255, 7);
  WriteCine(dir / "t.cine", frames, Recording(CinePixels::k8Bit));
  std::filesystem::resize_file(dir / "t.cine", std::filesystem::file_size(dir / "t.cine") - 60);
  auto src = OpenFrameSource(dir / "t.cine");
  ASSERT_EQ(src->size(), 4u);
  for (size_t i = 0; i < 3; ++i) EXPECT_TRUE(Same(src->Read(i).image, frames[i])) << i;
  const Frame last = src->Read(3);
  EXPECT_TRUE(last.image.empty());
  EXPECT_EQ(last.name, "t.cine#3");
  EXPECT_NE(last.error.find("past the end of the file"), std::string::npos) << last.error;
  EXPECT_NE(last.error.find("68 of 128 bytes present"), std::string::npos) << last.error;
}

TEST(Cine, TruncatedOffsetTableIsReportedPerFrame) {
  TempDir dir;
  WriteCine(dir / "u.cine", RandomFrames(4, 16, 8, CV_8UC1, 255, 8), Recording(CinePixels::k8Bit));
  const auto b = Bytes(dir / "u.cine");
  const size_t table = Le(b, cine::kHOffImageOffsets, 4);
  std::filesystem::resize_file(dir / "u.cine", table + 2 * 8 + 3);  // 2 entries and a bit
  auto src = OpenFrameSource(dir / "u.cine");
  ASSERT_EQ(src->size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const Frame f = src->Read(i);
    EXPECT_TRUE(f.image.empty());
    EXPECT_NE(f.error.find(i < 2 ? "image offset" : "offset table entry"), std::string::npos)
        << i << ": " << f.error;
  }
}

TEST(Cine, CorruptAnnotationSizeIsReportedPerFrame) {
  TempDir dir;
  const auto frames = RandomFrames(2, 16, 8, CV_8UC1, 255, 9);
  WriteCine(dir / "v.cine", frames, Recording(CinePixels::k8Bit));
  auto b = Bytes(dir / "v.cine");
  const size_t table = Le(b, cine::kHOffImageOffsets, 4);
  SetLe(&b, Le(b, table, 8), 3, 4);               // AnnotationSize 3 < 8
  SetLe(&b, table + 8, uint64_t(1) << 62, 8);     // frame 1 offset far outside the file
  Put(dir / "v.cine", b);
  auto src = OpenFrameSource(dir / "v.cine");
  EXPECT_NE(src->Read(0).error.find("corrupt annotation block"), std::string::npos);
  EXPECT_NE(src->Read(1).error.find("past the end of the file"), std::string::npos);
}

void ExpectNotCine(const std::string& path, const std::string& why) {
  try {
    OpenFrameSource(path);
    FAIL() << "opened " << path;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": not a Phantom .cine file (", 0), 0u) << msg;
    EXPECT_NE(msg.find(why), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(Cine, CorruptHeadersAreNotCine) {
  TempDir dir;
  WriteCine(dir / "ok.cine", RandomFrames(2, 16, 8, CV_8UC1, 255, 10),
            Recording(CinePixels::k8Bit));
  const auto good = Bytes(dir / "ok.cine");
  const size_t bitmap = Le(good, cine::kHOffImageHeader, 4), setup = Le(good, cine::kHOffSetup, 4);
  auto broken = [&](const std::string& name, size_t at, uint64_t v, int n) {
    auto b = good;
    SetLe(&b, at, v, n);
    Put(dir / name, b);
    return dir / name;
  };
  ExpectNotCine(broken("magic.cine", 0, 'X', 1), "no \"CI\" signature");
  ExpectNotCine(broken("width.cine", bitmap + cine::kBWidth, 0, 4), "absurd image size 0x8");
  ExpectNotCine(broken("height.cine", bitmap + cine::kBHeight, 1u << 30, 4), "absurd image size");
  ExpectNotCine(broken("count.cine", cine::kHImageCount, 0xFFFFFFFFu, 4), "absurd image count");
  ExpectNotCine(broken("setup.cine", setup + cine::kSMark, 0, 2), "no \"ST\" setup marker");
  ExpectNotCine(broken("offsetup.cine", cine::kHOffSetup, 0xFFFFFF00u, 4), "setup offset");
  ExpectNotCine(broken("offbmp.cine", cine::kHOffImageHeader, good.size() - 10, 4),
                "image header offset");
  Put(dir / "empty.cine", {});
  ExpectNotCine(dir / "empty.cine", "0 bytes");
  Put(dir / "short.cine", {'C', 'I', 44, 0});
  ExpectNotCine(dir / "short.cine", "shorter than the 44-byte file header");
}

TEST(Cine, UnsupportedPixelFormatsAreOneLineInputErrors) {
  TempDir dir;
  WriteCine(dir / "ok.cine", RandomFrames(1, 16, 8, CV_8UC1, 255, 11),
            Recording(CinePixels::k8Bit));
  const auto good = Bytes(dir / "ok.cine");
  auto expect_refused = [&](const std::string& name, size_t at, uint64_t v, int n,
                            const std::string& why) {
    auto b = good;
    SetLe(&b, at, v, n);
    Put(dir / name, b);
    try {
      OpenFrameSource(dir / name);
      FAIL() << name;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(dir / name, 0), 0u) << msg;
      EXPECT_NE(msg.find(why), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  };
  const size_t bitmap = Le(good, cine::kHOffImageHeader, 4);
  expect_refused("rgba.cine", bitmap + cine::kBBitCount, 32, 2, "32-bit pixels");
  expect_refused("jpeg.cine", cine::kHCompression, cine::kCompressionJpeg, 2, "JPEG-compressed");
  expect_refused("future.cine", cine::kHCompression, 7, 2, "Compression 7");
}

// Random bytes, with and without a valid-looking start: never a crash or an out-of-file read
// (the sanitizer build checks the latter); either a clean InputError or frames with reasons.
TEST(Cine, RandomGarbageNeverCrashes) {
  TempDir dir;
  WriteCine(dir / "ok.cine", RandomFrames(3, 16, 8, CV_8UC1, 255, 12),
            Recording(CinePixels::k8Bit));
  const auto good = Bytes(dir / "ok.cine");
  std::mt19937_64 rng(42);
  int not_cine = 0, opened = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> b;
    if (trial % 3 == 0) {  // pure garbage
      b.resize(rng() % 20000);
      for (auto& x : b) x = uint8_t(rng());
    } else {  // a real file with random bytes overwritten, some truncated
      b = good;
      for (int k = 0; k < 1 + int(rng() % 20); ++k) b[rng() % b.size()] = uint8_t(rng());
      if (trial % 3 == 2) b.resize(rng() % b.size());
    }
    Put(dir / "g.cine", b);
    try {
      auto src = OpenFrameSource(dir / "g.cine");
      ++opened;
      for (size_t i = 0; i < std::min<size_t>(src->size(), 8); ++i) {
        const Frame f = src->Read(i);
        EXPECT_NE(f.image.empty(), f.error.empty());
      }
    } catch (const InputError& e) {
      ++not_cine;
      EXPECT_NE(std::string(e.what()).find("g.cine: "), std::string::npos);
    }
  }
  EXPECT_GE(not_cine, 100);  // every pure-garbage file at least
  EXPECT_GT(opened, 10);     // and many damaged real files still open
}

TEST(Cine, ConcurrentReadsGiveTheSameFrames) {
  TempDir dir;
  const auto frames = RandomFrames(40, 64, 32, CV_16UC1, 1023, 13);
  WriteCine(dir / "p.cine", frames, Recording(CinePixels::k10BitPacked));
  auto src = OpenFrameSource(dir / "p.cine");
  std::vector<int> ok(2, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      for (int rep = 0; rep < 5; ++rep) {
        for (size_t i = t; i < frames.size(); i += 1) ok[t] += Same(src->Read(i).image, frames[i]);
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(ok[0], 200);
  EXPECT_EQ(ok[1], 195);
}

}  // namespace
}  // namespace dimer::tracking
