// The .cine reader's cross-checks of the header's redundant fields: a field that disagrees
// with another refuses the whole file in one line naming it; a frame whose own fields disagree
// (ImageSize, its table entry, the room before the next frame) is skipped with its reason and
// the rest of the film is read.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"
#include "tracking/io/cine_layout.h"
#include "tracking/io/cine_source.h"
#include "tracking/io/cine_writer.h"

namespace dimer::tracking {
namespace {

using dimer::testing::TempDir;

std::vector<cv::Mat> Ramp(int n, int w, int h) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < n; ++i) {
    cv::Mat m(h, w, CV_8U);
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) m.at<uint8_t>(r, c) = uint8_t(7 * i + 3 * r + c);
    }
    frames.push_back(m);
  }
  return frames;
}

std::vector<uint8_t> Load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void Save(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              std::streamsize(bytes.size()));
}
template <typename T>
T Get(const std::vector<uint8_t>& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}
template <typename T>
void Put(std::vector<uint8_t>* b, size_t at, T v) {
  std::memcpy(b->data() + at, &v, sizeof v);
}

// Offsets of the parts of a file the writer made.
struct Layout {
  uint32_t bitmap, setup, table;
  std::vector<int64_t> images;
};
Layout LayoutOf(const std::vector<uint8_t>& b) {
  Layout l{Get<uint32_t>(b, cine::kHOffImageHeader), Get<uint32_t>(b, cine::kHOffSetup),
           Get<uint32_t>(b, cine::kHOffImageOffsets), {}};
  for (uint32_t i = 0; i < Get<uint32_t>(b, cine::kHImageCount); ++i) {
    l.images.push_back(Get<int64_t>(b, l.table + 8 * i));
  }
  return l;
}

