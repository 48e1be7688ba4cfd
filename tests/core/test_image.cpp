// Image loading and sampling: pixel centres at integers, bilinear inside
// [0, W-1] x [0, H-1], nothing outside.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "meshnbv/error.h"
#include "meshnbv/image.h"
#include "test_util.h"

using namespace meshnbv;

namespace {
Image gradient(int w, int h) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = std::uint8_t(10 * x);
      p[1] = std::uint8_t(20 * y);
      p[2] = std::uint8_t(5 * (x + y));
    }
  return img;
}
}  // namespace

TEST(Image, LuminanceWeights) {
  Image img(1, 1, 3);
  img.pixel(0, 0)[0] = 255;
  EXPECT_NEAR(img.luminance(0, 0), 0.299, 1e-6);
  img.pixel(0, 0)[0] = 0;
  img.pixel(0, 0)[1] = 255;
  EXPECT_NEAR(img.luminance(0, 0), 0.587, 1e-6);
  Image grey(1, 1, 1);
  grey.pixel(0, 0)[0] = 51;
  EXPECT_NEAR(grey.luminance(0, 0), 0.2, 1e-6);
}

TEST(Image, BilinearAtCentresBetweenAndBorders) {
  const Image img = gradient(8, 6);
  float v = -1, rgb[3];
  ASSERT_TRUE(img.sample_luminance(3, 2, &v));
  EXPECT_NEAR(v, img.luminance(3, 2), 1e-6);
  // Channel values are linear in x and y, so bilinear interpolation is exact.
  ASSERT_TRUE(img.sample_rgb(2.25, 4.5, rgb));
  EXPECT_NEAR(rgb[0] * 255, 22.5, 1e-3);
  EXPECT_NEAR(rgb[1] * 255, 90.0, 1e-3);
  EXPECT_NEAR(rgb[2] * 255, 5 * 6.75, 1e-3);
  // Last column and row are inside and exact.
  ASSERT_TRUE(img.sample_rgb(7, 5, rgb));
  EXPECT_NEAR(rgb[0] * 255, 70, 1e-3);
  EXPECT_NEAR(rgb[1] * 255, 100, 1e-3);
  ASSERT_TRUE(img.sample_luminance(0, 0, &v));
  // Outside [0, W-1] x [0, H-1], and NaN: false, output untouched.
  v = -1;
  EXPECT_FALSE(img.sample_luminance(-0.01, 2, &v));
  EXPECT_FALSE(img.sample_luminance(7.01, 2, &v));
  EXPECT_FALSE(img.sample_luminance(2, 5.5, &v));
  EXPECT_FALSE(img.sample_luminance(NAN, 2, &v));
  EXPECT_EQ(v, -1);
}

TEST(Image, SaveLoadRoundTripPngTiffAndGrey) {
  const std::string dir = test::temp_dir("image_io");
  const Image img = gradient(13, 7);
  for (const char* name : {"a.png", "a.tif"}) {
    img.save(dir + "/" + name);
    const Image back = Image::load(dir + "/" + name);
    ASSERT_EQ(back.width(), 13);
    ASSERT_EQ(back.channels(), 3);
    EXPECT_EQ(std::vector<std::uint8_t>(back.data(), back.data() + back.bytes()),
              std::vector<std::uint8_t>(img.data(), img.data() + img.bytes()))
        << name;
  }
  // RGB order survives (OpenCV is BGR inside).
  EXPECT_EQ(Image::load(dir + "/a.png").pixel(3, 0)[0], 30);
  // JPEG is lossy: only close.
  img.save(dir + "/a.jpg");
  EXPECT_NEAR(Image::load(dir + "/a.jpg").pixel(6, 3)[1], 60, 12);
  Image grey(5, 4, 1);
  grey.pixel(2, 1)[0] = 200;
  grey.save(dir + "/g.png");
  const Image g = Image::load(dir + "/g.png");
  EXPECT_EQ(g.channels(), 1);
  EXPECT_EQ(g.pixel(2, 1)[0], 200);
}

TEST(Image, SixteenBitIsScaled) {
  const std::string dir = test::temp_dir("image_16");
  cv::Mat m(2, 2, CV_16UC1, cv::Scalar(65535));
  m.at<std::uint16_t>(0, 1) = 257 * 100;
  cv::imwrite(dir + "/d.png", m);
  const Image img = Image::load(dir + "/d.png");
  EXPECT_EQ(img.pixel(0, 0)[0], 255);
  EXPECT_EQ(img.pixel(1, 0)[0], 100);
}

TEST(Image, MissingAndUndecodableFiles) {
  const std::string dir = test::temp_dir("image_bad");
  MESHNBV_EXPECT_ERROR_CONTAINS(Image::load(dir + "/nope.png"), "not found");
  std::ofstream(dir + "/broken.png") << "\x89PNG\r\n\x1a\n this is not a png";
  MESHNBV_EXPECT_ERROR_CONTAINS(Image::load(dir + "/broken.png"), "does not decode");
}

TEST(ImageCache, BoundedLruAndSharedOwnership) {
  const std::string dir = test::temp_dir("image_cache");
  const Image img = gradient(100, 100);  // 30,000 bytes each
  for (int i = 0; i < 5; ++i) img.save(dir + "/" + std::to_string(i) + ".png");
  ImageCache cache(70000);  // room for two
  auto first = cache.get(dir + "/0.png");
  cache.get(dir + "/1.png");
  cache.get(dir + "/2.png");  // evicts 0
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_LE(cache.bytes_held(), 70000u);
  EXPECT_EQ(first->width(), 100);  // still valid: the caller holds it
  cache.get(dir + "/2.png");
  EXPECT_EQ(cache.loads(), 3u);  // a hit costs no decode
  cache.get(dir + "/0.png");
  EXPECT_EQ(cache.loads(), 4u);  // evicted, so decoded again
  MESHNBV_EXPECT_ERROR_CONTAINS(cache.get(dir + "/missing.png"), "not found");
}

TEST(ImageCache, ManyThreads) {
  const std::string dir = test::temp_dir("image_cache_threads");
  const Image img = gradient(50, 40);
  for (int i = 0; i < 6; ++i) img.save(dir + "/" + std::to_string(i) + ".png");
  ImageCache cache(3 * img.bytes());
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < 60; ++k) {
        auto im = cache.get(dir + "/" + std::to_string((k + t) % 6) + ".png");
        if (im->width() != 50) ++failures;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_LE(cache.bytes_held(), 3 * img.bytes());
}
