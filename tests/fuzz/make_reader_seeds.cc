// Writes the seed corpora of the file readers' fuzz targets (corpus/cine, bmp_decode,
// tiff_decode, lens) with the project's own writers: a few small valid files of each kind the
// readers take. Built in build-fuzz; run once from the repository's root when a reader learns a
// new kind of file:  build-fuzz/tests/fuzz/make_reader_seeds tests/fuzz/corpus
#include <opencv2/core.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "tracking/io/cine_writer.h"
#include "tracking/io/image_codecs.h"

namespace {

using namespace dimer::tracking;

cv::Mat Ramp(int w, int h, int type, int step) {
  cv::Mat m(h, w, type);
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const int v = (r * w + c) * step;
      if (type == CV_8U) m.at<uint8_t>(r, c) = uint8_t(v);
      if (type == CV_16U) m.at<uint16_t>(r, c) = uint16_t(v);
      if (type == CV_8UC3) m.at<cv::Vec3b>(r, c) = cv::Vec3b(uint8_t(v), uint8_t(2 * v), 9);
    }
  }
  return m;
}

// A grey 8-bit BMP as cameras write it: 256-entry grey palette, rows padded to 4 bytes.
void WriteGreyBmp(const std::string& path, const cv::Mat& m, bool top_down) {
  const int stride = (m.cols + 3) / 4 * 4;
  const uint32_t offset = 14 + 40 + 1024, size = offset + uint32_t(stride * m.rows);
  std::vector<uint8_t> b(size, 0);
  auto put = [&](size_t at, uint32_t v, int n) {
    for (int k = 0; k < n; ++k) b[at + k] = uint8_t(v >> (8 * k));
  };
  b[0] = 'B';
  b[1] = 'M';
  put(2, size, 4);
  put(10, offset, 4);
  put(14, 40, 4);
  put(18, uint32_t(m.cols), 4);
  put(22, uint32_t(top_down ? -m.rows : m.rows), 4);
  put(26, 1, 2);
  put(28, 8, 2);
  put(34, uint32_t(stride * m.rows), 4);
  put(46, 256, 4);
  for (int i = 0; i < 256; ++i) put(54 + 4 * i, uint32_t(i * 0x010101), 4);
  for (int r = 0; r < m.rows; ++r) {
    const int row = top_down ? r : m.rows - 1 - r;
    for (int c = 0; c < m.cols; ++c) b[offset + size_t(row * stride + c)] = m.at<uint8_t>(r, c);
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), size);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  CineWriteOptions o8;
  WriteCine(dir + "/cine/grey8.cine", {Ramp(8, 4, CV_8U, 3), Ramp(8, 4, CV_8U, 5)}, o8);
  CineWriteOptions o16;
  o16.pixels = CinePixels::k16Bit;
  o16.real_bpp = 12;
  o16.top_down = true;
  o16.annotation_size = 16;
  o16.frame_rate = 90000;
  o16.time_stamp_rate = 9000;
  WriteCine(dir + "/cine/grey16_time_stamps.cine",
            {Ramp(4, 4, CV_16U, 200), Ramp(4, 4, CV_16U, 100), Ramp(4, 4, CV_16U, 50)}, o16);
  CineWriteOptions o10;
  o10.pixels = CinePixels::k10BitPacked;
  WriteCine(dir + "/cine/packed10.cine", {Ramp(4, 4, CV_16U, 60), Ramp(4, 4, CV_16U, 30)}, o10);
  CineWriteOptions mosaic;
  mosaic.cfa = 3;
  WriteCine(dir + "/cine/mosaic8.cine", {Ramp(4, 4, CV_8U, 9)}, mosaic);
  CineWriteOptions bgr;
  bgr.channels = 3;
  WriteCine(dir + "/cine/bgr24.cine", {Ramp(4, 2, CV_8UC3, 11)}, bgr);

  WriteGreyBmp(dir + "/bmp_decode/grey_bottom_up.bmp", Ramp(5, 3, CV_8U, 7), false);
  WriteGreyBmp(dir + "/bmp_decode/grey_top_down.bmp", Ramp(8, 2, CV_8U, 13), true);

  const std::vector<int> plain = {cv::IMWRITE_TIFF_COMPRESSION, 1};
  dimer::tracking::codecs::Write(dir + "/tiff_decode/grey8.tif", Ramp(5, 3, CV_8U, 7), plain);
  dimer::tracking::codecs::Write(dir + "/tiff_decode/grey16.tif", Ramp(4, 4, CV_16U, 999), plain);

  std::ofstream(dir + "/lens/sample.yml")
      << "%YAML:1.0\n---\nimage_width: 320\nimage_height: 160\n"
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 1000., 0., 159.5, 0., 1000., 79.5, 0., 0., 1. ]\n"
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
         "   data: [ 0.3, 0., 0., 0., 0. ]\navg_reprojection_error: 0.25\n";
  std::ofstream(dir + "/lens/tutorial.xml")
      << "<?xml version=\"1.0\"?>\n<opencv_storage>\n"
         "<Camera_Matrix type_id=\"opencv-matrix\"><rows>3</rows><cols>3</cols><dt>d</dt>"
         "<data>800. 0. 320. 0. 810. 240. 0. 0. 1.</data></Camera_Matrix>\n"
         "<Distortion_Coefficients type_id=\"opencv-matrix\"><rows>4</rows><cols>1</cols>"
         "<dt>d</dt><data>-0.1 0.02 0.001 -0.002</data></Distortion_Coefficients>\n"
         "</opencv_storage>\n";
  return 0;
}