// The message of the InputError opening `path` gives, or "".
std::string OpenError(const std::string& path) {
  try {
    OpenCine(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool OneLine(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

TEST(CineChecks, RedundantHeaderFieldsThatDisagreeRefuseTheFile) {
  TempDir dir;
  const std::string good = dir / "good.cine";
  WriteCine(good, Ramp(3, 16, 8), {});
  const std::vector<uint8_t> bytes = Load(good);
  const Layout l = LayoutOf(bytes);
  ASSERT_EQ(OpenError(good), "");

  std::vector<uint8_t> b = bytes;
  Put<uint32_t>(&b, l.bitmap + cine::kBSizeImage, 16 * 8 + 4);
  Save(dir / "size_image.cine", b);
  std::string e = OpenError(dir / "size_image.cine");
  EXPECT_TRUE(OneLine(e)) << e;
  EXPECT_EQ(e.rfind(dir / "size_image.cine" + ": corrupt .cine header: biSizeImage 132", 0), 0u)
      << e;

  b = bytes;
  Put<uint16_t>(&b, l.setup + cine::kSImWidth, 17);
  Save(dir / "setup_width.cine", b);
  e = OpenError(dir / "setup_width.cine");
  EXPECT_TRUE(OneLine(e)) << e;
  EXPECT_NE(e.find("the setup's image size 17x8 is not the bitmap header's 16x8"),
            std::string::npos) << e;

  CineWriteOptions packed;
  packed.pixels = CinePixels::k10BitPacked;
  std::vector<cv::Mat> frames16;
  for (const cv::Mat& f : Ramp(2, 16, 8)) {
    cv::Mat m;
    f.convertTo(m, CV_16U);
    frames16.push_back(m);
  }
  WriteCine(dir / "packed.cine", frames16, packed);
  b = Load(dir / "packed.cine");
  ASSERT_EQ(OpenError(dir / "packed.cine"), "");
  Put<uint16_t>(&b, LayoutOf(b).bitmap + cine::kBBitCount, 8);
  Save(dir / "packed8.cine", b);
  e = OpenError(dir / "packed8.cine");
  EXPECT_TRUE(OneLine(e)) << e;
  EXPECT_NE(e.find("10-bit packed images with biBitCount 8"), std::string::npos) << e;
}

TEST(CineChecks, AChangedAnnotationSizeSkipsTheFramesInsteadOfShiftingTheirPixels) {
  TempDir dir;
  const std::string path = dir / "film.cine";
  WriteCine(path, Ramp(3, 16, 8), {});
  std::vector<uint8_t> b = Load(path);
  const Layout l = LayoutOf(b);
  for (int64_t at : l.images) Put<uint32_t>(&b, size_t(at), 12);  // 8 -> 12, no bytes added
  Save(path, b);
  auto src = OpenCine(path);
  for (size_t i = 0; i < 3; ++i) {
    const Frame f = src->Read(i);
    EXPECT_TRUE(f.image.empty());
    EXPECT_TRUE(OneLine(f.error));
    EXPECT_NE(f.error.find("is not the image's 128 bytes: corrupt annotation block"),
              std::string::npos) << f.error;
  }
}

TEST(CineChecks, ADuplicatedOffsetTableEntrySkipsTheFrameInsteadOfCopyingAnother) {
  TempDir dir;
  const std::string path = dir / "film.cine";
  const std::vector<cv::Mat> frames = Ramp(4, 16, 8);
  WriteCine(path, frames, {});
  std::vector<uint8_t> b = Load(path);
  const Layout l = LayoutOf(b);
  Put<int64_t>(&b, l.table + 8 * 2, l.images[1]);
  Save(path, b);
  auto src = OpenCine(path);
  const Frame f2 = src->Read(2);
  EXPECT_TRUE(f2.image.empty());
  EXPECT_NE(f2.error.find("does not follow frame 1's"), std::string::npos) << f2.error;
  EXPECT_NE(f2.error.find("corrupt offset table"), std::string::npos) << f2.error;
  for (size_t i : {0u, 1u, 3u}) {
    const Frame f = src->Read(i);
    ASSERT_EQ(f.error, "") << i;
    EXPECT_EQ(cv::norm(f.image, frames[i], cv::NORM_INF), 0) << i;
  }
}

// A table entry that points 4 bytes early: the frame before it would overrun it. That frame is
// skipped; the one the entry points at still reads (its annotation block starts where it says).
TEST(CineChecks, AFrameThatOverrunsTheNextFramesOffsetIsSkipped) {
  TempDir dir;
  const std::string path = dir / "film.cine";
  const std::vector<cv::Mat> frames = Ramp(3, 16, 8);
  CineWriteOptions o;
  o.annotation_size = 16;
  WriteCine(path, frames, o);
  std::vector<uint8_t> b = Load(path);
  const Layout l = LayoutOf(b);
  Put<int64_t>(&b, l.table + 8, l.images[1] - 4);
  Put<uint32_t>(&b, size_t(l.images[1] - 4), 20);  // an annotation block 4 bytes longer
  Save(path, b);
  auto src = OpenCine(path);
  const Frame f0 = src->Read(0);
  EXPECT_TRUE(f0.image.empty());
  EXPECT_NE(f0.error.find("overrun the next frame's offset"), std::string::npos) << f0.error;
  for (size_t i : {1u, 2u}) {
    const Frame f = src->Read(i);
    ASSERT_EQ(f.error, "") << i;
    EXPECT_EQ(cv::norm(f.image, frames[i], cv::NORM_INF), 0) << i;
  }
}

TEST(CineChecks, BFlipVIsReportedAndTheRowsKeepBiHeightsOrder) {
  TempDir dir;
  const std::string path = dir / "film.cine";
  const std::vector<cv::Mat> frames = Ramp(1, 16, 8);
  WriteCine(path, frames, {});
  std::vector<uint8_t> b = Load(path);
  EXPECT_FALSE(OpenCine(path)->recording().flip_v);
  Put<int32_t>(&b, LayoutOf(b).setup + cine::kSFlipV, 1);
  Save(path, b);
  auto src = OpenCine(path);
  EXPECT_TRUE(src->recording().flip_v);
  EXPECT_EQ(cv::norm(src->Read(0).image, frames[0], cv::NORM_INF), 0);
}

}  // namespace
}  // namespace dimer::tracking
